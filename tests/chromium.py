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

#: Every text a plot draws itself beside its glyphs (labels and legends: titles and axes
#: aside), with the box it is drawn in and the box it must lie in (a label: the plot's
#: frame, inside the axes; a legend: the canvas), in canvas pixels.
TEXTS_JS = """
const out = [];
const stack = [...Bokeh.index.roots];
while (stack.length) {
  const v = stack.pop();
  if (v.renderer_views && v.canvas) {
    const c = v.canvas.bbox;
    const canvas = {left: 0, right: c.width, top: 0, bottom: c.height};
    const f = v.frame.bbox;
    const frame = {left: f.left, right: f.right, top: f.top, bottom: f.bottom};
    for (const r of v.renderer_views.values()) {
      let box = null, texts = [], within = null;
      if (r._rect !== undefined && r.model.x_offset !== undefined) {  // a Label
        const {sx, sy, width, height, anchor} = r._rect;
        const left = sx - anchor.x * width, top = sy - anchor.y * height;
        box = {left, right: left + width, top, bottom: top + height};
        texts = [r.model.text];
        within = frame;  // a label beside a glyph: over an axis or a colour bar outside it
      } else if (r.model.items !== undefined && r.bbox !== undefined) {  // a Legend
        const b = r.bbox;
        box = {left: b.left, right: b.right, top: b.top, bottom: b.bottom};
        texts = r.model.items.map((i) => i.label?.value ?? String(i.label));
        within = canvas;  // a legend: beside the frame, inside the canvas
      }
      if (box) out.push({plot: v.model.name, texts, ...box, within});
    }
  }
  stack.push(...(v.child_views ?? []));
}
return out;
"""


def cut_texts(driver) -> list[dict]:
    """The labels and legends of the page's plots that run out of the box they must lie
    in (:data:`TEXTS_JS`): cut at the canvas's edge, or drawn over an axis."""
    return [
        t
        for t in driver.execute_script(TEXTS_JS)
        if t["left"] < t["within"]["left"] - 0.5
        or t["right"] > t["within"]["right"] + 0.5
        or t["top"] < t["within"]["top"] - 0.5
        or t["bottom"] > t["within"]["bottom"] + 0.5
    ]


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
