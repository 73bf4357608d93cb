"""The report's interactive views hold the result files' values: the maps' cells, the
strokes' positions, every claim under every reading; the marks name declared claims."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from bokeh.models import ColumnDataSource, CustomJS
from conftest import ROOT

from tennis_stroke.experiments.specs import RESULT_FILES
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.measures import valid_v_out
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.replication.marks import mark_values
from tennis_stroke.replication.registry import FIGURES, Figure, Mark
from tennis_stroke.replication.views import comparison, maps, multiverse, page, strokes

CLAIMS = {c["id"]: c for c in load_claims(ROOT / "config/claims.yaml")}


def _source(model, name: str) -> ColumnDataSource:
    return next(m for m in model.select({"type": ColumnDataSource}) if m.name == name)


def test_every_mark_names_a_declared_claim_and_its_coordinate():
    """Each mark's values are the paper's (config/claims.yaml) and ours; the other
    coordinate is the measure's argument or the other claim's value."""
    ours = {c: 1000.0 + i for i, c in enumerate(CLAIMS)}
    marked = 0
    for figure in FIGURES.values():
        for mark, entry in zip(figure.marks, mark_values(figure, CLAIMS, ours), strict=True):
            marked += 1
            assert entry["paper"] == CLAIMS[mark.claim]["paper_value"]
            assert entry["ours"] == ours[mark.claim]
            if mark.at:
                assert (
                    entry["other_paper"]
                    == entry["other_ours"]
                    == CLAIMS[mark.claim]["measure"][mark.at]
                )
            elif mark.other:
                assert entry["other_paper"] == CLAIMS[mark.other]["paper_value"]
                assert entry["other_ours"] == ours[mark.other]
            else:
                assert entry["other_paper"] is None
    assert marked >= 10


@pytest.mark.parametrize(
    ("mark", "named"),
    [(Mark("no_such_claim", "delta0"), "no_such_claim"), (Mark("fig9_v_H", "v", at="x"), "x")],
)
def test_a_mark_of_an_undeclared_claim_or_argument_is_named(mark, named):
    figure = Figure("fig99_x", "III", ("fig2",), "angle_map", "t", marks=(mark,))
    with pytest.raises(KeyError, match=named):
        mark_values(figure, CLAIMS)


@pytest.mark.parametrize(("step", "decimals"), [(0.25, 2), (0.5, 1), (2.0, 0), (0.0025, 4)])
def test_a_coordinate_is_written_with_the_decimals_its_step_needs(step, decimals):
    assert maps._decimals(step) == decimals


def test_a_map_view_holds_every_cell_of_the_file(tiny_run):
    """float32 of the file's v_out (failed strokes NaN), its status codes, cell for cell;
    a changed value is seen."""
    ds = load_result(tiny_run / RESULT_FILES["fig2"])
    ds["status"][0, 0] = 5  # a failed stroke: no value, its status
    p = maps.map_view(ds, "theta0", "delta0", "v_out", "t", "fig02_angle_map")
    data = _source(p, "fig02_angle_map-map").data
    expected = valid_v_out(ds).transpose("delta0", "theta0").values.astype(np.float32)
    np.testing.assert_array_equal(data["image"][0], expected)
    assert np.isnan(data["image"][0][0, 0])
    np.testing.assert_array_equal(data["status"][0], ds["status"].values.T)
    changed = ds.copy(deep=True)
    changed["v_out"][1, 1] += 0.01
    other = maps.map_view(changed, "theta0", "delta0", "v_out", "t", "x")
    assert not np.array_equal(_source(other, "x-map").data["image"][0], expected, equal_nan=True)


def test_a_map_over_an_uneven_axis_is_refused(tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["fig2"])
    theta = ds["theta0"].values.copy()
    theta[-1] += 0.1 * (theta[1] - theta[0])
    with pytest.raises(ValueError, match="theta0 is not uniform"):
        maps.map_view(ds.assign_coords(theta0=theta), "theta0", "delta0", "v_out", "t", "x")


def test_the_stroke_view_holds_the_files_positions(tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["fig4"])
    layout = strokes.stroke_view(ds, "s", "Fig. 4")
    curves = _source(layout, "s-curves").data
    now = _source(layout, "s-now").data
    for i in range(ds.sizes["stroke"]):
        for var in ("x_elbow", "y_wrist", "x_racket", "omega2", "kinetic_energy"):
            np.testing.assert_array_equal(curves[f"{var}_{i}"], ds[var].values[i].astype("f4"))
        first = [float(ds[v].values[i, 0]) for v in ("x_elbow", "x_wrist", "x_racket")]
        assert now["xs"][i] == pytest.approx(first, abs=1e-6)


def test_the_multiverse_view_holds_every_claim_under_every_reading(tiny_run):
    ds = load_result(tiny_run / RESULT_FILES["robustness"])
    claims = pd.read_csv(tiny_run / "results/claims.csv", keep_default_na=False)
    layout = multiverse.multiverse_view(ds, claims)
    (pick,) = {m for m in layout.select({"type": CustomJS}) if "data" in m.args}
    data = pick.args["data"]
    values = _source(layout, "multiverse-values").data
    order = ds.transpose("reading", "variant", "claim")
    np.testing.assert_array_equal(values["value"], order["value"].values.ravel())
    np.testing.assert_array_equal(values["within"], order["within"].values.ravel())
    readings = _source(layout, "multiverse-readings").data
    held = np.array([f == "" for f in claims.set_index("id").loc[data["claim"], "fit_set"]])
    within = order["within"].values[:, 0, :].astype(bool)
    np.testing.assert_array_equal(readings["passed"], (within & held).sum(axis=1))
    default = _source(layout, "multiverse-claims").data["default"]
    np.testing.assert_array_equal(
        default, claims.set_index("id").loc[data["claim"], "reproduced_value"].astype(float)
    )


def test_every_figure_with_a_view_gets_one(tiny_run):
    """The maps of Figs. 2-3, 5-9 and 13 (the issue's list) have views."""
    with_views = [n for n, f in FIGURES.items() if f.draw in maps.MAP_VIEWS]
    assert [n[:5] for n in with_views] == [
        "fig02",
        "fig03",
        "fig05",
        "fig06",
        "fig07",
        "fig08",
        "fig09",
        "fig13",
    ]
    for name in with_views:
        figure = FIGURES[name]
        data = [xr.open_dataset(tiny_run / RESULT_FILES[k]) for k in figure.files]
        view = maps.figure_view(figure, data, "t", mark_values(figure, CLAIMS))
        assert _source(view, f"{name}-map").data


def test_text_in_a_view_is_escaped(tiny_run):
    """A stroke's label from a file, shown in the view, never ends the page's script."""
    ds = load_result(tiny_run / RESULT_FILES["fig4"])
    hostile = "</script><script>alert(1)</script>"
    ds = ds.assign_coords(label=("stroke", [hostile] * ds.sizes["stroke"]))
    head, divs = page.page_views({"s": strokes.stroke_view(ds, "s", "t")})
    assert hostile not in head and "alert(1)" in head


def _angle_map(theta: np.ndarray, tilt: float = 0.0) -> xr.Dataset:
    """A map of v_out over (theta0, delta0) with a status, as a result file holds it;
    ``tilt`` adds a change that is negative at small theta0 and positive at large."""
    delta = np.arange(0.0, 91.0, 10.0)
    v = 100.0 + 0.3 * theta[:, None] + 0.1 * delta[None, :]
    v = v + tilt * (theta[:, None] - theta.mean())
    status = {"flag_values": np.arange(7, dtype=np.int8), "flag_meanings": " ".join("abcdefg")}
    attrs = {"units": "km/h", "long_name": "rebound speed"}
    return xr.Dataset(
        {
            "v_out": (("theta0", "delta0"), v, attrs),
            "status": (("theta0", "delta0"), np.zeros(v.shape, np.int8), status),
        },
        coords={
            "theta0": ("theta0", theta, {"units": "degree"}),
            "delta0": ("delta0", delta, {"units": "degree"}),
        },
    )


def _models(view, kind):
    return [m for m in view.select({"type": kind})]


def test_a_comparison_holds_both_maps_and_their_difference_on_shared_scales():
    """Paper and scenario on one colour range (the union of theirs) and one pair of axis
    ranges; the difference is scenario minus paper cell for cell (NaN where a stroke
    failed) on colours centred on 0; one crosshair's lines are every panel's, and every
    panel's hover reads the three values."""
    from bokeh.models import CrosshairTool, HoverTool, Image, LinearColorMapper, Plot

    theta = np.arange(60.0, 121.0, 5.0)
    paper, scenario = _angle_map(theta), _angle_map(theta, tilt=0.4)
    scenario["status"][3, 2] = 5
    view = comparison.map_comparison(paper, scenario, "theta0", "delta0", "v_out", "fig", "s")
    data = _source(view, "fig-compare").data
    first = valid_v_out(paper).transpose("delta0", "theta0").values.astype(np.float32)
    second = valid_v_out(scenario).transpose("delta0", "theta0").values.astype(np.float32)
    np.testing.assert_array_equal(data["paper"][0], first)
    np.testing.assert_array_equal(data["scenario"][0], second)
    np.testing.assert_array_equal(data["difference"][0], second - first)
    assert np.isnan(data["difference"][0][2, 3]) and data["status_scenario"][0][2, 3] == 5
    assert np.nanmin(data["difference"][0]) < 0 < np.nanmax(data["difference"][0])
    mappers = {m.name: m for m in _models(view, LinearColorMapper)}
    both = np.concatenate([first.ravel(), second.ravel()])
    assert (mappers["fig-colors"].low, mappers["fig-colors"].high) == (
        np.nanmin(both),
        np.nanmax(both),
    )
    reach = np.nanmax(np.abs(data["difference"][0]))
    assert mappers["fig-difference-colors"].high == -mappers["fig-difference-colors"].low == reach
    palette = mappers["fig-difference-colors"].palette
    assert palette[len(palette) // 2] == "#f7f7f7"  # white at 0
    plots = [c for c in view.children if isinstance(c, Plot)]
    assert [p.name for p in plots] == ["fig-paper", "fig-scenario", "fig-difference"]
    assert all(p.x_range is plots[0].x_range and p.y_range is plots[0].y_range for p in plots)
    overlays = [t.overlay for p in plots for t in p.tools if isinstance(t, CrosshairTool)]
    assert len(overlays) == 3 and all(o == overlays[0] for o in overlays)
    assert [s.name for s in overlays[0]] == ["fig-cross-x", "fig-cross-y"]
    for p, field in zip(plots, ("paper", "scenario", "difference"), strict=True):
        (image,) = [r for r in p.renderers if isinstance(r.glyph, Image)]
        assert image.glyph.image == field and image.data_source is plots[0].renderers[0].data_source
        (hover,) = [t for t in p.tools if isinstance(t, HoverTool) and t.renderers == [image]]
        assert [field for _, field in hover.tooltips][2:5] == [
            "@paper{value}",
            "@scenario{value}",
            "@difference{signed}",
        ]


def test_a_comparison_on_different_grids_draws_no_difference_and_says_why():
    from bokeh.models import Div, LinearColorMapper, Plot

    paper = _angle_map(np.arange(60.0, 121.0, 5.0))
    scenario = _angle_map(np.arange(50.0, 131.0, 2.5), tilt=0.4)
    view = comparison.map_comparison(paper, scenario, "theta0", "delta0", "v_out", "fig", "s")
    names = {m.name for m in _models(view, ColumnDataSource)}
    assert "fig-compare" not in names and {"fig-paper-map", "fig-scenario-map"} <= names
    (note,) = _models(view, Div)
    assert "different grids" in note.text
    plots = [c for c in view.children if isinstance(c, Plot)]
    assert len(plots) == 2 and plots[0].x_range is plots[1].x_range
    assert (plots[0].x_range.start, plots[0].x_range.end) == (50.0 - 1.25, 130.0 + 1.25)
    colors = next(m for m in _models(view, LinearColorMapper) if m.name == "fig-colors")
    assert colors.high == pytest.approx(float(scenario["v_out"].max()))


def test_a_curve_comparison_holds_both_curves_and_their_difference():
    from bokeh.models import CrosshairTool, Plot

    tau = np.linspace(0.0, 0.3, 31)
    status = {"flag_values": np.arange(7, dtype=np.int8), "flag_meanings": " ".join("abcdefg")}

    def curve(scale):
        return xr.Dataset(
            {
                "v_out": ("tau", 140.0 + scale * np.sin(10 * tau), {"units": "km/h"}),
                "status": ("tau", np.zeros(tau.size, np.int8), status),
            },
            coords={"tau": ("tau", tau, {"units": "s"})},
        )

    paper, scenario = curve(20.0), curve(30.0)
    scenario["status"][4] = 5  # a stroke that fails under the scenario only
    view = comparison.curve_comparison(paper, scenario, "tau", "v_out", "fig", "s")
    data = _source(view, "fig-compare").data
    expected = scenario["v_out"].values - paper["v_out"].values
    expected[4] = np.nan
    np.testing.assert_array_equal(data["difference"], expected)
    assert (data["status_paper"][4], data["status_scenario"][4]) == ("a", "f")
    # the hovers find every sample, a failed one too: their lines are finite everywhere
    assert np.isfinite(data["near"]).all() and np.isfinite(data["near_difference"]).all()
    assert data["near"][4] == data["paper"][4]
    plots = [c for c in view.children if isinstance(c, Plot)]
    assert [p.name for p in plots] == ["fig-curves", "fig-difference"]
    assert plots[0].x_range is plots[1].x_range
    overlays = [t.overlay for p in plots for t in p.tools if isinstance(t, CrosshairTool)]
    assert len(overlays) == 2 and overlays[0] is overlays[1] and overlays[0].name == "fig-cross-x"


def test_a_curve_comparison_on_different_grids_draws_no_difference():
    from bokeh.models import Div, Plot

    def curve(tau):
        status = {"flag_values": np.arange(2, dtype=np.int8), "flag_meanings": "ok failed"}
        return xr.Dataset(
            {
                "v_out": ("tau", 140.0 + 20 * np.sin(10 * tau), {"units": "km/h"}),
                "status": ("tau", np.zeros(tau.size, np.int8), status),
            },
            coords={"tau": ("tau", tau, {"units": "s"})},
        )

    paper, scenario = curve(np.linspace(0, 0.3, 31)), curve(np.linspace(0, 0.4, 81))
    view = comparison.curve_comparison(paper, scenario, "tau", "v_out", "fig", "s")
    names = {m.name for m in _models(view, ColumnDataSource)}
    assert "fig-compare" not in names and {"fig-paper-map", "fig-scenario-map"} <= names
    (plot,) = [c for c in view.children if isinstance(c, Plot)]
    assert (plot.x_range.start, plot.x_range.end) == (0.0, 0.4)
    assert "different grids" in next(c for c in view.children if isinstance(c, Div)).text


def test_a_map_comparison_draws_each_side_s_line_and_hovers_its_extras():
    """Figs. 2-3 draw the best delta0 of each side on its own map; Figs. 5-6 hover the
    optimum angles of both sides."""
    from bokeh.models import Line, Plot

    theta = np.arange(60.0, 121.0, 5.0)
    paper, scenario = _angle_map(theta), _angle_map(theta, tilt=0.4)
    for ds, shift in ((paper, 0.0), (scenario, 5.0)):
        ds["best_delta0"] = ("theta0", 20.0 + shift + 0 * theta, {"units": "degree"})
        ds["theta0_best"] = (("theta0", "delta0"), 0 * ds["v_out"].values + shift)
    view = comparison.map_comparison(
        paper,
        scenario,
        "theta0",
        "delta0",
        "v_out",
        "fig",
        "s",
        line="best_delta0",
        extra=["theta0_best"],
    )
    plots = [c for c in view.children if isinstance(c, Plot)]
    drawn = [
        [r.data_source.data["y"] for r in p.renderers if isinstance(r.glyph, Line)] for p in plots
    ]
    np.testing.assert_array_equal(drawn[0][0], paper["best_delta0"].values)
    np.testing.assert_array_equal(drawn[1][0], scenario["best_delta0"].values)
    assert drawn[2] == []  # the difference has no line
    data = _source(view, "fig-compare").data
    assert data["theta0_best_scenario"][0].max() == 5.0 and data["theta0_best_paper"][0].max() == 0


def test_every_mark_is_named_in_a_legend_the_panels_keep_one_frame():
    """A mark's name drawn beside it ran out of narrow plots ("fig14_wors",
    "fig2_best_delta0_at_120 (paper"): each is now a legend entry under the plot (the
    browser lays it out, tests/replication/test_report_browser.py checks it is whole),
    no label is left, and in a comparison the panel without marks grows as the others,
    so the frames stay level."""
    from bokeh.models import Label, Legend

    theta = np.arange(60.0, 121.0, 5.0)
    marks = [
        {
            "claim": "point",
            "axis": "delta0",
            "paper": 20.0,
            "ours": 25.0,
            "other_paper": 90.0,
            "other_ours": 90.0,
        },
        {
            "claim": "line",
            "axis": "theta0",
            "paper": 118.0,
            "ours": 65.0,
            "other_paper": None,
            "other_ours": None,
        },
    ]
    p = maps.map_view(_angle_map(theta), "theta0", "delta0", "v_out", "t", "fig", marks)
    assert not _models(p, Label)
    (legend,) = _models(p, Legend)
    named = [item.label["value"] for item in legend.items]
    assert named == ["point (paper)", "point (ours)", "line (paper)", "line (ours)"]
    assert p.height == 460 + maps.LEGEND_ROW * 4 + 8
    view = comparison.map_comparison(
        _angle_map(theta),
        _angle_map(theta, 0.1),
        "theta0",
        "delta0",
        "v_out",
        "f",
        "s",
        (marks, marks),
    )
    heights = {c.name: (c.height, c.min_border_bottom) for c in view.children}
    assert len({h for h, _ in heights.values()}) == 1, heights
    assert heights["f-difference"][1] == maps.LEGEND_ROW * 4 + 8 + 5, heights
