"""The live explorer served for real (``tennis-stroke explore`` on a random port) and used
from headless Chromium: a control moved shows the solver's strokes at the new setting, a
clicked point plays its stroke, another origin's websocket is refused, and SIGINT or
SIGTERM stops the server with one line."""

import http.client
import shutil
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest
from chromium import CHROMIUM, DRIVER, MISSING, POSITION_JS, chromium, wait_idle
from conftest import ROOT

from tennis_stroke.io.config_files import load_yaml
from tennis_stroke.live import address, compute, controls
from tennis_stroke.live import server as server_module
from tennis_stroke.solver.stroke import strike_batch

EXPLORE = [sys.executable, "-m", "tennis_stroke.cli", "explore"]
browser_needed = pytest.mark.skipif(CHROMIUM is None or DRIVER is None, reason=MISSING)

#: The maps the page received since it opened (generation, level, time).
MAPS_JS = "return window.__explore_maps || []"
#: The label of the stroke the page plays (null before any).
STROKE_LABEL_JS = """
const box = Bokeh.documents[0].get_model_by_name("explore-stroke-box").children[0]
const m = box.name ? Bokeh.documents[0].get_model_by_name(box.name + "-now") : null
return m ? m.data.label[0] : null
"""
#: Set the control named arguments[0] to arguments[1], as a reader's entry does.
SET_JS = "Bokeh.documents[0].get_model_by_name(arguments[0]).value = arguments[1]"


def project(folder):
    """A copy of what the explorer reads of a checkout (a saved scenario stays there)."""
    (folder / "workflow" / "schemas").mkdir(parents=True)
    shutil.copytree(ROOT / "config", folder / "config")
    shutil.copy(ROOT / "workflow/schemas/config.schema.yaml", folder / "workflow/schemas")
    shutil.copy(ROOT / "workflow/Snakefile", folder / "workflow")
    return folder


def start(folder, *options):
    """The explorer started in ``folder``; returns the process and its URL."""
    from tennis_stroke.live.address import free_port

    port = free_port("127.0.0.1")
    proc = subprocess.Popen(
        [*EXPLORE, "--port", str(port), *options],
        cwd=folder,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline()
    assert line.strip() == f"tennis-stroke explore: http://127.0.0.1:{port}/ (Ctrl-C stops)", (
        line + proc.stderr.read()
    )
    return proc, port


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = project(tmp_path_factory.mktemp("explore"))
    proc, port = start(folder)
    yield folder, port
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=30)


@pytest.fixture(scope="module")
def browser():
    driver = chromium(1500, 1300, loopback=True)
    yield driver
    driver.quit()


def open_page(driver, port):
    driver.get(f"http://127.0.0.1:{port}/")
    wait_idle(driver)


def wait_map(driver, generation, level="full", seconds=60.0):
    """The page's maps once the map of ``generation`` at ``level`` has arrived."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        maps = driver.execute_script(MAPS_JS)
        if any(m["generation"] >= generation and m["level"] == level for m in maps):
            return maps
        time.sleep(0.05)
    raise AssertionError(f"no {level} map of generation {generation}: {maps}")


def page_map(driver) -> np.ndarray:
    """The values the page's map holds, as (theta0, delta0)."""
    rows = driver.execute_script(
        "const d = Bokeh.documents[0].get_model_by_name('explore-map-map').data;"
        "const im = d.image[0]; const [h, w] = im.shape;"
        "const out = []; for (let j = 0; j < h; j++)"
        " out.push(Array.from(im.slice(j * w, (j + 1) * w), (v) => Number.isNaN(v) ? null : v));"
        "return out"
    )
    return np.array(rows, dtype=float).T


@pytest.mark.browser
@browser_needed
def test_a_moved_control_shows_the_solver_s_strokes_at_the_new_setting(server, browser):
    folder, port = server
    open_page(browser, port)
    browser.execute_script(SET_JS, "model.M2", "0.35")
    maps = wait_map(browser, 2)  # the session's first request is the page's own (1)
    assert [m["level"] for m in maps if m["generation"] == 2] == ["coarse", "full"]
    shown = page_map(browser)
    config = load_yaml(folder / "config" / "config.yaml")
    theta, delta = compute.map_axes(config, "fig2", "full")
    expected = strike_batch(theta[:, None], delta[None, :], {"M2": 0.35, "L1": 0.3})
    assert shown.shape == (241, 201)
    np.testing.assert_array_equal(shown, expected["v_out_kmh"].astype(np.float32))
    before = strike_batch(theta[:, None], delta[None, :], {"M2": 0.3, "L1": 0.3})
    with pytest.raises(AssertionError):  # the check tells the settings apart
        np.testing.assert_array_equal(shown, before["v_out_kmh"].astype(np.float32))


@pytest.mark.browser
@browser_needed
def test_a_clicked_point_plays_its_stroke(server, browser):
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    _, port = server
    open_page(browser, port)
    sx, sy = browser.execute_script(POSITION_JS, "explore-map", 100.0, 30.0)
    action = ActionBuilder(browser)
    action.pointer_action.move_to_location(int(round(sx)), int(round(sy))).click()
    action.perform()
    end = time.monotonic() + 60
    label = None
    while time.monotonic() < end and label is None:
        label = browser.execute_script(STROKE_LABEL_JS)
        time.sleep(0.1)
    assert label == "theta0 100, delta0 30 deg"
    v_out = browser.execute_script(
        "return Bokeh.documents[0].get_model_by_name('explore-stroke-readout').text"
    )
    assert v_out.startswith("t = 0.0000 s")


def websocket_status(port, origin) -> int:
    """The status of a websocket handshake to the explorer with ``origin``."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    conn.request(
        "GET",
        "/ws",
        headers={
            "Origin": origin,
            "Upgrade": "websocket",
            "Connection": "Upgrade",
            "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ==",
            "Sec-WebSocket-Version": "13",
        },
    )
    status = conn.getresponse().status
    conn.close()
    return status


@pytest.mark.process
def test_a_websocket_from_another_origin_is_refused(server):
    _, port = server
    assert websocket_status(port, "http://evil.example") == 403
    assert websocket_status(port, f"http://localhost:{port + 1}") == 403
    assert websocket_status(port, f"http://127.0.0.1:{port}") != 403


@pytest.mark.signals
@pytest.mark.parametrize(
    ("signum", "code", "name"), [(signal.SIGINT, 130, "SIGINT"), (signal.SIGTERM, 143, "SIGTERM")]
)
def test_a_signal_stops_the_server_with_one_line(tmp_path, signum, code, name):
    proc, port = start(project(tmp_path))
    assert websocket_status(port, "http://evil.example") == 403  # serving
    proc.send_signal(signum)
    out, err = proc.communicate(timeout=60)  # a guard against a hang, not a timing
    assert proc.returncode == code
    assert out == f"tennis-stroke explore: stopped ({name})\n"
    assert "Traceback" not in err


@pytest.mark.process
@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--port", "70000"], "--port 70000: a port is 1 to 65535"),
        (["--threads", "0"], "--threads 0: at least 1"),
        (["--figure", "fig5"], "invalid choice: 'fig5'"),
    ],
)
def test_a_bad_option_is_one_line(tmp_path, options, message):
    done = subprocess.run(
        [*EXPLORE, *options], cwd=project(tmp_path), capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 2 and message in done.stderr
    assert len(done.stderr.strip().splitlines()) <= 2, done.stderr  # usage and the error


#: The explore command, reporting at exit the compiled groups it had loaded
#: (``solver.compiled._done``) to the file named by its first argument: what "before the
#: compiled code loads" means, on a machine of any speed.
EXPLORE_LOADED = [
    sys.executable,
    "-c",
    "import atexit, runpy, sys; out = sys.argv.pop(1); atexit.register(lambda: open(out, 'w')"
    ".write(' '.join(sorted(getattr(sys.modules.get('tennis_stroke.solver.compiled'), "
    "'_done', ()))))); sys.argv[0] = 'tennis-stroke'; "
    "runpy.run_module('tennis_stroke.cli', run_name='__main__')",
]


@pytest.mark.process
def test_an_address_it_cannot_listen_at_is_one_line_before_anything_loads(tmp_path):
    """A port another server listens on, a host that is no address, an address of
    another machine: one line, exit 2, before any compiled code loads (a bound in seconds
    failed under load: what was loaded is what counts)."""
    folder = project(tmp_path)
    loaded = tmp_path / "loaded.txt"
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        for options, message in [
            (["--port", str(port)], f"--port {port}: in use on 127.0.0.1"),
            (["--host", "999.1.1.1"], "--host 999.1.1.1: not a name or an address"),
            (["--host", "192.0.2.1"], "--host 192.0.2.1: cannot listen there"),
        ]:
            done = subprocess.run(
                [*EXPLORE_LOADED, str(loaded), "explore", *options],
                cwd=folder,
                capture_output=True,
                text=True,
                timeout=120,
            )
            assert done.returncode == 2 and message in done.stderr, done.stderr
            assert len(done.stderr.strip().splitlines()) == 1, done.stderr
            assert loaded.read_text() == "", f"loaded before refusing: {loaded.read_text()}"


@pytest.mark.process
@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("  rtol: 5.0e-8 ", "  rtol: -1.0 ", "config key 'solver.rtol': -1.0 is less than"),
        ("model: {}", "model: {M2: [", "YAML syntax error"),
        ("  samples: 641", "  samples: 2000000000", "config key 'fig4.samples': the curves"),
    ],
)
def test_a_bad_config_stops_the_explorer_in_one_line_naming_the_key(tmp_path, old, new, message):
    """A config the workflow would refuse: refused by the explorer as the workflow does,
    before anything loads (a bad value was one line without its key)."""
    folder = project(tmp_path)
    config = folder / "config" / "config.yaml"
    text = config.read_text()
    assert old in text
    config.write_text(text.replace(old, new, 1))
    with pytest.raises(ValueError) as info:  # the command prints it as one line, exit 2
        server_module.serve(folder, port=address.free_port("127.0.0.1"))
    assert message in str(info.value) and "\n" not in str(info.value)
    if "rtol" in old:  # and through the command: one line, exit 2
        done = subprocess.run(EXPLORE, cwd=folder, capture_output=True, text=True, timeout=60)
        assert done.returncode == 2 and message in done.stderr, done.stderr
        assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_on_every_interface_the_machine_s_own_addresses_may_open_the_websocket():
    allowed = address.origins("0.0.0.0", 5006)
    assert f"{socket.gethostname()}:5006" in allowed and "127.0.0.1:5006" in allowed
    assert address.origins("127.0.0.1", 5006) == ["127.0.0.1:5006", "localhost:5006"]
    assert "0.0.0.0:5006" not in allowed  # no browser's page has that origin


@pytest.mark.process
def test_outside_a_checkout_the_explorer_says_where_to_run_it(tmp_path):
    done = subprocess.run([*EXPLORE], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr.strip() == (
        f"tennis-stroke: error: no workflow/Snakefile in {tmp_path}: "
        "run explore from the project's folder"
    )


#: The text input of the number field named arguments[0].
INPUT_JS = """
const m = Bokeh.documents[0].get_model_by_name(arguments[0]);
const stack = [...Bokeh.index.roots];
while (stack.length) {
  const v = stack.pop();
  if (v.model === m) {
    v.el.scrollIntoView({block: "center"});
    return v.shadow_el.querySelector("input");
  }
  stack.push(...(v.child_views ?? []));
}
return null;
"""
#: The text of the Div named arguments[0].
TEXT_JS = "return Bokeh.documents[0].get_model_by_name(arguments[0]).text"


def type_over(browser, name: str, text: str, end: str) -> None:
    """Select the field's text as a person does (Ctrl+A) and type ``text``, then ``end``."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys

    field = browser.execute_script(INPUT_JS, name)
    field.click()  # keys go to the focused field (an element's send_keys moves the caret)
    keys = ActionChains(browser).key_down(Keys.CONTROL).send_keys("a").key_up(Keys.CONTROL)
    for key in text:
        keys.send_keys(key)
    keys.perform()
    assert field.get_attribute("value") == text, name  # never rewritten while typed
    ActionChains(browser).send_keys(end).perform()


def wait_text(browser, name: str, words: str, seconds: float = 60.0) -> str:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        text = browser.execute_script(TEXT_JS, name)
        if words in text:
            return text
        time.sleep(0.05)
    raise AssertionError(f"{name} never said {words!r}: {text!r}")


def typed_values(controls):
    """For every number control, an in-bounds value near the paper's and the text a
    person might type for it: an integer, a decimal, an exponent, a decimal comma, a minus
    (typographic or not), in turn."""
    out = []
    for n, control in enumerate(c for c in controls if not c.choices):
        paper = float(control.paper)
        value = round(paper * 1.1, 6) if paper else 1.0
        if control.high is not None and value > control.high:
            value = round(paper * 0.9, 6)
        kind = n % 5
        if kind == 0:
            value = float(round(value))
            value = value + 1 if value == paper else value
            text = f"{value:.0f}"
        elif kind == 1:
            text = f"{value:.6f}".rstrip("0")
        elif kind == 2:
            text = f"{value:.4e}"
            value = float(text)
        elif kind == 3:
            text = f"{value:.6f}".rstrip("0").replace(".", ",")
        else:
            value = -value if control.low is None or control.low < -value else value
            text = f"{value:.6f}".rstrip("0").replace("-", "\u2212")
        assert control.low is None or value >= control.low, control.key
        out.append((control, text, value))
    return out


@pytest.mark.browser
@browser_needed
def test_every_number_field_computes_with_what_is_typed_over_its_text(server, browser):
    """Typing '4000' over k_contact's selected 7800 left '78004000' in the field and
    computed with it, and each keystroke came back reformatted: every number field takes
    the text typed over its selection (an integer, a decimal, an exponent, a comma, a
    minus), applied on Enter or on leaving the field, and the server computes with
    exactly those values (the page's 'computed with' line, from the config it solved)."""
    from selenium.webdriver.common.keys import Keys

    folder, port = server
    open_page(browser, port)
    wait_map(browser, 1)
    shared_controls = controls.controls(load_yaml(folder / "config" / "config.yaml"), "fig2")
    typed = typed_values(shared_controls)
    assert len(typed) > 20
    for n, (control, text, _) in enumerate(typed):
        type_over(browser, control.key, text, Keys.ENTER if n % 2 else Keys.TAB)
    said = wait_text(browser, "explore-setting", typed[-1][0].label + " = ")
    for control, text, value in typed:
        shown = browser.execute_script(INPUT_JS, control.key).get_attribute("value")
        assert shown == text, (control.key, shown)  # what was typed stays as typed
        unit = f" {control.unit}" if control.unit not in ("", "1") else ""
        assert f"{control.label} = {controls.number_text(value)}{unit}" in said, (control.key, said)
    assert browser.execute_script(TEXT_JS, "explore-error") == ""


@pytest.mark.browser
@browser_needed
def test_a_value_typed_wrongly_is_refused_and_the_field_restored(server, browser):
    """Out of bounds (the spinner clamped it silently) or not a number: the error line
    names it, the field shows the value in use again, nothing is recomputed."""
    from selenium.webdriver.common.keys import Keys

    _, port = server
    open_page(browser, port)
    wait_map(browser, 1)
    for text, words in (("2", "2 is outside [0.01, 1]"), ("0.9.5", "'0.9.5' is not a number")):
        type_over(browser, "model.restitution", text, Keys.ENTER)
        wait_text(browser, "explore-error", words)
        field = browser.execute_script(INPUT_JS, "model.restitution")
        end = time.monotonic() + 10
        while field.get_attribute("value") != "1" and time.monotonic() < end:
            time.sleep(0.05)
        assert field.get_attribute("value") == "1"
    assert not any(m["generation"] >= 2 for m in browser.execute_script(MAPS_JS))


#: Every widget of the page and the plots and table: kind, name, its box, and whether its
#: label's text is cut (wider than the label) or a table header's is.
LAYOUT_JS = """
const out = [];
const stack = [...Bokeh.index.roots];
while (stack.length) {
  const v = stack.pop();
  const type = v.model.type;
  const r = v.el.getBoundingClientRect();
  const box = [r.left, r.top, r.right, r.bottom];
  const root = v.shadow_el ?? v.el.shadowRoot ?? v.el;
  if (["Select", "TextInput", "Button"].includes(type)) {
    const label = root.querySelector("label");
    const cut = label ? label.scrollWidth > label.clientWidth + 1 : false;
    out.push({type, name: v.model.name, box, cut, text: label ? label.innerText : ""});
  } else if (type === "Figure" || type === "Plot") {
    out.push({type: "plot", name: v.model.name, box, cut: false, text: ""});
  } else if (type === "DataTable") {
    const headers = [...root.querySelectorAll(".slick-header-column")];
    const cut = headers.filter(
      (c) => c.querySelector(".slick-column-name").scrollWidth > c.clientWidth + 1
    ).map((c) => c.innerText);
    const hidden = headers.filter((c) => c.getBoundingClientRect().right > r.right + 1)
      .map((c) => c.innerText);
    out.push({type, name: v.model.name, box, cut: cut.length > 0, text: cut.join(", "), hidden});
  }
  stack.push(...(v.child_views ?? []));
}
return {items: out, width: window.innerWidth, height: window.innerHeight};
"""


def _overlap(a, b) -> bool:
    return a[0] < b[2] - 1 and b[0] < a[2] - 1 and a[1] < b[3] - 1 and b[1] < a[3] - 1


@pytest.mark.browser
@browser_needed
@pytest.mark.parametrize("width", [1280, 1920])
def test_the_page_is_laid_out_for_a_person(server, width):
    """At 1400 px the labels of neighbouring controls overlapped, contact_lead_rule's was
    cut, Fig. 9's toolbar left the window, claim names were cut and Save was below the
    fold: at 1280 and 1920 px no widget overlaps another, no label or header is cut,
    the plots are inside the window and Save is in view without scrolling."""
    _, port = server
    driver = chromium(width, 900, loopback=True)
    try:
        open_page(driver, port)
        layout = driver.execute_script(LAYOUT_JS)
    finally:
        driver.quit()
    items = layout["items"]
    widgets = [i for i in items if i["type"] in ("Select", "TextInput", "Button")]
    assert len(widgets) > 20
    visible = [w for w in widgets if w["box"][3] > w["box"][1]]
    for i, a in enumerate(visible):
        assert not a["cut"], (a["name"], a["text"])
        for b in visible[i + 1 :]:
            assert not _overlap(a["box"], b["box"]), (a["name"], b["name"])
    for plot in (i for i in items if i["type"] == "plot"):
        assert plot["box"][2] <= layout["width"], plot["name"]
    (table,) = [i for i in items if i["type"] == "DataTable"]
    assert not table["cut"], table["text"]
    assert table["box"][2] <= layout["width"]
    # the values are in view (at 1280 px 'here' was cut); the descriptions say they scroll
    assert all(h.startswith("quantity (the table scrolls") for h in table["hidden"]), table
    (save,) = [w for w in widgets if w["name"] == "explore-save"]
    assert 0 <= save["box"][1] and save["box"][3] <= layout["height"]
