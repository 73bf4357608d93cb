"""a live explorer in the browser: change a parameter, see Figs. 2-3 and 9 and their claims
recomputed
"""

from __future__ import annotations

import argparse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--figure",
        choices=("fig2", "fig3", "fig9"),
        default="fig2",
        help="the map shown: Fig. 2 (L1 0.3 m) or Fig. 3 (0.4 m; also for fig9); default fig2",
    )
    parser.add_argument(
        "--port", type=int, default=None, help="the port (default: a free one, printed)"
    )
    parser.add_argument(
        "--host",
        default="127.0.0.1",
        help="the address to serve on (default 127.0.0.1, this machine only; another one "
        "exposes the explorer to whoever reaches it)",
    )
    parser.add_argument(
        "--threads", type=int, default=None, help="solver threads (default: every core)"
    )


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    if not Path("workflow/Snakefile").is_file() or not Path("config/config.yaml").is_file():
        raise ValueError(
            f"no workflow/Snakefile in {Path.cwd()}: run explore from the project's folder"
        )
    if args.port is not None and not 0 < args.port < 65536:
        raise ValueError(f"--port {args.port}: a port is 1 to 65535")
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads {args.threads}: at least 1")
    from ..live.address import check_address

    check_address(args.host, args.port)  # before the server's modules load (about 2 s)
    from ..live.server import serve

    return serve(Path.cwd(), args.figure, args.host, args.port, args.threads)
