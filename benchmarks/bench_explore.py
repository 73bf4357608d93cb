"""How live the explorer feels: the time from a control's change to the updated map in
the browser, and from a click on the map to its stroke, on a real server in Debian's
headless Chromium (Selenium through Debian's chromedriver).

Starts ``tennis-stroke explore`` on a free port, opens it, then ``--changes`` times sets
the racket mass ``M2`` to a new value (0.301, 0.302, ... kg) and reads, in the page, the
milliseconds from the change until the coarse map (121 x 101) and the full map
(241 x 201) are drawn (the frame after each arrives); then clicks ``--changes`` points
of the map and times until the page holds the clicked stroke.  Prints every time and
the medians (a click is timed from the mouse button's release in the page).  Run it
on a quiet machine: nothing else computing.

Usage::

    python benchmarks/bench_explore.py [--changes 20]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from chromium import CHROMIUM, DRIVER, POSITION_JS, chromium, wait_idle  # noqa: E402

SET_JS = """
const t = performance.now()
Bokeh.documents[0].get_model_by_name(arguments[0]).value = arguments[1]
return t
"""
MAPS_JS = "return window.__explore_maps || []"
#: Records when the mouse button is released (a click's time; Selenium's own action
#: takes about 0.3 s before it, not counted).
CLICKED_JS = """
window.addEventListener("pointerup", () => { window.__clicked = performance.now() }, true)
"""
STROKE_JS = """
const box = Bokeh.documents[0].get_model_by_name('explore-stroke-box').children[0]
const m = box.name ? Bokeh.documents[0].get_model_by_name(box.name + '-now') : null
return [m ? m.data.label[0] : null, performance.now()]
"""


def _wait(ready, seconds: float = 60.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        seen = ready()
        if seen is not None:
            return seen
        time.sleep(0.005)
    raise SystemExit("bench_explore: the page did not update within 60 s")


def _changes(driver, count: int) -> tuple[list[float], list[float]]:
    coarse, full = [], []
    for n in range(count):
        generation = 2 + n
        t0 = driver.execute_script(SET_JS, "model.M2", f"{0.301 + 0.001 * n:.3f}")

        def arrived(generation=generation):
            maps = driver.execute_script(MAPS_JS)
            got = {m["level"]: m["t"] for m in maps if m["generation"] == generation}
            return got if "full" in got else None

        got = _wait(arrived)
        coarse.append(got["coarse"] - t0)
        full.append(got["full"] - t0)
        time.sleep(0.5)  # let the claims of this setting finish: each change on a quiet server
    return coarse, full


def _clicks(driver, count: int) -> list[float]:
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    times = []
    for n in range(count):
        theta0, delta0 = 70.0 + 2.0 * n, 20.0 + 1.5 * n
        sx, sy = driver.execute_script(POSITION_JS, "explore-map", theta0, delta0)
        action = ActionBuilder(driver)
        action.pointer_action.move_to_location(int(round(sx)), int(round(sy))).click()
        action.perform()
        t0 = driver.execute_script("return window.__clicked")  # the button's release
        want = f"theta0 {theta0:g}, delta0 {delta0:g} deg"

        def shown(want=want):
            label, t = driver.execute_script(STROKE_JS)
            return t if label == want else None

        times.append(_wait(shown) - t0)
    return times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--changes", type=int, default=20)
    args = parser.parse_args(argv)
    if CHROMIUM is None or DRIVER is None:
        print("bench_explore: needs chromium and chromedriver", file=sys.stderr)
        return 2
    from tennis_stroke.live.address import free_port

    port = free_port("127.0.0.1")
    server = subprocess.Popen(
        [sys.executable, "-m", "tennis_stroke.cli", "explore", "--port", str(port)],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        text=True,
    )
    print(server.stdout.readline().strip())
    driver = chromium(1500, 1300, loopback=True)
    try:
        driver.get(f"http://127.0.0.1:{port}/")
        wait_idle(driver)
        time.sleep(3.0)  # the first session's full map and claims
        driver.execute_script(CLICKED_JS)
        coarse, full = _changes(driver, args.changes)
        strokes = _clicks(driver, args.changes)
    finally:
        driver.quit()
        server.terminate()
        server.communicate(timeout=30)
    for name, times in (
        ("coarse map 121 x 101", coarse),
        ("full map 241 x 201", full),
        ("clicked stroke", strokes),
    ):
        shown = " ".join(f"{t:.0f}" for t in times)
        print(f"{name}: median {statistics.median(times):.0f} ms (ms: {shown})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
