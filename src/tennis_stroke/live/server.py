"""Serve the live explorer: a Bokeh server on 127.0.0.1 (another address only when asked,
with a warning), its websocket open only to pages of the served address, stopped by
SIGINT or SIGTERM with one line.  The compiled solver is loaded once, before the URL is
printed (the first stroke of the server), not per request."""

from __future__ import annotations

import signal
import sys
from collections.abc import Callable
from functools import partial
from pathlib import Path

from bokeh.application import Application
from bokeh.application.handlers.function import FunctionHandler
from bokeh.server.server import Server

from ..io.config_files import load_yaml
from ..pipeline.config_check import config_errors
from . import app
from .address import LOCALHOST, check_address, free_port, origins

#: Exit statuses after SIGINT and SIGTERM (128 + the signal, as a shell reports them).
EXIT = {signal.SIGINT: 130, signal.SIGTERM: 143}


def serve(
    root: Path,
    figure: str = "fig2",
    host: str = LOCALHOST,
    port: int | None = None,
    threads: int | None = None,
    say: Callable[[str], None] = print,
) -> int:
    """Serve the explorer of the project at ``root`` (its ``config/`` and the workflow's
    schema) until SIGINT or SIGTERM; returns the exit status (130 or 143).  An address
    it cannot listen at is one line (ValueError) before anything loads."""
    check_address(host, port)
    config = load_yaml(root / "config" / "config.yaml")
    schema = root / "workflow" / "schemas" / "config.schema.yaml"
    errors = config_errors(config, schema)  # as the workflow checks it: naming the key
    if errors:
        raise ValueError(f"{root / 'config' / 'config.yaml'}: {errors[0]}")
    shared = app.Shared.load(
        config,
        root / "config" / "claims.yaml",
        root / "config" / "readings.yaml",
        root / "config" / "scenarios.yaml",
        schema,
        figure,
        threads,
    )
    shared.paper_views()  # loads the compiled code; every session's first views
    port = port or free_port(host)
    unused = app.UNUSED_SESSION_SECONDS * 1000
    try:
        server = Server(
            Application(FunctionHandler(partial(app.make_document, shared))),
            address=host,
            port=port,
            allow_websocket_origin=origins(host, port),
            # a session whose page is gone, or never connected, is dropped this soon
            unused_session_lifetime_milliseconds=unused,
            check_unused_sessions_milliseconds=unused // 2,
        )
    except OSError as exc:  # taken since check_address looked
        raise ValueError(f"--port {port}: cannot listen on {host} ({exc.strerror})") from None
    server.start()
    if host != LOCALHOST:
        say(
            f"tennis-stroke explore: warning: serving on {host}: anyone who reaches this "
            "address can use the explorer and save scenarios into config/scenarios.yaml"
        )
    say(f"tennis-stroke explore: http://{host}:{port}/ (Ctrl-C stops)")
    received: list[int] = []

    def stop(signum: int) -> None:
        received.append(signum)
        shared.stopping.set()  # running work ends at its next block
        server.io_loop.stop()

    loop = server.io_loop.asyncio_loop
    for signum in EXIT:
        loop.add_signal_handler(signum, stop, signum)
    try:
        server.io_loop.start()
    finally:
        for signum in EXIT:
            loop.remove_signal_handler(signum)
        server.stop()
    signum = received[0] if received else signal.SIGINT
    say(f"tennis-stroke explore: stopped ({signal.Signals(signum).name})")
    sys.stdout.flush()
    return EXIT[signum]
