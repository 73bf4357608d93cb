"""The strokes of one file animated in the plane (:func:`stroke_view`): the stick figure's
points are result variables; play, pause, a time scrubber, the omega curves with a
cursor, each stroke's contact window shaded and its kinetic energy read out.  The live
explorer shows other strokes in the same view (:func:`update_stroke_view`).  The
current frame's source is named ``<name>-now``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from bokeh.core.properties import value as fixed_text
from bokeh.layouts import column, row
from bokeh.models import BoxAnnotation, Button, ColumnDataSource, CustomJS, Div, Slider, Span
from bokeh.palettes import Category10_10
from bokeh.plotting import figure as bokeh_figure

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
