"""A figure under the paper's configuration beside a scenario's (a scenario's page): one
colour scale and shared axes, their difference, linked hovers and a shared crosshair
(:func:`comparison_view`: :func:`map_comparison` or :func:`curve_comparison`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from bokeh.layouts import row
from bokeh.models import (
    ColumnDataSource,
    CrosshairTool,
    CustomJSHover,
    Div,
    HoverTool,
    LinearColorMapper,
    Range1d,
    Span,
)
from bokeh.palettes import Category10_10, RdBu11, interp_palette
from bokeh.plotting import figure as bokeh_figure

from ...inference.measures import valid_values
from ...io.compare import same_grid
from ..registry import Figure
from .maps import (
    CELL_JS,
    MAP_VIEWS,
    TOOLS,
    cell_hover,
    curve_data,
    draw_marks,
    map_colors,
    map_data,
    short_label,
    status_names,
    value_range,
)

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
        x_axis_label=short_label(ds[x]),
        y_axis_label=short_label(ds[y]),
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
    names = status_names(paper)
    sides = {"paper": (paper, first), "scenario": (scenario, second)}
    titles = {"paper": "the paper's configuration", "scenario": f"scenario {who}"}
    if same_grid(valid_values(paper, var), valid_values(scenario, var)):
        layers, hovers, fields = _linked_layers(sides, x, y, var, name, mapper, marks, extra)
    else:
        layers, hovers, fields = _own_layers(sides, x, y, var, name, mapper, marks)
    plots, crosshair = [], _crosshair(name)
    for side, source, field, colors, bar, pick in layers:
        p = _panel(paper, x, y, titles.get(side, DIFFERENCE), f"{name}-{side}", ranges, MAP_PANEL)
        image = p.image(
            image=field, source=source, x="left", y="bottom", dw="dw", dh="dh", color_mapper=colors
        )
        p.add_layout(image.construct_color_bar(title=bar, width=10), "right")
        p.add_tools(cell_hover(image, source, hovers[side], names, fields), crosshair())
        if line is not None and side in sides:
            ds = sides[side][0]
            p.line(ds[x].values, ds[line].values, color="red", line_width=2)
        draw_marks(p, pick, x, y)
        plots.append(p)
    _level(plots)
    if len(plots) == 2:
        plots.append(Div(text=_NO_DIFFERENCE.format(var=var), width=MAP_PANEL[0]))
    return row(*plots, name=name)


def _level(plots) -> None:
    """Panels side by side of one height and one frame: a panel without the marks'
    legend (:func:`~.maps.draw_marks` grows a panel by it) grows by as much, as room
    under its frame."""
    tallest = max(p.height for p in plots)
    for p in plots:
        extra = tallest - p.height
        if extra:
            border = p.min_border_bottom if p.min_border_bottom is not None else p.min_border
            p.height, p.min_border_bottom = tallest, (border or 0) + extra


def _linked_layers(sides, x: str, y: str, var: str, name: str, mapper, marks, extra):
    """The panels of a :func:`map_comparison` on one grid, ``(side, source, field,
    colours, colour bar title, marks)`` each: both maps and their difference from one
    source (``<name>-compare``); each panel's hover (all the same: every value of the
    cell) and the source's fields the hover writes as values."""
    paper, first = sides["paper"]
    second = sides["scenario"][1]
    label, coords = short_label(paper[var]), (short_label(paper[x]), short_label(paper[y]))
    status = "status" in first and "status" in second
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
    tips += [(f"status, {SIDES[side]}", f"@status_{side}{{status}}") for side in sides if status]
    tips += [
        (f"{short_label(paper[k])}, {SIDES[side]}", f"@{k}_{side}{{0.00}}")
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
    layers = [
        (side, source, side, mapper, label, pick) for side, pick in zip(sides, marks, strict=True)
    ]
    layers.append(("difference", source, "difference", colors, f"{DIFFERENCE} ({label})", ()))
    return layers, dict.fromkeys((*sides, "difference"), tips), fields


def _own_layers(sides, x: str, y: str, var: str, name: str, mapper, marks):
    """The panels of a :func:`map_comparison` on two grids (as :func:`_linked_layers`):
    each map from its own source (``<name>-paper-map``, ``<name>-scenario-map``) with its
    own hover, no difference."""
    paper = sides["paper"][0]
    label, coords = short_label(paper[var]), (short_label(paper[x]), short_label(paper[y]))
    layers, hovers = [], {}
    for (side, (ds, own)), pick in zip(sides.items(), marks, strict=True):
        source = ColumnDataSource(own, name=f"{name}-{side}-map")
        layers.append((side, source, "image", mapper, label, pick))
        hovers[side] = [(coords[0], "@image{x}"), (coords[1], "@image{y}")]
        hovers[side].append((f"{label}, {SIDES[side]}", "@image{value}"))
        if "status" in ds:
            hovers[side].append(("status", "@status{status}"))
    return layers, hovers, ("image", "status")


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
    label = short_label(paper[var])
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
    sides = _curve_sources(first, second, name, one)
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
                (short_label(paper[x]), "@x{0.0000}"),
                (f"{label}, {SIDES[side]}", "@v{value}"),
                ("status", "@status"),
            ]
            p.add_tools(_curve_hover(p, source_, "v", own, ("v",)))
    p.legend.location = "bottom_right"
    p.legend.background_fill_alpha = 0.6
    draw_marks(p, marks, x, var, ours_color="black")
    crosshair = _crosshair(name, "height")
    p.add_tools(crosshair())
    if not one:
        return row(
            p, Div(text=_NO_DIFFERENCE.format(var=var), width=CURVE_PANEL[0] // 2), name=name
        )
    q = _difference_panel(p, sides[0][1], paper, x, var, name, x_range, crosshair)
    _level([p, q])
    return row(p, q, name=name)


def _curve_sources(first: dict, second: dict, name: str, one: bool) -> list[tuple]:
    """The curves of a :func:`curve_comparison`, ``(side, source, field)`` each: on one
    grid (``one``), both from one source (``<name>-compare``) with their difference,
    else each from its own (``<name>-paper-map``, ``<name>-scenario-map``)."""
    if not one:
        return [
            (side, ColumnDataSource(data, name=f"{name}-{side}-map"), "v")
            for side, data in (("paper", first), ("scenario", second))
        ]
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
    return [("paper", source, "paper"), ("scenario", source, "scenario")]


def _difference_panel(
    p, source, paper: xr.Dataset, x: str, var: str, name: str, x_range, crosshair
):
    """The hover of the curves ``p`` of a :func:`curve_comparison` on one grid (every
    value at the sample nearest the mouse), and the panel of their difference beside
    it, on the same x axis, with the same hover and crosshair."""
    label = short_label(paper[var])
    tips = [(short_label(paper[x]), "@x{0.0000}")]
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
    return q


def _curve_hover(p, source: ColumnDataSource, field: str, tooltips, fields) -> HoverTool:
    """A hover on a curve: the sample nearest the mouse along x (one tooltip), found on
    an invisible line through ``field`` of ``source``; ``fields`` written as the maps'
    values are (two decimals, a failed stroke's "none (failed stroke)")."""
    near = p.line("x", field, source=source, line_alpha=0.0)
    value = CustomJSHover(args={"src": source, "names": {}}, code=CELL_JS)
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
