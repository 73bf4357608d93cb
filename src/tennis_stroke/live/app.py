"""The live explorer's page: one Bokeh document per browser session, its controls, its
views and the work that recomputes them.

A change of a control recomputes, in this order, each stage pushed to the page as soon
as it is done: the map at the coarse level, Fig. 9's curve, the map at the full level,
the picked stroke, the claims (:mod:`tennis_stroke.live.compute` computes each).
Every server shares one worker thread (the solver's own threads use the cores): a
session's request waits for it, and work for a setting that a newer one replaced is
dropped between two stages or two row blocks of a map, so rapid changes pile up
nothing (at most one running and one waiting request per session and kind).  A failed
stage shows one line in the page; the server keeps serving.

A page load computes nothing: a new session shows the paper's setting at the coarse
level and Fig. 9's curve, computed once per server (:meth:`Shared.paper_views`), and
asks for its full map and claims only when its page has connected (Bokeh's
``document_ready`` event): a page whose websocket never opens costs the building of its
document, and Bokeh drops it after :data:`UNUSED_SESSION_SECONDS`.  At most
:attr:`Shared.max_sessions` sessions live at once; a page beyond them gets one line
saying so, and no session.
"""

from __future__ import annotations

import html
import sys
import threading
import time
from collections.abc import Callable, Mapping
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import numpy as np
from bokeh.events import Tap
from bokeh.layouts import column, row
from bokeh.models import (
    Button,
    ColumnDataSource,
    CustomJS,
    DataTable,
    Div,
    NumberFormatter,
    Select,
    TableColumn,
    TextInput,
)

from ..inference.reading_space import claims_and_readings
from ..pipeline.scenarios import ScenarioError, save_scenario, scenario_config
from ..replication.marks import mark_values
from ..replication.registry import FIGURES as REGISTRY
from ..replication.registry import LIVE
from ..replication.views.maps import curve_data, curve_view, map_data, map_view, value_range
from ..replication.views.strokes import stroke_view, update_stroke_view
from ..replication.views.tables import fit_columns
from . import compute, controls

#: The one worker of every session (see the module's docstring).
_WORKER = ThreadPoolExecutor(max_workers=1, thread_name_prefix="tennis-stroke-explore")
#: The page's layout (px): the controls' panel, each control, the map and Fig. 9's curve;
#: they fit side by side in a 1280 px window (tests/live/test_server.py checks 1280 and
#: 1920 px: nothing overlaps, no text is cut).
PANEL_WIDTH, CONTROL_WIDTH, CONTROLS_HEIGHT = 370, 330, 760
MAP_WIDTH, CURVE_WIDTH = 480, 370
#: Sessions one server keeps at once (each holds its maps and views, a few MB).
MAX_SESSIONS = 8
#: Seconds after which Bokeh drops a session whose page is gone or never connected.
UNUSED_SESSION_SECONDS = 10


def _registry_figure(live: str):
    """The registry figure the explorer shows as ``live`` (``fig2``, ``fig3``, ``fig9``):
    its title and the paper's marks."""
    return REGISTRY[next(name for name, shown in LIVE.items() if shown == live)]


#: Records in the browser when each map is drawn (``window.__explore_maps``; the frame
#: after its data arrived): what the benchmark and the browser tests time and wait for.
_PROBE_JS = """
const d = source.data, seen = {generation: d.generation[0], level: d.level[0]}
requestAnimationFrame(() => (window.__explore_maps = window.__explore_maps || []).push(
  {...seen, t: performance.now()}))
"""


@dataclass
class Shared:
    """What every session of one server reads: the paper's configuration, the claims the
    views test, the files a saved scenario goes to, the map's figure, the threads."""

    config: dict
    claims: list
    declared: dict
    fit_of_claim: dict
    fitted: frozenset
    figure: str
    scenarios: Path
    schema: Path
    threads: int | None = None
    max_sessions: int = MAX_SESSIONS
    stopping: threading.Event = field(default_factory=threading.Event)
    sessions: int = 0
    _paper: tuple | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def paper_views(self) -> tuple:
        """The coarse map and Fig. 9's curve at the paper's setting (the default reading),
        computed by the first caller, then shared by every session of the server."""
        with self._lock:
            if self._paper is None:
                paper = {c.key: c.paper for c in self.controls()}
                overrides = controls.overrides(self.config, paper)  # as a session's first
                config = scenario_config(self.config, "explore", overrides, self.schema)
                self._paper = (
                    compute.map_level(config, self.figure, "coarse", threads=self.threads),
                    compute.fig9_curve(config, self.threads),
                )
            return self._paper

    def controls(self) -> list:
        """The page's controls, each marked with where its default comes from."""
        return controls.controls(self.config, self.figure, self.fitted)

    def open_session(self) -> bool:
        """Count a new session in, if fewer than :attr:`max_sessions` live."""
        with self._lock:
            if self.sessions >= self.max_sessions:
                return False
            self.sessions += 1
            return True

    def close_session(self) -> None:
        with self._lock:
            self.sessions = max(0, self.sessions - 1)

    @classmethod
    def load(
        cls,
        config,
        claims_path,
        readings_path,
        scenarios,
        schema,
        figure,
        threads=None,
        max_sessions=MAX_SESSIONS,
    ):
        claims, space = claims_and_readings(claims_path, readings_path)
        declared = {c["id"]: c for c in claims}
        return cls(
            config,
            compute.view_claims(claims),
            declared,
            dict(space.fit_of_claim()),
            space.fitted(),
            figure,
            Path(scenarios),
            Path(schema),
            threads,
            max_sessions,
        )


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}"


class Session:
    """One browser session: its controls' values, its views and its requests."""

    def __init__(self, shared: Shared, doc):
        self.shared, self.doc = shared, doc
        self.controls = shared.controls()
        self.values = {c.key: c.paper for c in self.controls}
        self.generation = {"all": 0, "stroke": 0}
        self._queued = {"all": False, "stroke": False}
        self._lock = threading.Lock()
        self._resetting = False
        self.picked: tuple[float, float] | None = None
        self.stroke = None  # the picked stroke's view, once a point is picked
        self.fig = compute.FIGURES[shared.figure][0]
        self._build(*shared.paper_views())
        self.status.text = "the paper's setting, coarse map; the full map once connected"
        doc.on_event("document_ready", self._connected)
        if hasattr(doc, "apply_json_patch"):  # a Bokeh document (tests use a stand-in)
            doc.apply_json_patch = partial(self._patched, doc.apply_json_patch)

    def _patched(self, apply: Callable, patch, setter=None) -> None:
        """Apply what the page sent (Bokeh's ``Document.apply_json_patch``).  Bokeh
        refuses a value of the wrong type (a number, a list, a dict for a text field)
        before any callback of ours runs, with a traceback in the server's log, nothing
        on the page and the page's widget keeping the value: here the refusal is the
        error line, and every field shows its value again."""
        try:
            apply(patch, setter=setter)
        except Exception as exc:  # noqa: BLE001 - anything a page can send
            self.error.text = html.escape(f"refused: {_first_line(exc)}", quote=False)
            for widget in [*self.widgets.values(), self.scenario_name]:
                widget.trigger("value", widget.value, widget.value)  # sent to the page

    def _connected(self, event) -> None:
        """The page is connected: compute its full map and claims (once)."""
        if self.generation["all"] == 0:
            self.request("all", skip=("coarse", "fig9"))

    # -- the page ---------------------------------------------------------------------

    def _build(self, ds, curve) -> None:
        """The page: the map and Fig. 9's curve (``ds``, ``curve``), the status lines,
        the claims table, the stroke's place, and the controls' panel beside them."""
        self._build_map(ds)
        self._build_curve(curve)
        views_width = MAP_WIDTH + CURVE_WIDTH
        self.status = Div(text="", name="explore-status", width=views_width)
        self.setting = Div(
            text="computed with the paper's setting", name="explore-setting", width=views_width
        )
        self.error = Div(
            text="",
            name="explore-error",
            width=views_width,
            styles={"color": "#b00020", "font-weight": "bold"},
        )
        self._build_claims_table(views_width)
        self.stroke_status = Div(
            text="<i>Click a point of the map to play its stroke.</i>", name="explore-stroke-status"
        )
        self.stroke_box = column(Div(), name="explore-stroke-box")
        panel = self._controls()
        views = column(
            self.status,
            self.setting,
            self.error,
            row(self.map, self.curve),
            self.claims_table,
            self.stroke_status,
            self.stroke_box,
        )
        self.doc.add_root(row(panel, views))
        self.doc.title = "tennis-stroke explore"

    def _build_map(self, ds) -> None:
        """The map of ``ds`` with the figure's marks; a tap on it picks a stroke."""
        registry = _registry_figure(self.fig)
        marks = mark_values(registry, self.shared.declared)
        title = f"{registry.title.split(':')[0]} live: v_out over (theta0, delta0)"
        self.map = map_view(
            ds, "theta0", "delta0", "v_out", title, "explore-map", marks, "best_delta0"
        )
        self.map_source = self.map.select_one({"name": "explore-map-map"})
        self.map_colors = self.map.select_one({"name": "explore-map-colors"})
        self.map_line = self.map.select_one({"name": "explore-map-line"})
        self._set_map(self._map_data(ds, 0))
        self.map_source.js_on_change(
            "data", CustomJS(args={"source": self.map_source}, code=_PROBE_JS)
        )
        self.map.on_event(Tap, self._tap)
        self.map.width = MAP_WIDTH

    def _build_curve(self, curve) -> None:
        """Fig. 9's curve with its marks."""
        fig9 = _registry_figure("fig9")
        self.curve = curve_view(
            curve,
            "tau",
            "v_out",
            "Fig. 9 live: v_out over tau",
            "explore-fig9",
            mark_values(fig9, self.shared.declared),
        )
        self.curve_source = self.curve.select_one({"name": "explore-fig9-map"})
        self.curve.width = CURVE_WIDTH

    def _build_claims_table(self, width: int) -> None:
        """The claims the views test, their verdicts filled as they are computed."""
        self.claims_source = ColumnDataSource(self._claims_data(None), name="explore-claims")
        self.claims_table = DataTable(
            source=self.claims_source,
            columns=[
                TableColumn(field="id", title="claim"),
                TableColumn(
                    field="paper_value", title="paper", formatter=NumberFormatter(format="0.0[000]")
                ),
                TableColumn(
                    field="reproduced_value",
                    title="here",
                    formatter=NumberFormatter(format="0.0[000]"),
                ),
                TableColumn(
                    field="tolerance",
                    title="tolerance",
                    formatter=NumberFormatter(format="0.0[000]"),
                ),
                TableColumn(field="unit", title="unit"),
                TableColumn(field="status", title="verdict"),
                # last: the long descriptions scroll sideways, the values stay in view
                TableColumn(field="quantity", title="quantity (the table scrolls sideways)"),
            ],
            width=width,
            autosize_mode="none",  # each column as wide as its text; a wide table scrolls
            height=28 * (len(self.shared.claims) + 2),
            index_position=None,
            name="explore-claims-table",
        )
        data = self.claims_source.data  # the verdicts to come, as wide as the widest
        fit_columns(
            {**data, "status": ["known_deviation", "used_for_fit"]}, self.claims_table.columns
        )
        self.claims_source.js_on_change(
            "data", CustomJS(args={"table": self.claims_table}, code="table.view.change.emit()")
        )

    def _widget(self, control: controls.Control):
        paper = control.paper
        unit = f" ({control.unit})" if control.unit not in ("", "1") else ""
        title = f"{control.label}{unit} · {control.origin} {paper}"
        if control.choices:
            widget = Select(
                title=title,
                value=str(paper),
                options=list(control.choices),
                width=CONTROL_WIDTH,
                name=control.key,
            )
        else:  # a text field: its value changes on Enter or on leaving it, never per key
            widget = TextInput(
                title=title,
                value=controls.number_text(paper),
                width=CONTROL_WIDTH,
                name=control.key,
            )
        widget.description = control.note or None
        widget.on_change("value", partial(self._changed, control))
        return widget

    def _controls(self):
        groups: dict[str, list] = {}
        for control in self.controls:
            section = control.key.split(".")[0]
            group = {
                "model": "Model" if not control.choices else "Readings and model",
                "solver": "Solver",
            }.get(section, "The figures' own values")
            groups.setdefault(group, []).append(self._widget(control))
        self.widgets = {w.name: w for ws in groups.values() for w in ws}
        reset = Button(
            label="Reset to the default reading", name="explore-reset", width=CONTROL_WIDTH
        )
        reset.on_click(self._reset)
        self.scenario_name = TextInput(
            title="Save these settings as scenario",
            width=CONTROL_WIDTH - 130,
            placeholder="a name",
            name="explore-scenario-name",
        )
        save = Button(label="Save as scenario", name="explore-save", width=120, align="end")
        save.on_click(self._save)
        self.saved = Div(text="", width=CONTROL_WIDTH, name="explore-saved")
        parts = []
        for group, widgets in groups.items():
            parts.append(Div(text=f"<b>{group}</b>"))
            parts += widgets
        # reset and save stay in view above the controls, which scroll on their own
        top = column(reset, row(self.scenario_name, save), self.saved, width=PANEL_WIDTH)
        controls = column(
            *parts,
            width=PANEL_WIDTH,
            height=CONTROLS_HEIGHT,
            styles={"overflow-y": "auto", "overflow-x": "hidden"},
        )
        return column(top, controls, width=PANEL_WIDTH)

    # -- data of the views ------------------------------------------------------------

    def _set_map(self, data: dict) -> None:
        """Show the map ``data``; its grid (first point, steps, shape) is kept apart for
        a tap: a page can send new data for the map's source."""
        self.map_source.data = data
        rows, cols = data["image"][0].shape
        self.grid = (*(data[k][0] for k in ("x0", "y0", "dx", "dy")), rows, cols)

    @staticmethod
    def _map_data(ds, generation: int, level: str = "coarse") -> dict:
        data = map_data(ds, "theta0", "delta0", "v_out")
        return data | {"level": [level], "generation": [generation]}

    def _claims_data(self, table) -> dict:
        keys = ("id", "quantity", "unit", "paper_value", "reproduced_value", "tolerance", "status")
        if table is None:
            return {
                "id": [c["id"] for c in self.shared.claims],
                "quantity": [c["quantity"] for c in self.shared.claims],
                "unit": [c["unit"] for c in self.shared.claims],
                "paper_value": [float(c["paper_value"]) for c in self.shared.claims],
                "reproduced_value": [np.nan] * len(self.shared.claims),
                "tolerance": [float(c["tolerance"]) for c in self.shared.claims],
                "status": ["computing"] * len(self.shared.claims),
            }
        return {k: list(table[k]) for k in keys}

    # -- events -----------------------------------------------------------------------

    def _config(self, values: Mapping[str, object] | None = None) -> dict:
        """The configuration at the controls' values (or ``values``), checked as a
        scenario's is."""
        values = self.values if values is None else values
        overrides = controls.overrides(self.shared.config, values)
        try:
            return scenario_config(self.shared.config, "explore", overrides, self.shared.schema)
        except ScenarioError as exc:
            raise controls.ExplorerError(str(exc).removeprefix("scenario 'explore': ")) from None

    def _changed(self, control: controls.Control, attr, old, new) -> None:
        """A control's value as the page sent it: a choice, or a number field's text
        (sent on Enter or when the field loses focus).  A refused value is named in the
        error line and the control shows its current value again; nothing is computed."""
        value, problem = new, None
        if not control.choices:
            try:
                value = controls.read_number(new)
            except ValueError as exc:
                problem = str(exc)
        if problem is None:
            if value == self.values[control.key]:  # a value put back: nothing to do
                return
            problem = controls.refusal(control, value)
        if problem is None:  # the whole setting, as the workflow checks it
            try:
                self._config({**self.values, control.key: value})
            except controls.ExplorerError as exc:
                problem = str(exc)
        if problem is not None:  # checked here: a page can send any value
            current = self.values[control.key]
            kept = current if control.choices else controls.number_text(current)
            if problem:
                self.error.text = html.escape(
                    f"{control.label}: {problem}; kept {kept}", quote=False
                )
            self.widgets[control.key].value = kept
            return
        self.error.text = ""  # a refusal said before no longer holds
        self.values[control.key] = value
        if not self._resetting:
            self.request("all")

    def _reset(self) -> None:
        self._resetting = True
        try:
            for control in self.controls:
                widget = self.widgets[control.key]
                paper = control.paper
                widget.value = str(paper) if control.choices else controls.number_text(paper)
        finally:
            self._resetting = False
        self.request("all")

    def _tap(self, event) -> None:
        """A tap on the map picks the stroke of the nearest grid point of the map shown
        (:attr:`grid`); a tap a page sends off the map, or not a number, is refused in
        the error line."""
        x0, y0, dx, dy, rows, cols = self.grid
        x, y = event.x, event.y
        numbers = all(isinstance(v, int | float) and np.isfinite(v) for v in (x, y))
        if not (numbers and x0 - dx <= x <= x0 + cols * dx and y0 - dy <= y <= y0 + rows * dy):
            self.error.text = html.escape(f"a tap at ({x!r}, {y!r}) is not on the map", quote=False)
            return
        i = int(np.clip(round((x - x0) / dx), 0, cols - 1))
        j = int(np.clip(round((y - y0) / dy), 0, rows - 1))
        self.picked = (float(round(x0 + i * dx, 6)), float(round(y0 + j * dy, 6)))
        self.request("stroke")

    def _save(self) -> None:
        name = self.scenario_name.value.strip()
        overrides = controls.overrides(self.shared.config, self.values)
        try:
            path = save_scenario(
                self.shared.scenarios, name, overrides, self.shared.config, self.shared.schema
            )
        except ScenarioError as exc:
            self.saved.text = html.escape(f"not saved: {exc}", quote=False)
            sys.stderr.write(f"tennis-stroke explore: not saved: {exc}\n")  # the log
            return
        name, path = html.escape(name, quote=False), html.escape(str(path), quote=False)
        self.saved.text = (
            f"saved scenario <code>{name}</code> to <code>{path}</code>; its page: "
            f"<code>snakemake -j2 report/scenarios/{name}/index.html</code>"
        )

    # -- the work ---------------------------------------------------------------------

    def request(self, kind: str, skip: tuple[str, ...] = ()) -> None:
        """Recompute ``kind`` (``all`` or ``stroke``) at the current values; work still
        running for older values is dropped at its next stage or block."""
        self.generation[kind] += 1
        self.status.text = "computing ..."
        with self._lock:
            if self._queued[kind]:
                return
            self._queued[kind] = True
        _WORKER.submit(self._work, kind, skip)

    def _stale(self, kind: str, generation: int) -> bool:
        return self.shared.stopping.is_set() or self.generation[kind] != generation

    def _work(self, kind: str, skip: tuple[str, ...]) -> None:
        with self._lock:
            self._queued[kind] = False
        generation = self.generation[kind]
        stale = partial(self._stale, kind, generation)
        started = time.perf_counter()
        try:
            config = self._config()
            if kind == "all":
                self._push(kind, generation, partial(self._show_setting, self._described(config)))
            for stage, run in self._stages(kind, config, stale):
                if stage in skip:
                    continue
                if stale():
                    return
                result = run()
                if result is None or stale():
                    return
                shown = getattr(self, f"_show_{stage}")
                elapsed = time.perf_counter() - started
                self._push(kind, generation, partial(shown, result, generation, elapsed))
        except Exception as exc:  # one line in the page, the server keeps serving
            self._push(kind, generation, partial(self._show_error, _first_line(exc)))

    def _stages(self, kind: str, config: Mapping, stale) -> list[tuple[str, Callable]]:
        figure, threads = self.shared.figure, self.shared.threads
        picked = self.picked
        stroke = ("stroke", lambda: compute.stroke_at(config, figure, *picked))
        if kind == "stroke":
            return [stroke] if picked else []
        stages = [
            ("coarse", lambda: compute.map_level(config, figure, "coarse", stale, threads)),
            ("fig9", lambda: compute.fig9_curve(config, threads)),
            ("full", lambda: compute.map_level(config, figure, "full", stale, threads)),
        ]
        if picked:
            stages.append(stroke)
        claims = self.shared.claims, self.shared.fit_of_claim
        stages.append(("claims", lambda: compute.claims_table(config, *claims, threads)))
        return stages

    def _push(self, kind: str, generation: int, show: Callable[[], None]) -> None:
        def guarded():
            if self.generation[kind] == generation:  # a newer request: not shown
                show()

        self.doc.add_next_tick_callback(guarded)

    def _described(self, config: Mapping) -> str:
        """The values ``config`` computes with where they are not the paper's, as the
        controls name them: what the views show, whatever the fields hold meanwhile."""
        changed = []
        for control in self.controls:
            value = controls.config_value(config, control.key)
            if str(value) == str(control.paper) or value == control.paper:
                continue
            text = value if control.choices else controls.number_text(value)
            unit = f" {control.unit}" if control.unit not in ("", "1") else ""
            changed.append(f"{control.label} = {text}{unit}")
        return "computed with " + ("; ".join(changed) or "the paper's setting")

    def _show_setting(self, text: str) -> None:
        self.setting.text = html.escape(text, quote=False)

    def _show_coarse(self, ds, generation, elapsed, level="coarse") -> None:
        self.error.text = ""
        data = self._map_data(ds, generation, level)
        self.map_colors.update(
            **dict(zip(("low", "high"), value_range(data["image"][0]), strict=True))
        )
        self._set_map(data)
        self.map_line.data = {"x": ds["theta0"].values, "y": ds["best_delta0"].values}
        shape = data["image"][0].shape[::-1]
        self.status.text = f"{level} map ({shape[0]} x {shape[1]}) in {elapsed:.2f} s"

    def _show_full(self, ds, generation, elapsed) -> None:
        self._show_coarse(ds, generation, elapsed, "full")

    def _show_fig9(self, ds, generation, elapsed) -> None:
        self.curve_source.data = curve_data(ds, "tau", "v_out")

    def _show_stroke(self, ds, generation, elapsed) -> None:
        theta0, delta0 = self.picked
        title = f"The stroke at theta0 = {theta0:g}, delta0 = {delta0:g} deg"
        self.stroke_status.text = f"stroke computed in {elapsed:.2f} s"
        if self.stroke is None:
            self.stroke = stroke_view(ds, "explore-stroke", title)
            self.stroke_box.children = [self.stroke]
        else:  # the same view, other data: the browser redraws, builds nothing
            update_stroke_view(self.stroke, ds, title)

    def _show_claims(self, table, generation, elapsed) -> None:
        self.claims_source.data = self._claims_data(table)
        self.status.text += f"; claims in {elapsed:.2f} s"

    def _show_error(self, line: str) -> None:
        self.error.text = html.escape(line, quote=False)
        self.status.text = "failed: the views show the last setting that computed"


def make_document(shared: Shared, doc) -> None:
    """A new browser session's document (Bokeh's application function): a session, or
    one line when :attr:`Shared.max_sessions` are open."""
    if not shared.open_session():
        doc.add_root(
            Div(
                text=(
                    f"The explorer serves {shared.max_sessions} sessions at once and all "
                    "are open. Reload this page in a minute: a session ends "
                    f"{UNUSED_SESSION_SECONDS} s after its page is closed."
                ),
                name="explore-busy",
            )
        )
        doc.title = "tennis-stroke explore (busy)"
        return
    doc.on_session_destroyed(lambda context: shared.close_session())
    try:
        Session(shared, doc)
    except BaseException:
        shared.close_session()
        raise
