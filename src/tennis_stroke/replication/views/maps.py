"""A figure's map or curve as an interactive view, drawn from its result file: hover shows
a cell's coordinates, its value and its stroke's status; zoom and pan; the paper's value
(red ring) and ours (white cross) of the figure's claims, each named by its claim id in a
legend under the plot (:class:`~tennis_stroke.replication.registry.Mark`).

* :func:`map_view`: a map of Figs. 2-3, 5-8 and 13; :func:`curve_view`: the curve of
  Fig. 9; :func:`figure_view`: the view of a registry figure (:data:`MAP_VIEWS`).
* :func:`map_data`, :func:`curve_data`: their sources, which the live explorer and the
  comparisons (:mod:`.comparison`) fill too.

Maps are embedded as float32 at full resolution (a 241 x 401 map is 0.4 MB before
base64), so hover reads the file's value itself to the two decimals shown; curves as
they are.  A view's image source is named ``<figure>-map``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from bokeh.models import (
    ColumnDataSource,
    CustomJSHover,
    HoverTool,
    Legend,
    LegendItem,
    LinearColorMapper,
    Span,
)
from bokeh.palettes import Magma256, Viridis256
from bokeh.plotting import figure as bokeh_figure

from ...inference.measures import valid_values
from ..registry import Figure

#: Tools of every plot (no scroll zoom by default: the page scrolls under the mouse).
TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
PAPER_COLOR, OURS_COLOR = "red", "white"


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


def short_label(da: xr.DataArray) -> str:
    unit = da.attrs.get("units", "")
    return f"{da.name}" + (f" ({unit})" if unit not in ("", "1") else "")


def status_names(ds: xr.Dataset) -> dict[int, str]:
    attrs = ds["status"].attrs if "status" in ds else {}
    values, meanings = attrs.get("flag_values"), attrs.get("flag_meanings", "")
    if values is None:
        return {}
    return {int(v): m for v, m in zip(np.atleast_1d(values), meanings.split(), strict=True)}


#: Hover of a map cell: the coordinate of column i / row j, the value, the status name.
#: The grid (first value, step, decimals) is read from the image's source, so a view
#: whose source is given a finer grid (the live explorer) hovers it right.
CELL_JS = """
const ij = special_vars.image_index, g = src.data
if (format === "x") return (g.x0[0] + ij.i * g.dx[0]).toFixed(g.xd[0])
if (format === "y") return (g.y0[0] + ij.j * g.dy[0]).toFixed(g.yd[0])
if (format === "status") return (names[value] ?? String(value))
if (!Number.isFinite(value)) return "none (failed stroke)"
return (format === "signed" && value >= 0 ? "+" : "") + value.toFixed(2)
"""


def cell_hover(image, source: ColumnDataSource, tooltips, names, fields=("image", "status")):
    """The hover of a map's image: each cell's coordinates from its column and row and
    the grid of ``source`` (:func:`map_data`), written with the decimals the step needs;
    the image ``fields`` of ``source`` the tooltips read through it."""
    cell = CustomJSHover(
        args={"src": source, "names": {str(k): v for k, v in names.items()}},
        code=CELL_JS,
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
    tooltips = [(short_label(ds[x]), "@image{x}"), (short_label(ds[y]), "@image{y}")]
    tooltips.append((short_label(ds[var]), "@image{value}"))
    if "status" in ds:
        tooltips.append(("status", "@status{status}"))
    tooltips += [(short_label(ds[key]), f"@{key}{{0.00}}") for key in extra]
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
    p.add_tools(cell_hover(image, source, tooltips, status_names(ds)))
    if line is not None:
        best = ColumnDataSource({"x": ds[x].values, "y": ds[line].values}, name=f"{name}-line")
        p.line("x", "y", source=best, color="red", line_width=2, legend_label=f"ours: {line}")
        p.legend.location = "top_right"
        p.legend.background_fill_alpha = 0.6
    draw_marks(p, marks, x, y)
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
                (short_label(ds[x]), "@x{0.0000}"),
                (short_label(ds[var]), "@v{0.00}"),
                ("status", "@status"),
            ],
            mode="vline",
        )
    )
    draw_marks(p, marks, x, var, ours_color="black")
    return p


def curve_data(ds: xr.Dataset, x: str, var: str) -> dict:
    """The source of a curve of ``var`` along ``x``: the values (failed strokes NaN) and
    each sample's status by name."""
    v = valid_values(ds, var)
    names = status_names(ds)
    return {
        "x": ds[x].values,
        "v": v.values,
        "status": [names.get(int(s), str(int(s))) for s in ds["status"].values],
    }


#: The marks' legend under a plot: its background (the white crosses of ours must show
#: on it, the names in black read on it) and the height each entry adds to the plot, so
#: the plot's frame keeps its size.
LEGEND_BACKGROUND, LEGEND_ROW = "#c8c8c8", 19


def draw_marks(p, marks: Sequence[Mapping], x: str, y: str, ours_color: str = OURS_COLOR):
    """The paper's value (red) and ours of each mark: a point (ring, cross) where the
    mark has another coordinate, else a line (dashed, dotted) across the plot along its
    axis; each named by its claim in a legend under the plot, which the browser lays out
    around the names it measures (names drawn beside the marks ran out of narrow plots:
    "fig14_wors", "fig2_best_delta0_at_120 (paper").  The plot grows by the legend's
    height."""
    items, points = [], []
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
                glyph = _mark_line(p, value, along_x, who, color)
            else:
                at = (value, other) if along_x else (other, value)
                glyph = _mark_point(p, at, who, color, text)
                points.append(glyph)
            items.append(LegendItem(label=text, renderers=[glyph]))
    if points:  # one hover for every mark of the plot
        tips = [("claim", "@text"), ("at", "(@x{0.0[000]}, @y{0.0[000]})")]
        p.add_tools(HoverTool(renderers=points, tooltips=tips))
    if items:
        legend = Legend(
            items=items,
            location="top_left",
            label_text_font_size="10px",
            label_height=12,
            glyph_height=12,
            spacing=2,
            padding=4,
            margin=2,
            background_fill_color=LEGEND_BACKGROUND,
            background_fill_alpha=1.0,
            name=f"{p.name}-marks" if p.name else None,
        )
        p.add_layout(legend, "below")
        p.height += LEGEND_ROW * len(items) + 8


def _mark_line(p, value: float, along_x: bool, who: str, color: str):
    """A line at ``value`` across the plot; the glyph its legend entry shows (a line of
    no points in the line's colour and dash, which draws nothing and moves no range)."""
    dash = "dashed" if who == "paper" else "dotted"
    dimension = "height" if along_x else "width"
    p.add_layout(
        Span(location=value, dimension=dimension, line_color=color, line_dash=dash, line_width=2)
    )
    return p.line(x=[], y=[], line_color=color, line_dash=dash, line_width=2)


def _mark_point(p, at: tuple[float, float], who: str, color: str, text: str):
    """A ring (the paper's) or a cross (ours) at ``at``, named ``text`` in the hover;
    its glyph."""
    marker = "circle" if who == "paper" else "x"
    source = ColumnDataSource({"x": [at[0]], "y": [at[1]], "text": [text]})
    return p.scatter(
        "x",
        "y",
        source=source,
        marker=marker,
        size=14,
        fill_alpha=0.0,
        line_color=color,
        line_width=2.5,
    )


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
