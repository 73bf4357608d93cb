"""The report's interactive views in a real browser (Debian's headless Chromium driven by
Selenium through Debian's chromedriver; no browser download), the network off: what a
reader hovers, picks and plays shows the result files' values."""

import os
import shutil
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from chromium import CHROMIUM, DRIVER, MISSING, ROWS_JS, chromium, hover_lines, wait_idle
from conftest import SCENARIO, SCENARIO_PAGE

from tennis_stroke.experiments.specs import RESULT_FILES
from tennis_stroke.inference.measures import valid_v_out
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline.scenarios import scenario_path
from tennis_stroke.replication.registry import FIGURES
from tennis_stroke.replication.views.maps import map_view
from tennis_stroke.replication.views.page import page_views

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(CHROMIUM is None or DRIVER is None, reason=MISSING),
]


@pytest.fixture(scope="module")
def browser():
    driver = chromium()
    yield driver
    driver.quit()


def _open(driver, page: Path) -> float:
    """Load ``page`` and wait until every view is drawn; the seconds it took."""
    start = time.perf_counter()
    driver.get(page.as_uri())
    wait_idle(driver)
    return time.perf_counter() - start


def _after(driver, act: str, read: str, ready, *args):
    """Run ``act`` (as a reader's change would), then ``read`` until ``ready`` of what it
    returns (BokehJS runs CustomJS callbacks asynchronously)."""
    driver.execute_script(act, *args)
    for _ in range(100):
        seen = driver.execute_script(read, *args)
        if ready(seen):
            return seen
        time.sleep(0.05)
    raise AssertionError(f"the page did not update: {seen}")


@pytest.fixture
def page(tiny_run, tmp_path):
    shutil.copy(tiny_run / "report/index.html", tmp_path / "index.html")
    return tmp_path / "index.html"


def test_the_page_draws_every_view_offline_without_a_console_error(browser, page):
    seconds = _open(browser, page)
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors
    names = browser.execute_script("return Bokeh.documents[0].roots().map((r) => r.name)")
    assert {"fig02_angle_map", "fig09_v_tau", "fig13_elbow_force", "multiverse"} <= set(names)
    assert {"strokes-fig04", "strokes-fig10", "strokes-table-i"} <= set(names)
    print(f"drawn in {seconds:.2f} s")


def _cells(ds, picks):
    theta, delta = ds["theta0"].values, ds["delta0"].values
    return [(float(theta[i]), float(delta[j])) for i, j in picks]


def test_hovering_a_cell_of_fig2_shows_the_files_value(browser, page, tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["fig2"])
    _open(browser, page)
    n, m = ds.sizes["theta0"], ds.sizes["delta0"]
    for theta0, delta0 in _cells(ds, [(1, 1), (n // 2, m // 2), (n - 2, m - 3)]):
        shown = hover_lines(browser, "fig02_angle_map", theta0, delta0)
        cell = ds.sel(theta0=theta0, delta0=delta0)
        assert float(shown["theta0 (degree)"]) == pytest.approx(theta0)
        assert float(shown["delta0 (degree)"]) == pytest.approx(delta0)
        assert shown["v_out (km/h)"] == f"{float(cell['v_out']):.2f}"
        assert shown["status"] == "ok"


def _map(tilt: float = 0.0) -> xr.Dataset:
    """A map of v_out over (theta0, delta0), as the paper's files hold one."""
    theta, delta = np.arange(60.0, 121.0, 5.0), np.arange(0.0, 101.0, 5.0)
    v = 130.0 + 0.3 * theta[:, None] + 0.1 * delta[None, :] + tilt * (theta[:, None] - 90.0)
    status = {"flag_values": np.arange(7, dtype=np.int8), "flag_meanings": " ".join("abcdefg")}
    return xr.Dataset(
        {
            "v_out": (("theta0", "delta0"), v, {"units": "km/h", "long_name": "rebound speed"}),
            "status": (("theta0", "delta0"), np.zeros(v.shape, np.int8), status),
        },
        coords={
            "theta0": ("theta0", theta, {"units": "degree"}),
            "delta0": ("delta0", delta, {"units": "degree"}),
        },
    )


def test_no_claim_name_of_a_view_is_cut(browser, tmp_path):
    """Issue 53: on a scenario's page a claim's name was cut ('fig2_best_delta0_at_120
    (paper'), as Fig. 13's had been ('fig14_wors'): names drawn beside their marks ran
    out of the comparison's narrow panels.  Fig. 3's marks (points at theta0 = 90 and
    120 deg, by delta0 = 0 deg) and a line near the edge, on a comparison and on a map of
    the report: in Chromium every label and legend lies whole in its box (a label in its
    plot's frame, a legend in its canvas) and every mark's name is on the page."""
    from chromium import TEXTS_JS, cut_texts

    from tennis_stroke.replication.views.comparison import map_comparison

    marks = [
        {
            "claim": f"fig3_best_delta0_at_{t}",
            "axis": "delta0",
            "paper": d,
            "ours": d + 1.0,
            "other_paper": float(t),
            "other_ours": float(t),
        }
        for t, d in ((120, 0.0), (90, 26.1))
    ] + [
        {
            "claim": "fig14_worst_direction",
            "axis": "theta0",
            "paper": 119.0,
            "ours": 61.0,
            "other_paper": None,
            "other_ours": None,
        }
    ]
    views = {
        "fig03_angle_map": map_comparison(
            _map(),
            _map(0.1),
            "theta0",
            "delta0",
            "v_out",
            "fig03_angle_map",
            "heavy",
            (marks, marks),
        ),
        "fig03_single": map_view(_map(), "theta0", "delta0", "v_out", "t", "fig03_single", marks),
    }
    head, divs = page_views(views)
    page = tmp_path / "marks.html"
    page.write_text(
        f"<!DOCTYPE html><html><head>{head}</head><body>{''.join(divs.values())}</body></html>"
    )
    _open(browser, page)
    assert cut_texts(browser) == []
    shown = [t for entry in browser.execute_script(TEXTS_JS) for t in entry["texts"]]
    for mark in marks:
        for who in ("paper", "ours"):
            assert shown.count(f"{mark['claim']} ({who})") == 3, (mark["claim"], who)
    shots = Path(os.environ.get("REPORT_SCREENSHOTS", tmp_path))
    shots.mkdir(parents=True, exist_ok=True)
    assert browser.save_screenshot(str(shots / "marks-legend.png"))


def test_no_text_of_the_report_s_or_a_scenario_s_views_is_cut(browser, page, scenario_page):
    from chromium import cut_texts

    for html in (page, scenario_page[1]):
        _open(browser, html)
        assert cut_texts(browser) == [], html


def test_the_hover_check_fails_on_a_view_whose_data_disagree(browser, tiny_run, tmp_path):
    """The same check on a view drawn from a changed copy of the file: it sees the
    change (so the test above can fail)."""
    ds = load_result(tiny_run / RESULT_FILES["fig2"])
    changed = ds.copy(deep=True)
    changed["v_out"][2, 2] += 0.5
    theta0, delta0 = _cells(ds, [(2, 2)])[0]
    for data, equal in ((ds, True), (changed, False)):
        view = map_view(data, "theta0", "delta0", "v_out", "t", "fig02_angle_map")
        head, divs = page_views({"fig02_angle_map": view})
        page = tmp_path / f"view-{equal}.html"
        page.write_text(
            f"<!DOCTYPE html><html><head>{head}</head><body>{divs['fig02_angle_map']}</body></html>"
        )
        _open(browser, page)
        shown = hover_lines(browser, "fig02_angle_map", theta0, delta0)["v_out (km/h)"]
        file_value = f"{float(ds['v_out'].sel(theta0=theta0, delta0=delta0)):.2f}"
        assert (shown == file_value) is equal, (shown, file_value)


def test_picking_a_reading_shows_its_claims(browser, page, tiny_run):
    """A reading and a variant picked as a reader does: the claims table holds each
    claim's value and verdict under them from results/robustness/claims.nc."""
    ds = load_result(tiny_run / RESULT_FILES["robustness"])
    _open(browser, page)
    reading, variant = ds.sizes["reading"] - 1, ds.sizes["variant"] - 1
    shown = _after(
        browser,
        """
        const doc = Bokeh.documents[0];
        doc.get_model_by_name("multiverse-variant").value = String(arguments[1]);
        doc.get_model_by_name("multiverse-readings").selected.indices = [arguments[0]];
        """,
        """
        const doc = Bokeh.documents[0];
        const c = doc.get_model_by_name("multiverse-claims").data;
        return {claim: [...c.claim], value: [...c.value], verdict: [...c.verdict],
                title: doc.get_model_by_name("multiverse-title").text};
        """,
        lambda seen: seen["title"].startswith("Reading") and f"variant {variant}" in seen["title"],
        reading,
        variant,
    )
    expected = ds.isel(reading=reading, variant=variant)
    assert shown["claim"] == [str(c) for c in ds["claim"].values]
    np.testing.assert_array_equal(np.array(shown["value"], dtype=float), expected["value"])
    assert shown["verdict"] == ["pass" if w else "fail" for w in expected["within"].values]
    assert shown["title"].startswith(f"Reading {int(ds['reading'][reading])}, variant {variant}")
    # and the rows a reader sees: the table redrawn, each visible claim's verdict
    rows = browser.execute_script(ROWS_JS, "multiverse-claim-table")
    verdicts = dict(zip(shown["claim"], shown["verdict"], strict=True))
    assert len(rows) >= 5
    assert all(r[5] == verdicts[r[0]] for r in rows), rows[:3]


def test_picking_a_claim_shows_the_readings_under_which_it_fails(browser, page, tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["robustness"])
    _open(browser, page)
    within = ds["within"].isel(variant=0).values
    claim = int(np.argmax((within == 0).sum(axis=0)))  # the claim failing most often
    marked = _after(
        browser,
        'Bokeh.documents[0].get_model_by_name("multiverse-claims").selected.indices'
        " = [arguments[0]];",
        'return [...Bokeh.documents[0].get_model_by_name("multiverse-readings")'
        ".data.selected_claim];",
        lambda seen: all(seen),
        claim,
    )
    assert marked == ["passes" if w else "fails" for w in within[:, claim]]


def test_the_animation_frame_at_a_time_shows_the_files_positions(browser, page, tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["delay"])
    _open(browser, page)
    k = ds.sizes["t"] // 2
    frame = _after(
        browser,
        'Bokeh.documents[0].get_model_by_name("strokes-fig10-time").value = arguments[0];',
        """
        const doc = Bokeh.documents[0];
        const now = doc.get_model_by_name("strokes-fig10-now").data;
        return {xs: now.xs.map((a) => [...a]), ys: now.ys.map((a) => [...a]), t: [...now.t],
                readout: doc.get_model_by_name("strokes-fig10-readout").text};
        """,
        lambda seen: seen["t"] and abs(seen["t"][0] - float(ds["t"][k])) < 1e-9,
        float(ds["t"][k]),
    )
    for i in range(ds.sizes["stroke"]):
        for axis in ("x", "y"):
            expected = [float(ds[f"{axis}_{p}"][i, k]) for p in ("elbow", "wrist", "racket")]
            assert frame[f"{axis}s"][i] == pytest.approx(expected, abs=1e-6)
        energy = f"{float(ds['kinetic_energy'][i, k]):.2f} J"
        assert f"{ds['label'].values[i]}: {energy}" in frame["readout"]
    assert frame["t"][0] == pytest.approx(float(ds["t"][k]))


def test_play_advances_the_time(browser, page):
    _open(browser, page)
    browser.execute_script(
        "Bokeh.documents[0].get_model_by_name('strokes-fig04-play')"
        ".trigger_event(new (Bokeh.require('core/bokeh_events').ButtonClick)())"
    )
    time.sleep(0.5)
    value = browser.execute_script(
        "return Bokeh.documents[0].get_model_by_name('strokes-fig04-time').value"
    )
    assert value > 0


def test_a_screenshot_of_a_hovered_map_for_a_person(browser, page, tiny_run, tmp_path):
    """Not a check: a picture of what a reader sees (REPORT_SCREENSHOTS keeps it)."""
    ds = load_result(tiny_run / RESULT_FILES["fig2"])
    _open(browser, page)
    theta0, delta0 = _cells(ds, [(ds.sizes["theta0"] // 2, ds.sizes["delta0"] // 2)])[0]
    hover_lines(browser, "fig02_angle_map", theta0, delta0)
    shots = Path(os.environ.get("REPORT_SCREENSHOTS", tmp_path))
    shots.mkdir(parents=True, exist_ok=True)
    shot = shots / "report-hover-fig2.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 0
    print(f"screenshot: {shot}")


#: Where the crosshair's shared lines of comparison arguments[0] stand: [x, y].
CROSS_JS = """
const doc = Bokeh.documents[0];
return ["x", "y"].map((a) => doc.get_model_by_name(`${arguments[0]}-cross-${a}`)?.location);
"""


def _shown(value: float, signed: bool = False) -> str:
    """A value as a view's hover writes it (float32 in the page)."""
    if not np.isfinite(value):
        return "none (failed stroke)"
    return f"{value:+.2f}" if signed else f"{value:.2f}"


def _pair(work: Path, figure: str) -> tuple:
    """The paper's and the scenario's result file of ``figure`` in ``work``."""
    path = RESULT_FILES[FIGURES[figure].files[0]]
    return load_result(work / path), load_result(work / scenario_path(path, SCENARIO[0]))


@pytest.fixture
def scenario_page(tiny_scenario, tmp_path):
    work, _ = tiny_scenario
    shutil.copy(work / SCENARIO_PAGE, tmp_path / "index.html")
    return work, tmp_path / "index.html"


def test_a_scenario_map_hovered_in_any_panel_shows_the_paper_the_scenario_and_the_difference(
    browser, scenario_page
):
    """Fig. 13 on the scenario's page: a cell hovered in the paper's panel, the
    scenario's or the difference's shows the paper file's value, the scenario file's
    and scenario minus paper, and the crosshair's lines, which every panel draws, stand
    on that cell."""
    work, page = scenario_page
    name = "fig13_elbow_force"
    x, y = FIGURES[name].axes
    paper, scenario = _pair(work, name)
    first, second = (valid_v_out(ds).astype(np.float32) for ds in (paper, scenario))
    assert not np.array_equal(first.values, second.values)  # the scenario changes it
    _open(browser, page)
    n, m = paper.sizes[x], paper.sizes[y]
    for side, (i, j) in zip(
        ("paper", "scenario", "difference"), [(0, 0), (n // 2, m // 2), (n - 1, m - 1)], strict=True
    ):
        at = float(paper[x][i]), float(paper[y][j])
        shown = hover_lines(browser, f"{name}-{side}", *at)
        a, b = float(first[{x: i, y: j}]), float(second[{x: i, y: j}])
        assert shown["v_out (km/h), paper's configuration"] == _shown(a), side
        assert shown["v_out (km/h), scenario"] == _shown(b), side
        assert shown["v_out (km/h), scenario \u2212 paper's configuration"] == _shown(
            b - a, signed=True
        ), side
        cross = browser.execute_script(CROSS_JS, name)
        steps = [float(paper[d][1] - paper[d][0]) for d in (x, y)]
        for where, want, step in zip(cross, at, steps, strict=True):
            assert abs(where - want) < 0.5 * step, (side, cross, at)


def test_a_scenario_curve_hovered_shows_both_curves_and_their_difference(browser, scenario_page):
    """Fig. 9 on the scenario's page: a sample hovered on the curves or on their
    difference shows the paper file's v_out, the scenario file's and the difference,
    and the shared vertical line stands at its tau."""
    work, page = scenario_page
    name = "fig09_v_tau"
    paper, scenario = (ds.isel(delta0=0) for ds in _pair(work, name))
    first, second = valid_v_out(paper), valid_v_out(scenario)
    _open(browser, page)
    k = paper.sizes["tau"] // 3
    tau = float(paper["tau"][k])
    a, b = float(first[k]), float(second[k])
    for plot, level in ((f"{name}-curves", b), (f"{name}-difference", b - a)):
        shown = hover_lines(browser, plot, tau, level)
        assert float(shown["tau (s)"]) == pytest.approx(tau, abs=5e-5), plot
        assert shown["v_out (km/h), paper's configuration"] == _shown(a), plot
        assert shown["v_out (km/h), scenario"] == _shown(b), plot
        assert shown["v_out (km/h), scenario \u2212 paper's configuration"] == _shown(
            b - a, signed=True
        ), plot
        x_line, _ = browser.execute_script(CROSS_JS, name)
        assert x_line == pytest.approx(tau, abs=0.5 * float(paper["tau"][1] - paper["tau"][0]))
