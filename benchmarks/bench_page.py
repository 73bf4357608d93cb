"""How heavy the report page is for a reader: its size and the time until every view is
drawn, in Debian's headless Chromium (driven by Selenium through Debian's chromedriver),
the network off.

Each of ``--runs`` loads opens the page fresh (a blank page in between) and reads, in the
page, the milliseconds from the start of navigation until BokehJS reports its document
idle (every view drawn); it also counts console errors.  Prints the size, every load's
time and their median.

Usage::

    python benchmarks/bench_page.py [report/index.html] [--runs 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from chromium import CHROMIUM, DRIVER, chromium  # noqa: E402

IDLE_JS = """
const done = arguments[arguments.length - 1];
const poll = () => (typeof Bokeh !== "undefined" && Bokeh.documents.length > 0
                    && Bokeh.documents[0].is_idle)
    ? done(performance.now()) : setTimeout(poll, 10);
poll();
"""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("page", nargs="?", default="report/index.html")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args(argv)
    page = Path(args.page).resolve()
    if not page.is_file() or CHROMIUM is None or DRIVER is None:
        print(f"bench_page: needs {page} (make report), chromium and chromedriver", file=sys.stderr)
        return 2
    driver = chromium(1280, 1000)
    driver.set_script_timeout(60)
    times, errors = [], 0
    try:
        for _ in range(args.runs):
            driver.get("about:blank")
            time.sleep(0.2)
            driver.get(page.as_uri())
            times.append(driver.execute_async_script(IDLE_JS) / 1000.0)
            errors += sum(e["level"] == "SEVERE" for e in driver.get_log("browser"))
    finally:
        driver.quit()
    print(f"page: {page} ({page.stat().st_size / 1e6:.2f} MB)")
    print("drawn after (s): " + ", ".join(f"{t:.2f}" for t in times))
    print(f"median of {len(times)}: {statistics.median(times):.2f} s; console errors: {errors}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
