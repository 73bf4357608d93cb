"""The report's interactive views: Bokeh standalone documents, drawn from the result files
the static figures are drawn from (never re-simulating), embedded in the page with every
script inline (works from ``file://`` with the network off).

* :func:`map_view`: a map of Figs. 2-3, 5-8 and 13, or the curve of Fig. 9. Hover shows
  the cell's coordinates, its value and its stroke's status; zoom and pan; the paper's
  value (red ring) and ours (white cross) of the figure's claims, each labelled with its
  claim id (:class:`~tennis_stroke.replication.registry.Mark`).
* :func:`stroke_view`: the strokes of one file animated in the plane (the stick figure's
  points are result variables), with play, pause, a time scrubber, the omega curves with
  a cursor, each stroke's contact window shaded and its kinetic energy read out.
* :func:`multiverse_view`: every consistent reading in a sortable table and in parallel
  coordinates; a reading (and a claim-level variant) picked there shows every claim's
  value and verdict under it beside the default reading's; a claim picked in that table
  highlights the readings under which it fails.

Embedded data: maps as float32 at full resolution (a 241 x 401 map is 0.4 MB before
base64), so hover reads the file's value itself to the two decimals shown; curves and
the multiverse's values as they are (float64: a few kB).  Each view's data source has a
``name`` (``<figure>-map``, ``<figure>-now``, ``multiverse-claims``) through which the
browser tests read it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr
from bokeh.core.properties import value as fixed_text
from bokeh.document import Document
from bokeh.embed import components
from bokeh.layouts import column, row
from bokeh.models import (
    BoxAnnotation,
    Button,
    ColumnDataSource,
    CrosshairTool,
    CustomJS,
    CustomJSHover,
    DataTable,
    Div,
    HoverTool,
    Label,
    LinearColorMapper,
    NumberFormatter,
    Range1d,
    Select,
    Slider,
    Span,
    TableColumn,
)
from bokeh.palettes import Category10_10, Magma256, RdBu11, Viridis256, interp_palette
from bokeh.plotting import figure as bokeh_figure
from bokeh.resources import Resources

from ..inference.measures import valid_values
from ..io.compare import same_grid
from .registry import Figure

#: Tools of every plot (no scroll zoom by default: the page scrolls under the mouse).
TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
PAPER_COLOR, OURS_COLOR = "red", "white"
#: BokehJS inline, only the parts the views use (no WebGL, no MathJax: 1.9 of 3.9 MB).
RESOURCES = Resources(mode="inline", components=["bokeh", "bokeh-widgets", "bokeh-tables"])


def _label(da: xr.DataArray) -> str:
    unit = da.attrs.get("units", "")
    name = str(da.attrs.get("long_name", da.name))
    return f"{da.name}: {name}" + (f" ({unit})" if unit not in ("", "1") else "")


def _step(values: np.ndarray, name: str) -> float:
    """The grid step of a uniform coordinate (the image's cell size)."""
    if len(values) < 2:
        return 1.0
    steps = np.diff(values)
    if not np.allclose(steps, steps[0], rtol=1e-6, atol=1e-12):
        raise ValueError(f"the coordinate {name} is not uniform: no map view of it")
    return float(steps[0])


def _decimals(step: float) -> int:
    """The fewest decimals (up to 6) that write every multiple of ``step`` exactly."""
    return next((d for d in range(7) if abs(round(step, d) - step) < 1e-9 * abs(step)), 6)


def _short(da: xr.DataArray) -> str:
    unit = da.attrs.get("units", "")
    return f"{da.name}" + (f" ({unit})" if unit not in ("", "1") else "")


def _status_names(ds: xr.Dataset) -> dict[int, str]:
    attrs = ds["status"].attrs if "status" in ds else {}
    values, meanings = attrs.get("flag_values"), attrs.get("flag_meanings", "")
    if values is None:
        return {}
    return {int(v): m for v, m in zip(np.atleast_1d(values), meanings.split(), strict=True)}


#: Hover of a map cell: the coordinate of column i / row j, the value, the status name.
#: The grid (first value, step, decimals) is read from the image's source, so a view
#: whose source is given a finer grid (the live explorer) hovers it right.
_CELL_JS = """
const ij = special_vars.image_index, g = src.data
if (format === "x") return (g.x0[0] + ij.i * g.dx[0]).toFixed(g.xd[0])
if (format === "y") return (g.y0[0] + ij.j * g.dy[0]).toFixed(g.yd[0])
if (format === "status") return (names[value] ?? String(value))
if (!Number.isFinite(value)) return "none (failed stroke)"
return (format === "signed" && value >= 0 ? "+" : "") + value.toFixed(2)
"""


def _cell_hover(image, source: ColumnDataSource, tooltips, names, fields=("image", "status")):
    """The hover of a map's image: each cell's coordinates from its column and row and
    the grid of ``source`` (:func:`map_data`), written with the decimals the step needs;
    the image ``fields`` of ``source`` the tooltips read through it."""
    cell = CustomJSHover(
        args={"src": source, "names": {str(k): v for k, v in names.items()}},
        code=_CELL_JS,
    )
    formatters = {f"@{field}": cell for field in fields}
    return HoverTool(renderers=[image], tooltips=tooltips, formatters=formatters)


def map_data(ds: xr.Dataset, x: str, y: str, var: str, extra: Sequence[str] = ()) -> dict:
    """The image source of a map of ``var`` over ``(x, y)``: the values (float32, failed
    strokes NaN), the status codes (int8), the variables ``extra``, and the grid (first
    value, step, decimals of each axis; the image's corner and size)."""
    da = valid_values(ds, var)
    xs, ys = ds[x].values.astype(float), ds[y].values.astype(float)
    dx, dy = _step(xs, x), _step(ys, y)
    data = {"image": [da.transpose(y, x).values.astype(np.float32)]}
    if "status" in ds:
        data["status"] = [ds["status"].transpose(y, x).values.astype(np.int8)]
    for key in extra:
        data[key] = [ds[key].transpose(y, x).values.astype(np.float32)]
    grid = {
        "x0": xs[0],
        "dx": dx,
        "xd": _decimals(dx),
        "y0": ys[0],
        "dy": dy,
        "yd": _decimals(dy),
        "left": xs[0] - dx / 2,
        "bottom": ys[0] - dy / 2,
        "dw": dx * len(xs),
        "dh": dy * len(ys),
    }
    return data | {k: [v] for k, v in grid.items()}


def value_range(image: np.ndarray) -> tuple[float, float]:
    """The colour range of a map: its finite values' (0 to 1 without any)."""
    finite = image[np.isfinite(image)]
    return (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)


def map_colors(var: str, span: tuple[float, float], name: str) -> LinearColorMapper:
    """The colours of a map of ``var`` over ``span`` (low, high), failed strokes grey;
    named ``<name>-colors``."""
    return LinearColorMapper(
        palette=Magma256 if var == "theta_c" else Viridis256,
        low=span[0],
        high=span[1],
        nan_color="lightgray",
        name=f"{name}-colors",
    )


def map_view(
    ds: xr.Dataset,
    x: str,
    y: str,
    var: str,
    title: str,
    name: str,
    marks: Sequence[Mapping] = (),
    line: str | None = None,
    extra: Sequence[str] = (),
):
    """A map of ``var`` over ``(x, y)`` (failed strokes blank), ``line`` (a variable over
    ``x``, the best ``y`` per column, source ``<name>-line``) drawn on top, and the
    figure's ``marks`` (:func:`~tennis_stroke.replication.marks.mark_values`); hover also
    reads the variables ``extra``.  The image's source (:func:`map_data`) is named
    ``<name>-map``, its colour mapper ``<name>-colors``."""
    data = map_data(ds, x, y, var, extra)
    tooltips = [(_short(ds[x]), "@image{x}"), (_short(ds[y]), "@image{y}")]
    tooltips.append((_short(ds[var]), "@image{value}"))
    if "status" in ds:
        tooltips.append(("status", "@status{status}"))
    tooltips += [(_short(ds[key]), f"@{key}{{0.00}}") for key in extra]
    source = ColumnDataSource(data, name=f"{name}-map")
    left, bottom = data["left"][0], data["bottom"][0]
    p = bokeh_figure(
        title=title,
        x_range=(left, left + data["dw"][0]),
        y_range=(bottom, bottom + data["dh"][0]),
        x_axis_label=_label(ds[x]),
        y_axis_label=_label(ds[y]),
        tools=TOOLS,
        width=620,
        height=460,
        name=name,
    )
    mapper = map_colors(var, value_range(data["image"][0]), name)
    image = p.image(
        image="image",
        source=source,
        x="left",
        y="bottom",
        dw="dw",
        dh="dh",
        color_mapper=mapper,
    )
    p.add_layout(image.construct_color_bar(title=_label(ds[var]), width=10), "right")
    p.add_tools(_cell_hover(image, source, tooltips, _status_names(ds)))
    if line is not None:
        best = ColumnDataSource({"x": ds[x].values, "y": ds[line].values}, name=f"{name}-line")
        p.line("x", "y", source=best, color="red", line_width=2, legend_label=f"ours: {line}")
        p.legend.location = "top_right"
        p.legend.background_fill_alpha = 0.6
    _draw_marks(p, marks, x, y)
    return p


def curve_view(
    ds: xr.Dataset, x: str, var: str, title: str, name: str, marks: Sequence[Mapping] = ()
):
    """Fig. 9: ``var`` along ``x`` (failed strokes blank), hover on every sample."""
    source = ColumnDataSource(curve_data(ds, x, var), name=f"{name}-map")
    p = bokeh_figure(
        title=title,
        x_axis_label=_label(ds[x]),
        y_axis_label=_label(ds[var]),
        tools=TOOLS,
        width=620,
        height=420,
        name=name,
    )
    p.line("x", "v", source=source, line_width=2)
    dots = p.scatter("x", "v", source=source, size=4, alpha=0.0, hover_alpha=1.0)
    p.add_tools(
        HoverTool(
            renderers=[dots],
            tooltips=[
                (_short(ds[x]), "@x{0.0000}"),
                (_short(ds[var]), "@v{0.00}"),
                ("status", "@status"),
            ],
            mode="vline",
        )
    )
    _draw_marks(p, marks, x, var, ours_color="black")
    return p


def curve_data(ds: xr.Dataset, x: str, var: str) -> dict:
    """The source of a curve of ``var`` along ``x``: the values (failed strokes NaN) and
    each sample's status by name."""
    v = valid_values(ds, var)
    names = _status_names(ds)
    return {
        "x": ds[x].values,
        "v": v.values,
        "status": [names.get(int(s), str(int(s))) for s in ds["status"].values],
    }


def _draw_marks(p, marks: Sequence[Mapping], x: str, y: str, ours_color: str = OURS_COLOR):
    """The paper's value (red) and ours of each mark, labelled with its claim id: a point
    (ring, cross) where the mark has another coordinate, else a line (dashed, dotted)
    across the plot along its axis."""
    lines = 0  # labels of lines stack up from the plot's edge
    points = []
    for mark in marks:
        along_x = mark["axis"] == x
        for who, value, other, color in (
            ("paper", mark["paper"], mark["other_paper"], PAPER_COLOR),
            ("ours", mark["ours"], mark["other_ours"], ours_color),
        ):
            if value is None or (other is None and mark["other_paper"] is not None):
                continue
            text = f"{mark['claim']} ({who})"
            if other is None:
                lines += 1
                _mark_line(p, value, along_x, who, color, text, 4 + 16 * (lines - 1))
            else:
                at = (value, other) if along_x else (other, value)
                points.append(_mark_point(p, at, who, color, text))
    if points:  # one hover for every mark of the plot
        tips = [("claim", "@text"), ("at", "(@x{0.0[000]}, @y{0.0[000]})")]
        p.add_tools(HoverTool(renderers=points, tooltips=tips))


def _mark_label(text: str, color: str, **place) -> Label:
    backdrop = "black" if color == "white" else "white"
    return Label(
        text=text,
        text_color=color,
        text_font_size="10px",
        background_fill_color=backdrop,
        background_fill_alpha=0.6,
        **place,
    )


def _mark_line(p, value: float, along_x: bool, who: str, color: str, text: str, edge: float):
    """A line at ``value`` across the plot, its label ``edge`` pixels from the plot's
    bottom (a vertical line) or left (a horizontal one)."""
    dash = "dashed" if who == "paper" else "dotted"
    dimension = "height" if along_x else "width"
    p.add_layout(
        Span(location=value, dimension=dimension, line_color=color, line_dash=dash, line_width=2)
    )
    if along_x:  # in the right half, the label ends at the line (else it is cut)
        place = {"x_offset": -4, "text_align": "right"} if _right_half(p, value) else {}
        p.add_layout(_mark_label(text, color, x=value, y=edge, y_units="screen", **place))
    else:
        p.add_layout(_mark_label(text, color, x=40 + edge, y=value, x_units="screen"))


def _right_half(p, x: float) -> bool:
    """Whether ``x`` lies in the right half of ``p``'s x range (False for a range the
    browser computes)."""
    start, end = getattr(p.x_range, "start", None), getattr(p.x_range, "end", None)
    return start is not None and end is not None and x > 0.5 * (start + end)


def _mark_point(p, at: tuple[float, float], who: str, color: str, text: str):
    """A ring (the paper's) or a cross (ours) at ``at``, labelled; its glyph."""
    marker = "circle" if who == "paper" else "x"
    source = ColumnDataSource({"x": [at[0]], "y": [at[1]], "text": [text]})
    glyph = p.scatter(
        "x",
        "y",
        source=source,
        marker=marker,
        size=14,
        fill_alpha=0.0,
        line_color=color,
        line_width=2.5,
    )
    offset = 6 if who == "paper" else -16
    right = _right_half(p, at[0])
    place = {"x_offset": -8, "text_align": "right"} if right else {"x_offset": 8}
    p.add_layout(_mark_label(text, color, x=at[0], y=at[1], y_offset=offset, **place))
    return glyph


#: Which view each drawing function of the registry gets: (kind, var, line, extra); its
#: axes are the figure's (:attr:`~tennis_stroke.replication.registry.Figure.axes`).
MAP_VIEWS = {
    "angle_map": ("map", "v_out", "best_delta0", ()),
    "mass_length": ("map", None, None, ("theta0_best", "delta0_best")),
    "delay_map": ("map", "v_out", "best_tau", ()),
    "v_tau": ("curve", "v_out", None, ()),
    "elbow_force": ("map", "v_out", None, ()),
}


def figure_view(figure: Figure, datasets: Sequence[xr.Dataset], title: str, marks):
    """The interactive view of a registry figure, or None for a figure without one."""
    spec = MAP_VIEWS.get(figure.draw)
    if spec is None:
        return None
    kind, var, line, extra = spec
    ds = datasets[0]
    x, y = figure.axes
    var = var or figure.args[0]
    if kind == "curve":
        return curve_view(ds.isel(delta0=0), x, var, title, figure.name, marks)
    return map_view(ds, x, y, var, title, figure.name, marks, line, extra)


# ---------------------------------------------------------------------------------------
# a scenario against the paper's configuration

#: Colours of a difference: diverging, white at 0, blue below and red above (those of
#: the comparison PNG, :data:`tennis_stroke.replication.compare.DIVERGING`).
DIFFERENCE_COLORS = tuple(interp_palette(RdBu11, 255))
DIFFERENCE = "scenario \u2212 paper's configuration"
#: How a comparison's hover names each side: ours under the paper's configuration (not
#: the paper's printed value, which the red marks show) and ours under the scenario.
SIDES = {"paper": "paper's configuration", "scenario": "scenario"}
#: Each panel of a comparison of maps (three fit the page's width) and of curves (two).
MAP_PANEL, CURVE_PANEL = (372, 340), (560, 380)


def _crosshair(name: str, dimensions: str = "both"):
    """The crosshair lines (data units, named ``<name>-cross-x`` and ``-y``) every panel
    of comparison ``name`` shares, and a function giving a panel its crosshair tool
    drawing them: the mouse over one panel draws them in all."""
    spans = tuple(
        Span(dimension=d, line_color="black", line_dash="dashed", name=f"{name}-cross-{a}")
        for d, a in (("height", "x"), ("width", "y"))
        if dimensions in ("both", d)
    )
    overlay = spans if len(spans) == 2 else spans[0]
    return lambda: CrosshairTool(overlay=overlay, dimensions=dimensions)


def _union(first: Sequence[float], second: Sequence[float]) -> tuple[float, float]:
    return min(first[0], second[0]), max(first[1], second[1])


def _panel(ds: xr.Dataset, x: str, y: str, title: str, name: str, ranges, size):
    """A panel of a comparison: ``ranges`` (x, y) shared with its other panels (None:
    its own); its axes labelled by name and unit (the long names would not fit: the
    comparison's PNG above has them)."""
    shared = {k: r for k, r in zip(("x_range", "y_range"), ranges, strict=True) if r is not None}
    return bokeh_figure(
        title=title,
        **shared,
        x_axis_label=_short(ds[x]),
        y_axis_label=_short(ds[y]),
        tools=TOOLS,
        width=size[0],
        height=size[1],
        name=name,
    )


def map_comparison(
    paper: xr.Dataset,
    scenario: xr.Dataset,
    x: str,
    y: str,
    var: str,
    name: str,
    who: str,
    marks: tuple[Sequence[Mapping], Sequence[Mapping]] = ((), ()),
    line: str | None = None,
    extra: Sequence[str] = (),
):
    """The paper configuration's map of ``var`` beside scenario ``who``'s, on one colour
    scale (``<name>-colors``, from both maps' finite values) and shared axes, then their
    difference (scenario minus paper, ``<name>-difference-colors``: diverging, centred
    on 0) where both lie on one grid.  Hovering a cell of any panel shows the cell's
    paper, scenario and difference values, both statuses and both ``extra`` variables
    (one source, ``<name>-compare``); a crosshair follows the mouse in every panel, and
    pan and zoom are shared.  Where the grids differ, each map keeps its own source
    (``<name>-paper-map``, ``<name>-scenario-map``) and hover, and the difference panel
    says why it is missing.  Each map draws its own ``line`` (a variable over ``x``: the
    best ``y`` per column) and ``marks`` (the paper configuration's, the scenario's)."""
    first = map_data(paper, x, y, var, extra)
    second = map_data(scenario, x, y, var, extra)
    both = np.concatenate([first["image"][0].ravel(), second["image"][0].ravel()])
    mapper = map_colors(var, value_range(both), name)
    ranges = tuple(
        Range1d(*_union(*((d[lo][0], d[lo][0] + d[size][0]) for d in (first, second))))
        for lo, size in (("left", "dw"), ("bottom", "dh"))
    )
    label, coords = _short(paper[var]), (_short(paper[x]), _short(paper[y]))
    names = _status_names(paper)
    sides = {"paper": (paper, first), "scenario": (scenario, second)}
    titles = {"paper": "the paper's configuration", "scenario": f"scenario {who}"}
    status = "status" in first and "status" in second
    layers, hovers = [], {}
    if same_grid(valid_values(paper, var), valid_values(scenario, var)):
        grid = {k: v for k, v in first.items() if k not in ("image", "status", *extra)}
        data = dict(grid)
        for side, (_, own) in sides.items():
            data[side] = own["image"]
            data |= {f"{k}_{side}": own[k] for k in extra}
            if status:
                data[f"status_{side}"] = own["status"]
        data["difference"] = [second["image"][0] - first["image"][0]]
        source = ColumnDataSource(data, name=f"{name}-compare")
        tips = [(coords[0], "@paper{x}"), (coords[1], "@paper{y}")]
        tips += [(f"{label}, {SIDES[side]}", f"@{side}{{value}}") for side in sides]
        tips.append((f"{label}, {DIFFERENCE}", "@difference{signed}"))
        tips += [
            (f"status, {SIDES[side]}", f"@status_{side}{{status}}") for side in sides if status
        ]
        tips += [
            (f"{_short(paper[k])}, {SIDES[side]}", f"@{k}_{side}{{0.00}}")
            for k in extra
            for side in sides
        ]
        fields = tuple(k for k in data if k not in grid)
        reach = float(np.nanmax(np.abs(data["difference"][0]), initial=0.0)) or 1.0
        colors = LinearColorMapper(
            palette=DIFFERENCE_COLORS,
            low=-reach,
            high=reach,
            nan_color="lightgray",
            name=f"{name}-difference-colors",
        )
        for side, pick in zip(sides, marks, strict=True):
            layers.append((side, source, side, mapper, label, pick))
            hovers[side] = tips
        layers.append(("difference", source, "difference", colors, f"{DIFFERENCE} ({label})", ()))
        hovers["difference"] = tips
    else:
        fields = ("image", "status")
        for (side, (ds, own)), pick in zip(sides.items(), marks, strict=True):
            source = ColumnDataSource(own, name=f"{name}-{side}-map")
            layers.append((side, source, "image", mapper, label, pick))
            hovers[side] = [(coords[0], "@image{x}"), (coords[1], "@image{y}")]
            hovers[side].append((f"{label}, {SIDES[side]}", "@image{value}"))
            if "status" in ds:
                hovers[side].append(("status", "@status{status}"))
    plots, crosshair = [], _crosshair(name)
    for side, source, field, colors, bar, pick in layers:
        p = _panel(paper, x, y, titles.get(side, DIFFERENCE), f"{name}-{side}", ranges, MAP_PANEL)
        image = p.image(
            image=field, source=source, x="left", y="bottom", dw="dw", dh="dh", color_mapper=colors
        )
        p.add_layout(image.construct_color_bar(title=bar, width=10), "right")
        p.add_tools(_cell_hover(image, source, hovers[side], names, fields), crosshair())
        if line is not None and side in sides:
            ds = sides[side][0]
            p.line(ds[x].values, ds[line].values, color="red", line_width=2)
        _draw_marks(p, pick, x, y)
        plots.append(p)
    if len(plots) == 2:
        plots.append(Div(text=_NO_DIFFERENCE.format(var=var), width=MAP_PANEL[0]))
    return row(*plots, name=name)


_NO_DIFFERENCE = (
    "<p><b>No difference drawn:</b> the paper's configuration and the scenario compute "
    "{var} on different grids (the difference would need one of them interpolated).</p>"
)


def curve_comparison(
    paper: xr.Dataset,
    scenario: xr.Dataset,
    x: str,
    var: str,
    name: str,
    who: str,
    marks: Sequence[Mapping] = (),
):
    """The paper configuration's curve of ``var`` along ``x`` and scenario ``who``'s on
    one plot (``<name>-curves``), and beside it their difference (scenario minus paper)
    on the same x axis where both lie on one grid.  Hovering either panel shows the
    paper, scenario and difference values and statuses at the sample nearest the mouse
    (one source, ``<name>-compare``; a failed stroke's value is "none (failed stroke)"),
    and a vertical line follows the mouse in both; ``marks``: the scenario's."""
    first, second = curve_data(paper, x, var), curve_data(scenario, x, var)
    x_range = Range1d(
        *_union(*((float(np.min(d["x"])), float(np.max(d["x"]))) for d in (first, second)))
    )
    label = _short(paper[var])
    p = _panel(
        paper,
        x,
        var,
        f"the paper's configuration and scenario {who}",
        f"{name}-curves",
        (x_range, None),
        CURVE_PANEL,
    )
    one = same_grid(valid_values(paper, var), valid_values(scenario, var))
    if one:
        difference = second["v"] - first["v"]
        source = ColumnDataSource(
            {
                "x": first["x"],
                "paper": first["v"],
                "scenario": second["v"],
                "difference": difference,
                "status_paper": first["status"],
                "status_scenario": second["status"],
                # where the mouse finds a sample: finite wherever a stroke failed
                "near": np.where(np.isfinite(second["v"]), second["v"], first["v"]),
                "near_difference": np.nan_to_num(difference, nan=0.0),
            },
            name=f"{name}-compare",
        )
        sides = [("paper", source, "paper"), ("scenario", source, "scenario")]
    else:
        sides = [
            (side, ColumnDataSource(data, name=f"{name}-{side}-map"), "v")
            for side, data in (("paper", first), ("scenario", second))
        ]
    for (side, source_, field), color, dash in zip(
        sides, ("gray", Category10_10[0]), ("solid", "solid"), strict=True
    ):
        legend = "the paper's configuration" if side == "paper" else f"scenario {who}"
        p.line(
            "x",
            field,
            source=source_,
            color=color,
            line_dash=dash,
            line_width=2,
            legend_label=legend,
        )
        if not one:
            own = [
                (_short(paper[x]), "@x{0.0000}"),
                (f"{label}, {SIDES[side]}", "@v{value}"),
                ("status", "@status"),
            ]
            p.add_tools(_curve_hover(p, source_, "v", own, ("v",)))
    p.legend.location = "bottom_right"
    p.legend.background_fill_alpha = 0.6
    _draw_marks(p, marks, x, var, ours_color="black")
    crosshair = _crosshair(name, "height")
    p.add_tools(crosshair())
    if not one:
        return row(
            p, Div(text=_NO_DIFFERENCE.format(var=var), width=CURVE_PANEL[0] // 2), name=name
        )
    tips = [(_short(paper[x]), "@x{0.0000}")]
    tips += [(f"{label}, {SIDES[side]}", f"@{side}{{value}}") for side in SIDES]
    tips.append((f"{label}, {DIFFERENCE}", "@difference{signed}"))
    tips += [(f"status, {SIDES[side]}", f"@status_{side}") for side in SIDES]
    fields = ("paper", "scenario", "difference")
    p.add_tools(_curve_hover(p, source, "near", tips, fields))
    q = _panel(paper, x, var, DIFFERENCE, f"{name}-difference", (x_range, None), CURVE_PANEL)
    q.yaxis.axis_label = f"{DIFFERENCE} ({label})"
    q.add_layout(Span(location=0.0, dimension="width", line_color="gray", line_width=1))
    q.line("x", "difference", source=source, line_width=2, color=Category10_10[3])
    q.add_tools(_curve_hover(q, source, "near_difference", tips, fields), crosshair())
    return row(p, q, name=name)


def _curve_hover(p, source: ColumnDataSource, field: str, tooltips, fields) -> HoverTool:
    """A hover on a curve: the sample nearest the mouse along x (one tooltip), found on
    an invisible line through ``field`` of ``source``; ``fields`` written as the maps'
    values are (two decimals, a failed stroke's "none (failed stroke)")."""
    near = p.line("x", field, source=source, line_alpha=0.0)
    value = CustomJSHover(args={"src": source, "names": {}}, code=_CELL_JS)
    return HoverTool(
        renderers=[near],
        tooltips=tooltips,
        mode="vline",
        formatters={f"@{f}": value for f in fields},
    )


def comparison_view(
    figure: Figure,
    paper: Sequence[xr.Dataset],
    scenario: Sequence[xr.Dataset],
    who: str,
    marks: tuple[Sequence[Mapping], Sequence[Mapping]] = ((), ()),
):
    """The view of a registry figure under the paper's configuration and scenario
    ``who`` with their difference (:func:`map_comparison`, :func:`curve_comparison`),
    or None for a figure without one.  ``marks``: the paper configuration's and the
    scenario's (:func:`~tennis_stroke.replication.marks.mark_values`)."""
    spec = MAP_VIEWS.get(figure.draw)
    if spec is None:
        return None
    kind, var, line, extra = spec
    x, y = figure.axes
    var = var or figure.args[0]
    if kind == "curve":
        first, second = (ds[0].isel(delta0=0) for ds in (paper, scenario))
        return curve_comparison(first, second, x, var, figure.name, who, marks[1])
    return map_comparison(paper[0], scenario[0], x, y, var, figure.name, who, marks, line, extra)


# ---------------------------------------------------------------------------------------
# strokes


#: Advances the scrubber while playing (one timer per view; pause clears it).
_PLAY_JS = """
const key = "__stroke_timer_" + slider.id
if (window[key]) { clearInterval(window[key]); window[key] = null; button.label = "Play"; return }
button.label = "Pause"
if (slider.value >= slider.end) slider.value = slider.start
window[key] = setInterval(() => {
  const next = Math.min(slider.value + slider.step, slider.end)
  slider.value = next
  if (next >= slider.end) { clearInterval(window[key]); window[key] = null; button.label = "Play" }
}, 40)
"""

#: One frame: the stick figures and the ball at the scrubber's time.
_FRAME_JS = """
const t = slider.value
const T = curves.data.t
let k = Math.round((t - T[0]) / (T[1] - T[0]))
k = Math.max(0, Math.min(T.length - 1, k))
const I = info.data, n = I.label.length
const xs = [], ys = [], bx = [], by = [], energy = []
for (let s = 0; s < n; s++) {
  const c = (v) => curves.data[v + "_" + s][k]
  xs.push([c("x_elbow"), c("x_wrist"), c("x_racket")])
  ys.push([c("y_elbow"), c("y_wrist"), c("y_racket")])
  const tc = I.t_contact_start[s], ts = I.t_separation[s]
  // the ball: in along +x at ball_speed to the hitting point at the contact start,
  // held there during the contact, out along -x at v_out after the separation
  let x = I.x_hit_contact[s], y = I.y_hit_contact[s]
  if (t < tc) x -= I.ball_speed[s] * (tc - t)
  else if (t > ts) x -= I.v_out_ms[s] * (t - ts)
  bx.push(x); by.push(y)
  const e = c("kinetic_energy")
  energy.push(I.label[s] + ": " + (Number.isFinite(e) ? e.toFixed(2) + " J" : "n/a"))
}
now.data = {xs: xs, ys: ys, color: I.color, label: I.label,
            t: Array(n).fill(T[k]), x_ball: bx, y_ball: by}
cursor.location = T[k]
readout.text = "t = " + T[k].toFixed(4) + " s; kinetic energy of the rods: " + energy.join(", ")
"""


#: The stick figure's points, rod by rod: elbow, wrist, racket end.
STICK = ("elbow", "wrist", "racket")


def _stroke_data(ds: xr.Dataset, picks: Sequence[int]) -> tuple[dict, dict]:
    """The curves of the picked strokes (``<var>_<n>``, float32, on the file's times) and
    one row of numbers per stroke: label, colour, contact window, and what draws the ball
    (the hitting point at the contact start, ``ball_speed``, v_out in m/s)."""
    t = ds["t"].values.astype(float)
    curves: dict[str, np.ndarray] = {"t": t}
    keys = ("label", "color", "t_contact_start", "t_separation", "x_hit_contact")
    info: dict[str, list] = {k: [] for k in (*keys, "y_hit_contact", "ball_speed", "v_out_ms")}
    for n, i in enumerate(picks):
        for var in (*(f"{a}_{p}" for p in STICK for a in "xy"), "omega1", "omega2"):
            curves[f"{var}_{n}"] = ds[var].values[i].astype(np.float32)
        curves[f"kinetic_energy_{n}"] = ds["kinetic_energy"].values[i].astype(np.float32)
        tc = float(ds["t_contact_start"].values[i])
        k = int(np.argmin(np.abs(t - tc)))
        info["label"].append(str(ds["label"].values[i]))
        info["color"].append(Category10_10[n % 10])
        info["t_contact_start"].append(tc)
        info["t_separation"].append(float(ds["t_separation"].values[i]))
        info["x_hit_contact"].append(float(ds["x_hit"].values[i, k]))
        info["y_hit_contact"].append(float(ds["y_hit"].values[i, k]))
        info["ball_speed"].append(float(ds.attrs.get("param_ball_speed", 0.0)))
        info["v_out_ms"].append(float(ds["v_out"].values[i]) / 3.6)
    return curves, info


def _plane_ranges(curves: Mapping, pad: float = 0.1) -> dict[str, tuple[float, float]]:
    """The plane's x and y ranges: every point of the strokes, ``pad`` (m) around."""
    out = {}
    for axis_name in "xy":
        values = np.concatenate([v for k, v in curves.items() if k.startswith(f"{axis_name}_")])
        out[axis_name] = (float(np.nanmin(values)) - pad, float(np.nanmax(values)) + pad)
    return out


def _plane(now, source, curves: Mapping, info: Mapping, title: str, name: str):
    """The stick figures and the ball of the current frame, each racket end's path."""
    ranges = _plane_ranges(curves)
    plane = bokeh_figure(
        title=f"{title}: the strokes in the plane",
        x_range=ranges["x"],
        y_range=ranges["y"],
        match_aspect=True,
        x_axis_label="x (m)",
        y_axis_label="y (m)",
        toolbar_location=None,  # a player, not a map: each toolbar costs drawing time
        width=420,
        height=420,
        name=f"{name}-plane",
    )
    plane.multi_line("xs", "ys", source=now, line_color="color", line_width=4)
    plane.scatter("x_ball", "y_ball", source=now, size=9, color="color", line_color="black")
    for n, (label, color) in enumerate(zip(info["label"], info["color"], strict=True)):
        plane.line(
            f"x_racket_{n}",
            f"y_racket_{n}",
            source=source,
            color=color,
            alpha=0.25,
            legend_label=f"{label} (racket end's path)",
        )
    plane.legend.label_text_font_size = "9px"
    plane.legend.background_fill_alpha = 0.6
    return plane


def _omegas(source: ColumnDataSource, info: Mapping, cursor: Span, name: str):
    """omega2 and omega1 of every stroke, its contact window shaded, the time's cursor."""
    p = bokeh_figure(
        title="omega2 (solid) and omega1 (dashed); contact shaded",
        x_axis_label="t (s)",
        y_axis_label="angular velocity (rad/s)",
        toolbar_location=None,
        width=420,
        height=420,
        name=f"{name}-omegas",
    )
    for n, (label, color) in enumerate(zip(info["label"], info["color"], strict=True)):
        p.line(
            "t",
            f"omega2_{n}",
            source=source,
            color=color,
            line_width=2,
            legend_label=f"omega2 {label}",
        )
        p.line(
            "t",
            f"omega1_{n}",
            source=source,
            color=color,
            line_dash="dashed",
            legend_label=f"omega1 {label}",
        )
        window = (info["t_contact_start"][n], info["t_separation"][n])
        p.add_layout(
            BoxAnnotation(
                left=window[0],
                right=window[1],
                fill_color=color,
                fill_alpha=0.15,
                name=f"{name}-contact-{n}",
            )
        )
    p.legend.label_text_font_size = "9px"
    p.legend.location = "top_left"
    p.add_layout(cursor)
    return p


def stroke_view(ds: xr.Dataset, name: str, title: str):
    """The strokes of a file animated: the arm, the racket and the ball in the plane, the
    omega curves with a cursor and the contact windows shaded, the kinetic energy read
    out; play, pause and a time scrubber.  The current frame's source is named
    ``<name>-now``, the scrubber ``<name>-time`` (:func:`update_stroke_view` shows other
    strokes in it)."""
    curves, info = _stroke_data(ds, range(ds.sizes["stroke"]))
    t = curves["t"]
    source = ColumnDataSource(curves, name=f"{name}-curves")
    now = ColumnDataSource(_first_frame(curves, info), name=f"{name}-now")
    cursor = Span(location=float(t[0]), dimension="height", line_color="black", line_width=1)
    slider = Slider(
        start=float(t[0]),
        end=float(t[-1]),
        step=float(t[1] - t[0]),
        value=float(t[0]),
        title="t (s)",
        format="0.0000",
        width=420,
        name=f"{name}-time",
    )
    button = Button(label="Play", width=80, name=f"{name}-play")
    readout = Div(
        text=f"t = {t[0]:.4f} s; press Play or drag the time", width=420, name=f"{name}-readout"
    )
    frame = CustomJS(
        args={
            "slider": slider,
            "curves": source,
            "info": ColumnDataSource(info, name=f"{name}-info"),
            "now": now,
            "cursor": cursor,
            "readout": readout,
        },
        code=_FRAME_JS,
    )
    slider.js_on_change("value", frame)
    play = CustomJS(args={"slider": slider, "button": button}, code=_PLAY_JS)
    button.js_on_event("button_click", play)
    plane = _plane(now, source, curves, info, title, name)
    plots = row(plane, _omegas(source, info, cursor, name))
    return column(row(button, slider), plots, readout, name=name)


def update_stroke_view(view, ds: xr.Dataset, title: str) -> None:
    """Show the strokes of ``ds`` in a :func:`stroke_view` made for as many strokes (the
    live explorer's picked stroke): its data, ranges, contact windows, labels and title
    replaced, the time back at the start."""
    name = view.name
    curves, info = _stroke_data(ds, range(ds.sizes["stroke"]))
    pick = view.select_one
    info_source = pick({"name": f"{name}-info"})
    if len(info_source.data["label"]) != len(info["label"]):
        raise ValueError(
            f"{name} shows {len(info_source.data['label'])} strokes, not {len(info['label'])}"
        )
    pick({"name": f"{name}-curves"}).data = curves
    info_source.data = info
    pick({"name": f"{name}-now"}).data = _first_frame(curves, info)
    plane = pick({"name": f"{name}-plane"})
    ranges = _plane_ranges(curves)
    plane.x_range.update(start=ranges["x"][0], end=ranges["x"][1])
    plane.y_range.update(start=ranges["y"][0], end=ranges["y"][1])
    plane.title.text = f"{title}: the strokes in the plane"
    for n, item in enumerate(plane.legend[0].items):
        item.label = fixed_text(f"{info['label'][n]} (racket end's path)")
    omegas = pick({"name": f"{name}-omegas"})
    for n, label in enumerate(info["label"]):
        window = (info["t_contact_start"][n], info["t_separation"][n])
        pick({"name": f"{name}-contact-{n}"}).update(left=window[0], right=window[1])
        omegas.legend[0].items[2 * n].label = fixed_text(f"omega2 {label}")
        omegas.legend[0].items[2 * n + 1].label = fixed_text(f"omega1 {label}")
    t0 = float(curves["t"][0])
    pick({"name": f"{name}-time"}).value = t0
    pick({"name": f"{name}-readout"}).text = f"t = {t0:.4f} s; press Play or drag the time"


def _first_frame(curves: Mapping, info: Mapping) -> dict[str, list]:
    """The frame at the first time, so the page shows the strokes before any script runs
    a frame (the same positions and ball as :data:`_FRAME_JS` draws there)."""
    n = len(info["label"])
    t0 = float(curves["t"][0])
    return {
        "xs": [[float(curves[f"x_{p}_{s}"][0]) for p in STICK] for s in range(n)],
        "ys": [[float(curves[f"y_{p}_{s}"][0]) for p in STICK] for s in range(n)],
        "color": list(info["color"]),
        "label": list(info["label"]),
        "t": [t0] * n,
        "x_ball": [
            info["x_hit_contact"][s] - info["ball_speed"][s] * (info["t_contact_start"][s] - t0)
            for s in range(n)
        ],
        "y_ball": list(info["y_hit_contact"]),
    }


# ---------------------------------------------------------------------------------------
# the multiverse


_PICK_JS = """
const r = readings.selected.indices.length ? readings.selected.indices[0] : null
const v = Number(variant.value)
const value_of = values.data.value, within_of = values.data.within
const nc = data.claim.length, nv = data.n_variants
const value = [], verdict = []
for (let c = 0; c < nc; c++) {
  if (r === null) { value.push(NaN); verdict.push("pick a reading"); continue }
  const at = (data.reading_row[r] * nv + v) * nc + c
  value.push(value_of[at])
  verdict.push(within_of[at] ? "pass" : "fail")
}
const d = {...claims.data}
d.value = value; d.verdict = verdict
claims.data = d
claim_table.view.change.emit()  // a DataTable redraws its rows on its view's change
// readings: claims passed under the variant, and the picked claim's failures
const sel = claims.selected.indices.length ? claims.selected.indices[0] : null
const nr = readings.data.reading.length
const passed = [], fails = []
for (let i = 0; i < nr; i++) {
  const row = data.reading_row[i]
  let p = 0
  for (let c = 0; c < nc; c++) if (data.held[c] && within_of[(row * nv + v) * nc + c]) p++
  passed.push(p)
  const f = sel !== null && !within_of[(row * nv + v) * nc + sel]
  fails.push(sel === null ? "" : (f ? "fails" : "passes"))
}
const rd = {...readings.data}
rd.passed = passed; rd.selected_claim = fails
readings.data = rd
reading_table.view.change.emit()
const lo = Math.min(...passed), hi = Math.max(...passed)
const ld = {...lines.data}
ld.color = ld.row.map((row, i) => {
  if (sel !== null) return fails[i] === "fails" ? "#d62728" : "#c7c7c7"
  const u = hi > lo ? (passed[i] - lo) / (hi - lo) : 1
  return palette[Math.round(u * (palette.length - 1))]
})
ld.width = ld.row.map((row, i) => (r !== null && i === r) ? 4 : 1.5)
lines.data = ld
title.text = (r === null ? "No reading picked" : "Reading " + readings.data.reading[r]) +
  ", variant " + v + (sel === null ? "" : "; claim " + claims.data.claim[sel] +
  " fails under " + fails.filter(x => x === "fails").length + " of " + nr + " readings (red)")
"""


def _unknowns(ds: xr.Dataset) -> list[str]:
    """The readings' unknowns: the per-reading variables but the design's indices."""
    return [
        k
        for k in ds.data_vars
        if ds[k].dims == ("reading",) and k not in ("combination", "candidate")
    ]


def _readings_table(ds: xr.Dataset, passed: np.ndarray, held: int, name: str):
    """Every reading with its unknowns, the held-out claims it passes and whether it
    passes the picked claim: its source and its sortable table."""
    n = ds.sizes["reading"]
    data = {"reading": ds["reading"].values.astype(int), "row": np.arange(n)}
    columns = [TableColumn(field="reading", title="reading")]
    for k in _unknowns(ds):
        data[k] = ds[k].values
        unit = ds[k].attrs.get("units", "1")
        if np.issubdtype(ds[k].dtype, np.number):
            title = k + (f" ({unit})" if unit != "1" else "")
            columns.append(
                TableColumn(field=k, title=title, formatter=NumberFormatter(format="0.0000[00]"))
            )
        else:
            columns.append(TableColumn(field=k, title=k))
    data["passed"] = passed
    data["selected_claim"] = [""] * n
    columns.append(TableColumn(field="passed", title=f"held-out passed (of {held})"))
    columns.append(TableColumn(field="selected_claim", title="picked claim"))
    source = ColumnDataSource(data, name=f"{name}-readings")
    return source, _data_table(source, columns, 260, f"{name}-reading-table")


def _claims_table(ds: xr.Dataset, claims: pd.DataFrame, held: np.ndarray, name: str):
    """Every claim: paper's value, tolerance, unit, its value and verdict under the
    picked reading (filled by the page), the default reading's value and status (the
    claims table) and its role; its source and its sortable table."""
    ids = [str(c) for c in ds["claim"].values]
    by_id = claims.set_index("id").loc[ids]
    source = ColumnDataSource(
        {
            "claim": ids,
            "unit": [str(u) for u in ds["claim_unit"].values],
            "paper": ds["paper_value"].values,
            "tolerance": ds["tolerance"].values,
            "held": [
                "held out" if h else f"fit ({f})"
                for f, h in zip(by_id["fit_set"], held, strict=True)
            ],
            "value": np.full(len(ids), np.nan),
            "verdict": ["pick a reading"] * len(ids),
            "default": by_id["reproduced_value"].to_numpy(dtype=float),
            "default_status": [str(v) for v in by_id["status"]],
        },
        name=f"{name}-claims",
    )
    number = NumberFormatter(format="0.0[000]")
    columns = [TableColumn(field="claim", title="claim", width=230)]
    for field, title in (
        ("paper", "paper"),
        ("tolerance", "tolerance"),
        ("unit", "unit"),
        ("value", "picked reading"),
        ("verdict", "verdict"),
        ("default", "default reading"),
        ("default_status", "default status"),
        ("held", "role"),
    ):
        numeric = field in ("paper", "tolerance", "value", "default")
        columns.append(
            TableColumn(field=field, title=title, **({"formatter": number} if numeric else {}))
        )
    return source, _data_table(source, columns, 420, f"{name}-claim-table")


def multiverse_view(ds: xr.Dataset, claims: pd.DataFrame, name: str = "multiverse"):
    """Every consistent reading of ``ds`` (``results/robustness/claims.nc``): a sortable
    table of the readings, parallel coordinates of their unknowns coloured by the number
    of held-out claims passed, a variant picker, and the claims table under the picked
    reading beside the default reading's (``claims``: the claims table)."""
    ids = [str(c) for c in ds["claim"].values]
    held = (claims.set_index("id").loc[ids, "fit_set"] == "").to_numpy()
    order = ds.transpose("reading", "variant", "claim")
    within = order["within"].values.astype(np.int8)
    passed = (within[:, 0, :].astype(bool) & held).sum(axis=1)
    readings, reading_table = _readings_table(ds, passed, int(held.sum()), name)
    claim_source, claim_table = _claims_table(ds, claims, held, name)
    variants = [k for k in ds.data_vars if ds[k].dims == ("variant",)]
    options = [
        (str(v), f"{v}: " + ", ".join(f"{k} = {ds[k].values[v]}" for k in variants))
        for v in range(ds.sizes["variant"])
    ]
    variant = Select(
        title="claim-level variant", value="0", options=options, width=700, name=f"{name}-variant"
    )
    lines = ColumnDataSource(_parallel_lines(ds, passed), name=f"{name}-lines")
    overview = bokeh_figure(
        title="Every consistent reading: its unknowns, scaled to their range",
        x_range=_unknowns(ds),
        y_range=(-0.05, 1.05),
        tools="pan,box_zoom,reset,save",
        width=1000,
        height=300,
        name=f"{name}-overview",
    )
    overview.multi_line(
        "xs", "ys", source=lines, line_color="color", line_width="width", line_alpha=0.7
    )
    overview.yaxis.visible = False
    heading = Div(
        text="<b>No reading picked</b>: pick a row of the readings table",
        width=1000,
        name=f"{name}-title",
    )
    pick = CustomJS(
        args={
            "readings": readings,
            "claims": claim_source,
            "reading_table": reading_table,
            "claim_table": claim_table,
            "variant": variant,
            "lines": lines,
            "title": heading,
            "palette": list(Viridis256),
            # every claim under every (reading, variant), flat in that order: arrays, not
            # lists (Bokeh walks a list's every item looking for models)
            "values": ColumnDataSource(
                {"value": order["value"].values.ravel(), "within": within.ravel()},
                name=f"{name}-values",
            ),
            "data": {
                "claim": ids,
                "held": held.astype(int).tolist(),
                "n_variants": int(ds.sizes["variant"]),
                "reading_row": list(range(ds.sizes["reading"])),
            },
        },
        code=_PICK_JS,
    )
    readings.selected.js_on_change("indices", pick)
    claim_source.selected.js_on_change("indices", pick)
    variant.js_on_change("value", pick)
    return column(heading, variant, reading_table, overview, claim_table, name=name)


#: Pixels per character of a table's text (12 px sans-serif) and around it: a column is
#: as wide as its title and its longest value (up to :data:`CELL_CHARS` characters); its
#: title was cut ("contact_lead", "k_contact (N/").
HEADER_CHAR_PX, HEADER_PAD_PX, CELL_CHARS = 7.5, 22, 80


def _text_width(col, values) -> int:
    """Characters a table column needs: its title, its values (a number: 10)."""
    cells = [10 if isinstance(v, (int, float, np.number)) else len(str(v)) for v in values[:500]]
    return max(len(col.title), min(max(cells, default=0), CELL_CHARS))


def fit_columns(data: Mapping, columns: Sequence) -> None:
    """Make each table column as wide as its title and its longest value in ``data``
    (up to :data:`CELL_CHARS` characters): no title or value is cut."""
    for col in columns:
        chars = _text_width(col, list(data.get(col.field, [])))
        col.width = int(HEADER_CHAR_PX * chars + HEADER_PAD_PX)


def _data_table(source: ColumnDataSource, columns: list, height: int, name: str) -> DataTable:
    """A sortable table whose rows a reader picks (no column dragging: it needs
    jquery-ui, which BokehJS does not ship), each column as wide as its title at least
    (a wide table scrolls sideways)."""
    fit_columns(source.data, columns)
    return DataTable(
        source=source,
        columns=columns,
        sortable=True,
        reorderable=False,
        selectable=True,
        index_position=None,
        autosize_mode="none",
        width=1000,
        height=height,
        name=name,
    )


def _parallel_lines(ds: xr.Dataset, passed: np.ndarray) -> dict[str, list]:
    """One polyline per reading over the unknowns' axes, each scaled to [0, 1] (a
    discrete unknown by its options' order), coloured by ``passed``."""
    unknowns = _unknowns(ds)
    columns = []
    for k in unknowns:
        values = ds[k].values
        if np.issubdtype(values.dtype, np.number):
            lo, hi = float(np.min(values)), float(np.max(values))
            columns.append((values - lo) / (hi - lo) if hi > lo else np.full(len(values), 0.5))
        else:
            options = sorted({str(v) for v in values})
            scale = max(len(options) - 1, 1)
            columns.append(np.array([options.index(str(v)) / scale for v in values]))
    ys = np.column_stack(columns)
    lo, hi = passed.min(), passed.max()
    shade = (passed - lo) / (hi - lo) if hi > lo else np.ones(len(passed))
    return {
        "xs": [list(unknowns)] * len(passed),
        "ys": [list(map(float, row)) for row in ys],
        "color": [Viridis256[int(round(u * 255))] for u in shade],
        "width": [1.5] * len(passed),
        "row": list(range(len(passed))),
    }


# ---------------------------------------------------------------------------------------
# the page


def page_views(views: Mapping[str, object]) -> tuple[str, dict[str, str]]:
    """Bokeh's inline resources with the one script of all ``views`` (one document), and
    each view's div by name: what the page embeds.  The views go into one document in
    one step: Bokeh walks a document's models again after each root it adds, so adding
    them one by one (what ``components`` does with views of no document) walks them
    once per view."""
    document = Document()
    with document.models.freeze():
        for view in views.values():
            document.add_root(view)
    script, divs = components(dict(views))
    return RESOURCES.render() + script, divs
