"""Debian's headless Chromium driven by Selenium through Debian's chromedriver (no
browser download), for the page tests and benchmarks: the driver, and the scripts that
find a Bokeh view's screen position, its tooltips and a table's rows."""

from __future__ import annotations

import shutil
import time

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
MISSING = "no chromium or chromedriver on PATH (.ci/run installs them)"

#: Every tooltip's text, through the shadow roots Bokeh draws them in.
TOOLTIP_JS = """
const out = [];
const walk = (node) => {
  if (node.shadowRoot) walk(node.shadowRoot);
  for (const c of node.children || []) walk(c);
  if (node.classList && node.classList.contains("bk-tooltip-content")) out.push(node.innerText);
};
walk(document.body);
return out.filter((t) => t.trim());
"""

#: The screen position of the data point (x, y) of the plot named arguments[0].
POSITION_JS = """
const plot = Bokeh.documents[0].get_model_by_name(arguments[0]);
const stack = [...Bokeh.index.roots];
while (stack.length) {
  const v = stack.pop();
  if (v.model === plot) {
    v.el.scrollIntoView({block: "center"});
    const r = v.el.getBoundingClientRect();
    return [r.left + v.frame.x_scale.compute(arguments[1]),
            r.top + v.frame.y_scale.compute(arguments[2])];
  }
  stack.push(...(v.child_views ?? []));
}
return null;
"""

#: The rendered rows of the data table named arguments[0]: each row's cell texts.
ROWS_JS = """
const table = Bokeh.documents[0].get_model_by_name(arguments[0]);
const stack = [...Bokeh.index.roots];
while (stack.length) {
  const v = stack.pop();
  if (v.model === table) {
    const root = v.shadow_el ?? v.el.shadowRoot ?? v.el;
    return [...root.querySelectorAll(".slick-row")].map(
      (r) => [...r.querySelectorAll(".slick-cell")].map((c) => c.innerText.trim()));
  }
  stack.push(...(v.child_views ?? []));
}
return null;
"""

#: Whether the page's Bokeh document is drawn and idle.
IDLE_JS = (
    "return typeof Bokeh !== 'undefined' && Bokeh.documents.length > 0"
    " && Bokeh.documents[0].is_idle"
)


def chromium(width: int = 1300, height: int = 1000, loopback: bool = False):
    """A headless Chromium with the network off: every request goes to a dead proxy (and
    logs an error), but with ``loopback`` those to this machine (a local server)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        f"--window-size={width},{height}",
    ):
        options.add_argument(arg)
    options.add_argument("--proxy-server=127.0.0.1:9")
    if not loopback:  # Chromium sends loopback requests past any proxy unless told so
        options.add_argument("--proxy-bypass-list=<-loopback>")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(DRIVER), options=options)


def wait_idle(driver, seconds: float = 30.0) -> None:
    """Wait until the page's views are drawn."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if driver.execute_script(IDLE_JS):
            return
        time.sleep(0.05)
    raise AssertionError(f"the views were not drawn within {seconds:g} s")


def hover_lines(driver, plot: str, x: float, y: float) -> dict[str, str]:
    """The tooltip of ``plot`` with the mouse on the data point (x, y), as label: value."""
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    sx, sy = driver.execute_script(POSITION_JS, plot, x, y)
    action = ActionBuilder(driver)
    action.pointer_action.move_to_location(int(round(sx)), int(round(sy)))
    action.perform()
    for _ in range(40):
        texts = driver.execute_script(TOOLTIP_JS)
        lines = [t for t in texts if "\t" in t or ":\n" in t]
        if lines:
            break
        time.sleep(0.05)
    pairs = [line.split(":", 1) for line in max(texts, key=len).split("\n") if ":" in line]
    return {k.strip(): v.strip() for k, v in pairs}
