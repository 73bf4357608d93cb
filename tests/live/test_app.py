"""A live explorer session in one process (a stand-in for Bokeh's document that runs what
the server would run on its next tick): what a change, a reset, a bad value, a failing
stage and a burst of changes do to its views and its work."""

import threading

import numpy as np
import pytest
from conftest import ROOT

from tennis_stroke.experiments.specs import merged
from tennis_stroke.io.config_files import load_yaml
from tennis_stroke.live import app, compute, controls
from tennis_stroke.solver.stroke import strike_batch


class Document:
    """What a session uses of a Bokeh document; the next-tick callbacks run at once, in
    the order they are added, like the server's loop runs them.  Its page connects at
    once (``document_ready``), unless ``connects=False`` (a page load whose websocket
    never opens); :meth:`destroy` ends the session as Bokeh does."""

    def __init__(self, connects=True):
        self.roots, self.title, self.lock = [], "", threading.Lock()
        self.connects, self.destroyed = connects, []

    def add_root(self, model):
        self.roots.append(model)

    def on_event(self, name, callback):
        assert name == "document_ready"
        if self.connects:
            callback(None)

    def on_session_destroyed(self, callback):
        self.destroyed.append(callback)

    def destroy(self):
        for callback in self.destroyed:
            callback(None)

    def add_next_tick_callback(self, callback):
        with self.lock:
            callback()


@pytest.fixture(scope="module")
def shared(tmp_path_factory):
    folder = tmp_path_factory.mktemp("explore")
    config = merged(
        load_yaml(ROOT / "config" / "config.yaml"),
        {
            "angle_maps": {
                "theta0": {"start": 110.0, "stop": 112.0, "step": 1.0},
                "delta0": {"start": 10.0, "stop": 14.0, "step": 1.0},
            },
            "torque_delay": {"fig9": {"tau": {"start": 0.0, "stop": 0.2, "step": 0.05}}},
        },
    )
    (folder / "scenarios.yaml").write_text("# scenarios\n")
    return app.Shared.load(
        config,
        ROOT / "config" / "claims.yaml",
        ROOT / "config" / "readings.yaml",
        folder / "scenarios.yaml",
        ROOT / "workflow" / "schemas" / "config.schema.yaml",
        "fig2",
        threads=1,
    )


def settle(session, seconds=60.0):
    """Wait until the worker has nothing left for the session."""
    done = threading.Event()
    app._WORKER.submit(done.set)  # one worker: runs after everything queued before it
    assert done.wait(seconds)
    while any(session._queued.values()):
        done.clear()
        app._WORKER.submit(done.set)
        assert done.wait(seconds)


def test_a_change_shows_the_strokes_at_the_new_setting(shared):
    session = app.Session(shared, Document())
    settle(session)
    session.widgets["model.M2"].value = "0.35"
    settle(session)
    data = session.map_source.data
    assert data["level"] == ["full"] and data["generation"] == [2]
    theta, delta = np.arange(110.0, 112.01, 0.25), np.arange(10.0, 14.01, 0.5)
    expected = strike_batch(theta[:, None], delta[None, :], {"M2": 0.35, "L1": 0.3})
    np.testing.assert_array_equal(data["image"][0], expected["v_out_kmh"].T.astype(np.float32))
    verdicts = dict(zip(*(session.claims_source.data[k] for k in ("id", "status")), strict=True))
    # the map spans theta0 110-112 deg: a claim at 120 deg is off its axis, no verdict
    # (it was read at the 112 deg row, issue 66); the others have theirs
    assert verdicts.pop("fig2_best_delta0_at_120") == compute.OFF_AXIS
    assert set(verdicts.values()) <= {"pass", "fail", "used_for_fit", compute.OFF_AXIS}
    assert {"pass", "fail", "used_for_fit"} & set(verdicts.values())
    assert "full map (9 x 9)" in session.status.text and session.error.text == ""


def test_a_page_load_computes_nothing_until_its_page_connects(shared, monkeypatch):
    """100 page loads without a websocket took 47.7 s and 316 MB: each computed a coarse
    map on the server's loop and queued a full one.  Now a session starts from the
    paper's views, computed once per server, and asks for work only once connected."""
    shared.paper_views()
    computed = []
    for name in ("map_level", "fig9_curve", "claims_table"):
        monkeypatch.setattr(
            compute, name, lambda *a, _name=name, **k: computed.append((_name, *a[2:3]))
        )
    sessions = [app.Session(shared, Document(connects=False)) for _ in range(3)]
    settle(sessions[-1])
    assert computed == []
    for session in sessions:
        assert session.generation["all"] == 0 and not any(session._queued.values())
        assert session.map_source.data["level"] == ["coarse"]
    coarse = shared.paper_views()[0]
    expected = app.Session._map_data(coarse, 0)["image"][0]
    np.testing.assert_array_equal(sessions[0].map_source.data["image"][0], expected)
    sessions[0]._connected(None)  # the page connects: its full map follows (the stub
    settle(sessions[0])  # returns nothing, so the stages stop there)
    assert computed == [("map_level", "full")]  # the coarse map and Fig. 9 are shown


def test_sessions_are_bounded_and_a_page_beyond_them_says_so(shared, monkeypatch):
    monkeypatch.setattr(shared, "max_sessions", 2)
    monkeypatch.setattr(shared, "sessions", 0)
    docs = [Document(connects=False) for _ in range(3)]
    for doc in docs:
        app.make_document(shared, doc)
    assert shared.sessions == 2
    (busy,) = docs[2].roots
    assert busy.name == "explore-busy" and "serves 2 sessions at once" in busy.text
    docs[0].destroy()  # Bokeh drops a closed (or never connected) page's session
    assert shared.sessions == 1
    fourth = Document(connects=False)
    app.make_document(shared, fourth)
    assert shared.sessions == 2 and fourth.roots[0].name != "explore-busy"


def test_a_value_out_of_bounds_is_refused_and_the_old_kept(shared):
    session = app.Session(shared, Document())
    settle(session)
    before = session.generation["all"]
    session.widgets["model.M2"].value = "-1.0"
    assert session.widgets["model.M2"].value == "0.3"
    assert "M2: -1 is outside" in session.error.text and "kept 0.3" in session.error.text
    assert session.generation["all"] == before  # nothing recomputed


def test_initial_angles_more_than_a_turn_before_the_hit_are_refused(shared):
    """Fig. 9's theta0 at 300 deg with delta0 52.5 deg: each within its bounds, but the
    racket would pass phi = 360 deg and hit a turn later; refused by the workflow's rule
    of the initial angles, the old value kept (issue 66, case 2)."""
    session = app.Session(shared, Document())
    settle(session)
    before = session.generation["all"]
    session.widgets["torque_delay.theta0"].value = "300"
    assert session.widgets["torque_delay.theta0"].value == "90"
    assert "initial angles theta0 + delta0 must be &lt; 360 degree" in session.error.text
    assert session.generation["all"] == before  # nothing recomputed


def test_failed_strokes_show_as_failed_never_as_numbers(shared):
    session = app.Session(shared, Document())
    settle(session)
    session.widgets["model.C1"].value = "-25"  # the elbow torque backwards
    settle(session)
    data = session.map_source.data
    failed = data["status"][0] != 0
    assert failed.any()
    assert np.isnan(data["image"][0][failed]).all()
    assert np.isfinite(data["image"][0][~failed]).all()


def test_a_failing_stage_is_one_line_and_the_next_change_computes(shared, monkeypatch):
    session = app.Session(shared, Document())
    settle(session)

    def broken(*args, **kwargs):
        raise RuntimeError("the solver broke\nsecond line")

    with monkeypatch.context() as m:
        m.setattr(compute, "fig9_curve", broken)
        session.widgets["model.M2"].value = "0.4"
        settle(session)
    assert session.error.text == "RuntimeError: the solver broke"
    assert session.map_source.data["level"] == ["coarse"]  # the stage before it was shown
    session.widgets["model.M2"].value = "0.41"
    settle(session)
    assert session.error.text == "" and session.map_source.data["level"] == ["full"]


def test_ten_rapid_changes_compute_the_last_and_pile_up_nothing(shared, monkeypatch):
    session = app.Session(shared, Document())
    settle(session)
    computed = []
    real = compute.map_level
    burst = threading.Event()

    def counted(config, figure, level, stale=lambda: False, threads=None):
        computed.append((config["model"]["M2"], level))
        burst.wait(10)  # slower than the changes arrive, however loaded the machine
        return real(config, figure, level, stale, threads)

    monkeypatch.setattr(compute, "map_level", counted)
    threads = threading.active_count()
    for n in range(10):
        session.widgets["model.M2"].value = f"{0.31 + 0.01 * n:.2f}"
    assert sum(session._queued.values()) <= 1  # one request waits, whatever the burst
    burst.set()
    settle(session)
    assert threading.active_count() <= threads + 1
    assert session.map_source.data["generation"] == [session.generation["all"]]
    assert computed[-2:] == [(0.4, "coarse"), (0.4, "full")]
    assert len(computed) <= 4  # the first (maybe) and the last: no stale setting's map


def test_reset_returns_every_control_to_the_default_reading(shared):
    session = app.Session(shared, Document())
    settle(session)
    session.widgets["model.M2"].value = "0.35"
    session.widgets["model.inertia"].value = "paper_text"
    session.widgets["solver.rtol"].value = "1e-06"
    settle(session)
    session._reset()
    settle(session)
    for control in session.controls:
        assert session.widgets[control.key].value == (
            control.paper if control.choices else controls.number_text(control.paper)
        )
    assert controls.overrides(shared.config, session.values) == {}


def test_a_picked_point_plays_its_stroke(shared):
    session = app.Session(shared, Document())
    settle(session)

    class Tap:
        x, y = 111.1, 12.4

    session._tap(Tap)
    settle(session)
    assert session.picked == (111.0, 12.5)  # the nearest point of the full grid
    view = session.stroke_box.children[0]
    assert view.name == "explore-stroke"
    now = view.select_one({"name": "explore-stroke-now"})
    assert now.data["label"] == ["theta0 111, delta0 12.5 deg"]


def test_saving_the_settings_declares_a_scenario(shared):
    session = app.Session(shared, Document())
    settle(session)
    session.widgets["model.M2"].value = "0.35"
    session.scenario_name.value = "from_the_explorer"
    session._save()
    assert "saved scenario <code>from_the_explorer</code>" in session.saved.text
    text = shared.scenarios.read_text()
    assert text.startswith("# scenarios\n") and "from_the_explorer:" in text
    session._save()
    assert session.saved.text.startswith("not saved: scenario 'from_the_explorer' is already")


def test_saving_the_paper_s_setting_is_refused_in_the_page(shared):
    """Save at the defaults appended ``good-one: {}`` (issue 56, 9): refused as whatif
    and the workflow's planning refuse it, the file as it was."""
    session = app.Session(shared, Document())
    settle(session)
    before = shared.scenarios.read_text()
    session.scenario_name.value = "good-one"
    session._save()
    assert session.saved.text == (
        "not saved: scenario 'good-one' changes nothing of the paper's configuration "
        "(each override is the value it has, or a model value's default)"
    )
    assert shared.scenarios.read_text() == before


def test_a_second_pick_shows_its_stroke_in_the_same_view(shared):
    session = app.Session(shared, Document())
    settle(session)

    class First:
        x, y = 110.0, 11.0

    class Second:
        x, y = 112.0, 14.0

    session._tap(First)
    settle(session)
    view = session.stroke
    session._tap(Second)
    settle(session)
    assert session.stroke is view and session.stroke_box.children == [view]
    expected = compute.stroke_at(session._config(), "fig2", 112.0, 14.0)
    now = view.select_one({"name": "explore-stroke-now"})
    assert now.data["label"] == ["theta0 112, delta0 14 deg"]
    info = view.select_one({"name": "explore-stroke-info"}).data
    assert info["t_contact_start"] == [float(expected["t_contact_start"].values[0])]
    curves = view.select_one({"name": "explore-stroke-curves"}).data
    np.testing.assert_array_equal(
        curves["omega2_0"], expected["omega2"].values[0].astype(np.float32)
    )
    plane = view.select_one({"name": "explore-stroke-plane"})
    assert plane.title.text.startswith("The stroke at theta0 = 112, delta0 = 14 deg")


def test_a_value_the_widgets_do_not_offer_is_refused_on_the_server(shared):
    """A page can send any value: a choice that is not one of the control's (rtol
    '1e-300' was computed), a NaN or an out-of-bounds number; each
    is refused with its reason, escaped, the old value kept, nothing recomputed; the
    next valid change clears the line."""
    session = app.Session(shared, Document())
    settle(session)
    before = session.generation["all"]
    choice = next(c for c in session.controls if c.choices)
    number = next(c for c in session.controls if not c.choices and c.key == "model.M2")
    cases = [
        (choice, "1e-300", "is not one of"),
        (choice, "<img src=x onerror=alert(1)>", "&lt;img src=x onerror=alert(1)&gt;"),
        (number, "nan", "is not a number"),
        (number, "inf", "is not a number"),
        (number, "1e400", "is not a finite number"),
        (number, "-1", "is outside"),
        (number, "<img src=x onerror=alert(1)>", "&lt;img src=x onerror=alert(1)&gt;"),
    ]
    for control, value, words in cases:
        kept = session.widgets[control.key].value
        session.widgets[control.key].value = value
        assert session.widgets[control.key].value == kept, (control.key, value)
        assert words in session.error.text and "<img" not in session.error.text, value
    assert session.generation["all"] == before  # nothing recomputed
    session.widgets["model.M2"].value = "0.31"
    assert session.error.text == ""


def test_text_from_a_user_is_escaped_in_the_page(shared, monkeypatch):
    """A saved scenario's name and an error's words go into Divs (HTML) escaped."""
    session = app.Session(shared, Document())
    settle(session)
    session.scenario_name.value = "<script>alert(1)</script>"
    session._save()
    assert "<script>" not in session.saved.text and "&lt;script&gt;" in session.saved.text
    session._show_error("ValueError: <b>bold</b>")
    assert session.error.text == "ValueError: &lt;b&gt;bold&lt;/b&gt;"


@pytest.mark.parametrize(
    "text, value",
    [
        ("4000", 4000.0),
        (" 0.35 ", 0.35),
        ("0,35", 0.35),
        (".5", 0.5),
        ("3.", 3.0),
        ("1e-5", 1e-5),
        ("2.5E3", 2500.0),
        ("-10", -10.0),
        ("\u221210.5", -10.5),
        ("+7", 7.0),
    ],
)
def test_a_number_is_read_as_a_person_types_it(text, value):
    assert controls.read_number(text) == value


@pytest.mark.parametrize(
    "text, words",
    [
        ("", "no value"),
        ("78004000x", "is not a number"),
        ("0.3.5", "is not a number"),
        ("1_000", "is not a number"),
        ("7,800", "ambiguous"),
        ("1,5,0", "is not a number"),
        ("nan", "is not a number"),
        ("1e999", "is not a finite number"),
        ("0x10", "is not a number"),
    ],
)
def test_what_is_not_a_number_is_named(text, words):
    with pytest.raises(ValueError, match=words):
        controls.read_number(text)


def test_a_field_computes_with_the_value_typed_and_never_rewrites_it(shared, monkeypatch):
    """The field's text is what the server computes with: '0,35' computes at 0.35 and
    the field keeps '0,35' (the page echoed each keystroke back reformatted, and
    '78004000' was computed when '4000' was typed over a selection)."""
    session = app.Session(shared, Document())
    settle(session)
    seen = []
    real = compute.map_level
    monkeypatch.setattr(
        compute,
        "map_level",
        lambda config, *a, **k: seen.append(config["model"]["M2"]) or real(config, *a, **k),
    )
    session.widgets["model.M2"].value = "0,35"
    settle(session)
    assert session.widgets["model.M2"].value == "0,35" and session.values["model.M2"] == 0.35
    assert set(seen) == {0.35} and session.error.text == ""
    session.widgets["model.M2"].value = "0.3x"
    assert session.widgets["model.M2"].value == "0.35" and "'0.3x' is not a number" in (
        session.error.text
    )


def test_the_page_names_the_values_it_computed_with(shared):
    session = app.Session(shared, Document())
    settle(session)
    assert session.setting.text == "computed with the paper's setting"
    session.widgets["model.M2"].value = "0,35"
    session.widgets["model.k_contact"].value = "4e3"
    settle(session)
    assert session.setting.text == "computed with M2 = 0.35 kg; k_contact = 4000 N/m"


#: Values a page can type into a number field beyond what a person means (issue 56, 8:
#: 1e30 and 2**63 gave a traceback on the server and kept the field's value).
HOSTILE_TEXTS = ["1e30", "-1e-320"]


def test_every_control_refuses_or_computes_any_value_a_page_can_send(shared, monkeypatch):
    """Every control (number fields and selects) given values no widget offers: each is
    refused (the error line, the control shown at its value again, nothing changed) or
    computed (no error: the maps and Fig. 9's curve; the claims' stage is left out here
    for time, its failures are one line, test_a_failing_stage_is_one_line...)."""
    session = app.Session(shared, Document())
    settle(session)
    first = session._claims_data(None)
    monkeypatch.setattr(compute, "claims_table", lambda *a, **k: first)
    for control in session.controls:
        texts = ["1e-300", "nan", "", "__proto__"] if control.choices else HOSTILE_TEXTS
        for text in texts:
            widget = session.widgets[control.key]
            kept, values = widget.value, dict(session.values)
            widget.value = text
            settle(session)
            if widget.value == kept and text != kept:  # refused
                assert session.values == values, (control.key, text)
                assert session.error.text or text == "", (control.key, text)
                continue
            assert session.error.text == "", (control.key, text, session.error.text)
            assert not session.status.text.startswith("failed"), (control.key, text)
            widget.value = kept  # back to a value that computes
            settle(session)
            assert session.error.text == "", (control.key, kept)


def test_a_value_the_control_passes_and_the_workflow_refuses_is_refused_and_kept_out(
    shared, monkeypatch
):
    """A value is checked with the whole setting, as the workflow checks a scenario,
    before it is taken: with a control's own check missing one (stood in for here), the
    worker failed on it, and every later change failed too, as the value stayed."""
    session = app.Session(shared, Document())
    settle(session)
    monkeypatch.setattr(controls, "refusal", lambda control, value: None)
    session.widgets["model.M2"].value = "-1"
    assert session.widgets["model.M2"].value == "0.3" and session.values["model.M2"] == 0.3
    assert session.error.text == (
        "M2: config key 'model': parameter 'M2' must be &gt; 0 kg, got -1; kept 0.3"
    )
    session.widgets["model.M2"].value = "0.31"
    settle(session)
    assert session.error.text == "" and session.values["model.M2"] == 0.31


def _patch(model, attr, value):
    """A page's change of ``model.attr`` to ``value``, as Bokeh's websocket carries it."""
    event = {"kind": "ModelChanged", "model": {"id": model.id}, "attr": attr, "new": value}
    return {"events": [event]}


@pytest.mark.parametrize(
    "value", [1e30, 2**63, -(2**63) - 1, True, None, [0.3], {"a": 1}, 0.35], ids=repr
)
def test_a_value_of_the_wrong_type_from_the_page_is_refused_in_the_page(shared, value):
    """A page sends any JSON value: Bokeh refused one of the wrong type for a field
    before any callback ran (a traceback in the server's log, nothing on the page, the
    page's widget keeping it).  Now the refusal is the error line and every field is sent
    to the page again at its value; a server-side Bokeh document applies the patch."""
    from bokeh.document import Document as BokehDocument

    doc = BokehDocument()
    session = app.Session(shared, doc)
    sent = []
    doc.on_change(lambda event: sent.append(event))
    for widget in (
        session.widgets["model.M2"],
        session.widgets["solver.method"],
        session.scenario_name,
    ):
        kept, values = widget.value, dict(session.values)
        sent.clear()
        doc.apply_json_patch(_patch(widget, "value", value), setter=None)
        assert widget.value == kept and session.values == values
        # refused by Bokeh (a text field's value is a string) or by the control's check
        # (a select takes any value from the page)
        said = session.error.text
        assert said.startswith("refused: ValueError: failed to validate") or (
            said.startswith("method: ") and said.endswith("; kept DOP853")
        ), said
        assert any(getattr(e, "model", None) is widget and e.attr == "value" for e in sent)
        session.error.text = ""
    doc.apply_json_patch(_patch(session.widgets["model.M2"], "value", "0.31"), setter=None)
    assert session.values["model.M2"] == 0.31


@pytest.mark.parametrize(
    "x, y",
    [(float("nan"), 11.0), (1e308, 11.0), (110.0, -1e308), (float("inf"), 11.0), (500.0, 11.0)],
)
def test_a_tap_off_the_map_is_refused_in_one_line(shared, x, y):
    session = app.Session(shared, Document())
    settle(session)

    class Event:
        pass

    Event.x, Event.y = x, y
    before = session.generation["stroke"]
    session._tap(Event)
    assert session.error.text.startswith("a tap at (") and "is not on the map" in session.error.text
    assert session.generation["stroke"] == before and session.picked is None


def test_a_tap_reads_the_grid_the_server_drew_not_the_page_s_data(shared):
    """A page can send new data for the map's source (a zero step divided by zero)."""
    session = app.Session(shared, Document())
    settle(session)
    session.map_source.data = {**session.map_source.data, "dx": [0.0], "x0": [float("nan")]}

    class Event:
        x, y = 111.0, 12.0

    session._tap(Event)
    assert session.picked == (111.0, 12.0) and session.error.text == ""
    settle(session)


@pytest.mark.parametrize(
    "what, refusal",
    [
        ("temporary_beside", PermissionError(1, "Operation not permitted")),  # immutable
        ("replace", OSError(28, "No space left on device")),  # the rename of a full disk
    ],
)
def test_a_save_the_system_will_not_write_is_one_line_on_the_page_and_in_the_log(
    shared, monkeypatch, capsys, what, refusal
):
    """Was: a PermissionError inside the handler (config/ immutable, append-only), nothing
    on the page, nothing in the log, nothing saved (issue 66, case 5).  As root, a mode
    does not stop a write: the system's refusal is made here."""
    from tennis_stroke.pipeline import scenarios

    def refuse(*args, **kwargs):
        raise refusal

    session = app.Session(shared, Document())
    settle(session)
    before = shared.scenarios.read_text()
    session.widgets["model.M2"].value = "0.35"
    session.scenario_name.value = "kept_out"
    target = scenarios if what == "temporary_beside" else scenarios.os
    monkeypatch.setattr(target, what, refuse)
    session._save()
    monkeypatch.undo()
    line = f"not saved: {shared.scenarios}: cannot be written ({refusal.strerror}): not saved"
    assert session.saved.text == line
    assert capsys.readouterr().err == f"tennis-stroke explore: {line}\n"
    assert shared.scenarios.read_text() == before
    assert [p.name for p in shared.scenarios.parent.iterdir() if p.suffix == ".tmp"] == []
