"""The live explorer's computations (tennis_stroke.live.compute) and controls
(tennis_stroke.live.controls): each view at a setting is what the solver and the claims
job give at that setting."""

import numpy as np
import pandas as pd
import pytest
import yaml
from conftest import ROOT

from tennis_stroke.experiments.grids import axis
from tennis_stroke.experiments.specs import merged
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.io.config_files import load_yaml
from tennis_stroke.live import compute, controls
from tennis_stroke.model.params import (
    INITIAL_ANGLES,
    PARAMETERS,
    ParameterError,
    resolve_params,
)
from tennis_stroke.pipeline.scenarios import (
    ScenarioError,
    load_scenarios,
    save_scenario,
    scenario_config,
)
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import strike_batch

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"


@pytest.fixture(scope="module")
def paper():
    return load_yaml(ROOT / "config" / "config.yaml")


@pytest.fixture(scope="module")
def small(paper):
    """The paper's configuration with a map range a few cells wide (the explorer's steps)."""
    return merged(
        paper,
        {
            "angle_maps": {
                "theta0": {"start": 100.0, "stop": 102.0, "step": 0.25},
                "delta0": {"start": 20.0, "stop": 23.0, "step": 0.25},
            },
            "torque_delay": {"fig9": {"tau": {"start": 0.0, "stop": 0.2, "step": 0.05}}},
        },
    )


@pytest.mark.parametrize("level", ["coarse", "full"])
@pytest.mark.parametrize("figure", ["fig2", "fig3"])
def test_a_map_level_is_each_stroke_at_its_grid_point(small, level, figure):
    values = {"model.M2": 0.35, "model.inertia": "paper_text", "angle_maps.L1.1": 0.45}
    config = controls.configuration(small, values)
    ds = compute.map_level(config, figure, level)
    step_theta, step_delta = compute.LEVELS[level]
    theta = np.arange(100.0, 102.0 + 1e-9, step_theta)
    delta = np.arange(20.0, 23.0 + 1e-9, step_delta)
    np.testing.assert_array_equal(ds["theta0"], theta)
    np.testing.assert_array_equal(ds["delta0"], delta)
    l1 = 0.3 if figure == "fig2" else 0.45
    expected = strike_batch(
        theta[:, None], delta[None, :], {"M2": 0.35, "inertia": "paper_text", "L1": l1}
    )
    np.testing.assert_array_equal(ds["v_out"].values, expected["v_out_kmh"])
    np.testing.assert_array_equal(ds["status"].values, expected["status"])
    assert compute.map_shape(config, figure, level) == (theta.size, delta.size)


def test_the_paper_maps_are_121_by_101_and_241_by_201(paper):
    assert compute.map_shape(paper, "fig2", "coarse") == (121, 101)
    assert compute.map_shape(paper, "fig2", "full") == (241, 201)


def test_a_stale_map_stops_between_blocks(small):
    calls = []

    def stale():
        calls.append(1)
        return len(calls) > 1  # a newer setting arrives after the first block

    assert compute.map_level(small, "fig2", "full", stale) is None
    assert len(calls) == 2


def test_the_fig9_curve_is_each_delay_s_stroke(small):
    config = controls.configuration(small, {"torque_delay.base_stroke.C2": 6.0, "model.M2": 0.4})
    ds = compute.fig9_curve(config)
    tau = axis(small["torque_delay"]["fig9"]["tau"])
    expected = strike_batch(90.0, 52.5, {"M2": 0.4, "L1": 0.4, "C2": 6.0, "tau": tau})
    np.testing.assert_array_equal(ds["tau"], tau)
    np.testing.assert_array_equal(ds["v_out"].values, expected["v_out_kmh"])


def test_a_picked_stroke_has_the_stroke_s_numbers(small):
    config = controls.configuration(small, {"model.M2": 0.35})
    ds = compute.stroke_at(config, "fig2", 101.0, 21.5)
    expected = strike_batch(101.0, 21.5, {"M2": 0.35, "L1": 0.3})
    assert ds.sizes["stroke"] == 1
    assert ds["v_out"].values[0] == expected["v_out_kmh"]
    assert {"x_wrist", "y_racket", "omega2", "kinetic_energy"} <= set(ds.data_vars)


def test_the_overrides_hold_only_what_differs_from_the_paper(paper):
    values = {c.key: c.paper for c in controls.controls(paper, "fig3")}
    assert controls.overrides(paper, values) == {}
    values |= {"model.M2": 0.35, "solver.rtol": "1e-06", "angle_maps.L1.1": 0.5}
    assert controls.overrides(paper, values) == {
        "model": {"M2": 0.35},
        "solver": {"rtol": 1e-6, "atol": 1e-6},
        "angle_maps": {"L1": [0.3, 0.5]},
    }


def test_every_model_parameter_has_a_control_with_its_bounds(paper):
    by_key = {c.key: c for c in controls.controls(paper, "fig2")}
    for name, spec in PARAMETERS.items():
        if spec.derived:
            assert f"model.{name}" not in by_key  # derived: the reading sets it
            continue
        key = "angle_maps.L1.0" if name == "L1" else f"model.{name}"
        control = by_key[key]
        assert control.paper == spec.default or name == "L1"
        if spec.lower is not None:
            assert control.low >= spec.lower
            resolve_params({name: control.low})  # the lowest value it takes is valid
            if spec.strict:
                assert control.low > spec.lower
                with pytest.raises(ParameterError):
                    resolve_params({name: spec.lower})
        if spec.upper is not None:
            assert control.high == spec.upper
    for name in INITIAL_ANGLES:  # Fig. 9's initial angles: the table's bounds (issue 66)
        key = "torque_delay.theta0" if name == "theta0" else "torque_delay.base_stroke.delta0"
        spec = INITIAL_ANGLES[name]
        assert (by_key[key].low, by_key[key].high, by_key[key].unit) == (
            spec.lower,
            spec.upper,
            spec.unit,
        )
    assert by_key["model.inertia"].choices == ("uniform_rod", "paper_text")
    assert set(by_key["solver.method"].choices) == {"DOP853", "DP54"}
    for tolerance in by_key["solver.rtol"].choices:
        SolverSettings(rtol=float(tolerance), atol=float(tolerance))


def test_the_claims_are_the_claims_job_s_at_the_same_configuration(tiny_run):
    """The tiny run's claims job against the explorer's claims at its configuration."""
    shipped = load_yaml(ROOT / "config" / "config.yaml")  # the defaults the run's omits
    config = merged(shipped, load_yaml(tiny_run / "config" / "config.yaml"))
    claims, space = claims_and_readings(
        tiny_run / "config" / "claims.yaml", tiny_run / "config" / "readings.yaml"
    )
    shown = compute.view_claims(claims)
    assert {c["id"] for c in shown} >= {"fig2_best_delta0_at_120", "fig9_v_H", "fig9_tau_H"}
    table = compute.claims_table(config, shown, space.fit_of_claim())
    job = pd.read_csv(tiny_run / "results" / "claims.csv").set_index("id")
    for row in table.itertuples():
        assert row.reproduced_value == pytest.approx(job.loc[row.id, "reproduced_value"])
        assert row.status == job.loc[row.id, "status"]


def test_a_saved_scenario_is_declared_with_the_file_s_comments_kept(paper, tmp_path):
    path = tmp_path / "scenarios.yaml"
    path.write_text("# my scenarios\nheavy: {model: {M2: 0.35}}   # kg\n")
    overrides = {"model": {"M2": 0.4, "inertia": "paper_text"}, "angle_maps": {"L1": [0.3, 0.5]}}
    save_scenario(path, "found_live", overrides, paper, SCHEMA)
    text = path.read_text()
    assert text.startswith("# my scenarios\nheavy: {model: {M2: 0.35}}   # kg\n")
    assert load_scenarios(path)["found_live"] == overrides
    scenario_config(paper, "found_live", load_scenarios(path)["found_live"], SCHEMA)
    assert yaml.safe_load(text)["heavy"] == {"model": {"M2": 0.35}}


@pytest.mark.parametrize(
    ("name", "overrides", "message"),
    [
        ("heavy", {"model": {"M2": 0.4}}, "already declared"),
        ("bad name", {"model": {"M2": 0.4}}, "a letter, then letters"),
        ("a" + "x" * 20, {"model": {"M2": 0.4}}, "repeated 20 times"),
        ("negative", {"model": {"M2": -1.0}}, "must be > 0"),
        # Save at the defaults appended `good-one: {}`, whose page planned jobs
        ("good-one", {}, "changes nothing of the paper's configuration"),
        ("good-one", {"model": {"M2": 0.3}, "solver": {"rtol": 5e-8}}, "changes nothing"),
    ],
)
def test_a_refused_scenario_leaves_the_file_as_it_was(paper, tmp_path, name, overrides, message):
    path = tmp_path / "scenarios.yaml"
    path.write_text("heavy: {model: {M2: 0.35}}\n")
    with pytest.raises(ScenarioError, match=message):
        save_scenario(path, name, overrides, paper, SCHEMA)
    assert path.read_text() == "heavy: {model: {M2: 0.35}}\n"
    assert [p.name for p in tmp_path.iterdir()] == ["scenarios.yaml"]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{a: {model: {M2: 0.35}}}\n", "would not read back"),  # a flow-style mapping
        ("a: {model: {M2: 0.35}}\n...\n", "would not read back"),  # a document end
    ],
    ids=["flow-style", "document-end"],
)
def test_a_file_an_appended_scenario_would_break_is_kept(paper, tmp_path, text, message):
    """Saving reported success and left the file unreadable, which disabled every
    scenario; now the new text is read back before it replaces the old."""
    path = tmp_path / "scenarios.yaml"
    path.write_text(text)
    with pytest.raises(ScenarioError, match=message):
        save_scenario(path, "b", {"model": {"M2": 0.4}}, paper, SCHEMA)
    assert path.read_text() == text and load_scenarios(path) == {"a": {"model": {"M2": 0.35}}}
    assert [p.name for p in tmp_path.iterdir()] == ["scenarios.yaml"]


def test_saving_keeps_a_link_a_link_and_the_file_s_mode_and_refuses_a_read_only_one(
    paper, tmp_path
):
    real = tmp_path / "kept" / "scenarios.yaml"
    real.parent.mkdir()
    real.write_text("a: {model: {M2: 0.35}}\n")
    real.chmod(0o640)
    link = tmp_path / "scenarios.yaml"
    link.symlink_to(real)
    save_scenario(link, "b", {"model": {"M2": 0.4}}, paper, SCHEMA)
    assert link.is_symlink() and set(load_scenarios(real)) == {"a", "b"}
    assert real.stat().st_mode & 0o777 == 0o640
    real.chmod(0o444)  # read-only by its mode (root could write it all the same)
    with pytest.raises(ScenarioError, match="read-only: not saved"):
        save_scenario(link, "c", {"model": {"M2": 0.45}}, paper, SCHEMA)
    assert set(load_scenarios(real)) == {"a", "b"} and real.stat().st_mode & 0o777 == 0o444


def test_two_savers_of_one_name_at_once_save_it_once(paper, tmp_path):
    """Two explorer servers saving the same name: one saves, the other is refused (a
    duplicate key made every later save, and every scenario, fail)."""
    import threading

    path = tmp_path / "scenarios.yaml"
    path.write_text("# mine\n")
    outcomes, start = [], threading.Barrier(4)

    def save(m2):
        start.wait()
        try:
            save_scenario(path, "same", {"model": {"M2": m2}}, paper, SCHEMA)
            outcomes.append("saved")
        except ScenarioError as exc:
            outcomes.append(str(exc))

    # 0.31 ...: none is the default M2 (a scenario that changes nothing is refused)
    threads = [threading.Thread(target=save, args=(0.31 + i / 100,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert outcomes.count("saved") == 1, outcomes
    assert all("already declared" in o for o in outcomes if o != "saved")
    assert list(load_scenarios(path)) == ["same"] and path.read_text().startswith("# mine\n")


def test_the_report_links_each_figure_the_explorer_recomputes():
    from tennis_stroke.replication.registry import FIGURES, LIVE

    assert set(LIVE.values()) == set(compute.FIGURES)
    assert all(name in FIGURES for name in LIVE)


def test_the_command_line_offers_each_figure_the_explorer_recomputes():
    from tennis_stroke.cli import build_parser

    explore = build_parser()._subparsers._group_actions[0].choices["explore"]
    figure = next(a for a in explore._actions if a.dest == "figure")
    assert set(figure.choices) == set(compute.FIGURES)
