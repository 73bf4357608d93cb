"""What page loads alone cost the explorer: ``--loads`` concurrent ``GET /`` (no
websocket ever opens, as a crawler, a prefetch or a hostile page would), the wall time
until all are answered, how long a static file of the server waits meanwhile, and the
server's resident memory before, after the loads, and once its unused sessions were
dropped.

Starts ``tennis-stroke explore`` on a free port; run it on a quiet machine.

Usage::

    python benchmarks/bench_page_loads.py [--loads 100] [--settle 25]
"""

from __future__ import annotations

import argparse
import concurrent.futures
import re
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def rss_mb(pid: int) -> float:
    """Resident memory of process ``pid`` (MB)."""
    text = Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"VmRSS:\s+(\d+)", text).group(1)) / 1024


def get(url: str) -> tuple[int, float]:
    started = time.perf_counter()
    with urllib.request.urlopen(url, timeout=600) as response:
        response.read()
        return response.status, time.perf_counter() - started


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--loads", type=int, default=100, help="concurrent GET / (100)")
    parser.add_argument(
        "--settle", type=float, default=25.0, help="seconds to wait for unused sessions (25)"
    )
    args = parser.parse_args()
    log = tempfile.NamedTemporaryFile("w+", suffix=".log")  # a pipe left unread would fill
    server = subprocess.Popen(
        [sys.executable, "-m", "tennis_stroke.cli", "explore", "--threads", "1"],
        cwd=ROOT,
        stdout=log,
        stderr=subprocess.STDOUT,
        text=True,
    )
    try:
        url = None
        while url is None and server.poll() is None:
            time.sleep(0.2)
            found = re.search(r"(http://\S+/)", Path(log.name).read_text())
            url = found.group(1) if found else None
        if url is None:
            print("the explorer did not start", file=sys.stderr)
            return 1
        static = url + "static/js/bokeh.min.js"
        get(static)
        before = rss_mb(server.pid)
        with concurrent.futures.ThreadPoolExecutor(args.loads + 1) as pool:
            started = time.perf_counter()
            pages = [pool.submit(get, url) for _ in range(args.loads)]
            time.sleep(0.5)
            static_wait = pool.submit(get, static).result()[1]
            statuses = [p.result()[0] for p in pages]
            wall = time.perf_counter() - started
        after = rss_mb(server.pid)
        time.sleep(args.settle)
        settled = rss_mb(server.pid)
        print(
            f"{args.loads} concurrent GET /: all answered in {wall:.1f} s "
            f"(statuses {sorted(set(statuses))})"
        )
        print(f"a static file requested 0.5 s after them waited {static_wait:.2f} s")
        print(
            f"server memory: {before:.0f} MB before, {after:.0f} MB after the loads, "
            f"{settled:.0f} MB {args.settle:g} s later"
        )
    finally:
        server.terminate()
        server.wait(30)
    return 0


if __name__ == "__main__":
    sys.exit(main())
