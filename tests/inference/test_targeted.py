"""The targeted evaluation (tennis_stroke.inference.targeted): the same measurements on
searched files answer what they answer on the maps, and it reads no map step."""

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke.experiments import maps, strokes
from tennis_stroke.experiments.grids import axis
from tennis_stroke.experiments.specs import EXPERIMENTS
from tennis_stroke.inference import measures as ms
from tennis_stroke.inference import search_plan
from tennis_stroke.inference import targeted as tg
from tennis_stroke.pipeline.config_check import load_schema, with_defaults
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import rhs_evaluations

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
SETTINGS = SolverSettings(**CONFIG["solver"])
SEARCH = CONFIG["search"]


def args(key, config=CONFIG):
    return EXPERIMENTS[key].arguments(config)


def test_angle_rows_find_the_red_line_of_a_dense_map():
    a = args("fig2")
    a["theta0"] = {"start": 60.0, "stop": 120.0, "step": 30.0}
    found = tg.angle_rows(a, SEARCH, [{}], SETTINGS)[0]
    dense = maps.angle_map(
        axis(a["theta0"]), np.arange(0.0, 100.01, 0.1), {"L1": a["L1"]}, SETTINGS
    )
    # the dense map's parabola-refined optimum, 0.1 deg apart: the same within 0.02 deg
    assert np.max(np.abs(found["best_delta0"] - dense["best_delta0"])) < 0.02
    assert ms.measure_best_delta0(found, 120.0) == pytest.approx(
        ms.measure_best_delta0(dense, 120.0), abs=0.02
    )


def test_the_threshold_is_bracketed_to_its_tolerance_and_agrees_with_the_map():
    a = args("fig7")
    a["C2"] = {"start": 0.0, "stop": 4.0, "step": 0.05}
    a["tau"] = {"start": 0.0, "stop": 0.3, "step": 0.005}
    found = tg.delay_threshold(a, SEARCH, [{}], SETTINGS)[0]
    half = 0.5 * 0.005
    c2, best = found["C2"].values, found["best_tau"].values
    threshold = ms.measure_delay_threshold(found)
    below, above = c2[c2 < threshold], c2[c2 > threshold]
    assert above[0] - below[-1] <= SEARCH["C2_tolerance"] + 1e-12
    assert np.all(best[(c2 > 0) & (c2 < threshold)] <= half)  # tau stays 0 below
    assert np.all(best[c2 > threshold] > half)
    grid = maps.torque_delay_section(
        a["L1"], a["theta0"], a["C2"], a["delta0"], a["tau"], {}, SETTINGS
    )
    # the map's threshold is a midpoint between its C2 rows: within half their step
    assert abs(ms.measure_delay_threshold(grid) - threshold) <= 0.025 + 1e-9
    assert ms.measure_below_threshold_tau_zero(found) == 1.0


def test_the_optima_of_figs_8_9_and_13_are_no_worse_than_any_grid_point():
    fig9 = tg.delay_line(args("fig9"), SEARCH, [{}], SETTINGS)[0]
    a9 = args("fig9")
    line = maps.torque_delay_section(
        a9["L1"], a9["theta0"], a9["C2"], a9["delta0"], a9["tau"], {}, SETTINGS
    )
    assert float(fig9["best_v_out"][0]) >= float(ms.valid_v_out(line).max()) - 1e-6
    assert ms.measure_fig9(fig9, "v_L") == ms.measure_fig9(line, "v_L")  # the same stroke
    a13 = copy.deepcopy(args("elbow_map"))
    a13["psi_f"] = {"start": 0.0, "stop": 360.0, "step": 20.0}
    a13["tau_f"] = {"start": -0.1, "stop": 0.1, "step": 0.05}
    found = tg.elbow_extremes(a13, SEARCH, [{}], SETTINGS)[0]
    grid = maps.elbow_force_section_map(
        a13["force"], a13["psi_f"], a13["tau_f"], a13["stroke"], {}, SETTINGS
    )
    v = ms.valid_v_out(grid)
    assert float(found["v_out"].max()) >= float(v.max()) - 1e-6
    assert float(found["v_out"].min()) <= float(v.min()) + 1e-6
    assert 0.0 <= ms.measure_minimum(found, "psi_F") < 360.0  # a direction, wrapped


def test_table1_numbers_are_the_strokes_of_the_workflow():
    a = args("elbow", {**CONFIG, "figure_curves": "free_swing"})
    found = tg.table1_numbers(a, {}, SETTINGS)
    whole = strokes.elbow_force_strokes(a["force"], a["stroke"], {}, SETTINGS)
    for name in ("v_out", "omega2_phi0", "omega2_contact", "t_contact_start"):
        assert np.array_equal(found[name].values, whole[name].values), name


def test_the_targeted_evaluation_reads_no_map_step():
    """targeted_config drops exactly the steps of UNREAD_STEPS, and changing one of them
    changes no targeted value (so the jobs that run it need not rerun)."""
    stripped = search_plan.targeted_config(CONFIG)
    for key in search_plan.UNREAD_STEPS:
        node = stripped
        for part in key.split("."):
            node = node[part]
        assert "step" not in node and {"start", "stop"} <= set(node)
    assert stripped["angle_maps"]["theta0"] == CONFIG["angle_maps"]["theta0"]
    assert stripped["torque_delay"]["fig7"]["tau"] == CONFIG["torque_delay"]["fig7"]["tau"]
    finer = copy.deepcopy(CONFIG)
    finer["torque_delay"]["fig9"]["tau"]["step"] = 0.001
    a, b = (tg.delay_line(args("fig9", c), SEARCH, [{}], SETTINGS)[0] for c in (CONFIG, finer))
    assert a.equals(b)
    assert tg.delay_line(args("fig9", stripped), SEARCH, [{}], SETTINGS)[0].equals(a)


def test_readings_searched_in_lockstep_get_the_files_each_gets_alone():
    """Three readings (discrete and continuous unknowns, Figs. 5-6's largest L1) searched
    together by searched_files_of: every file of every reading bit for bit the one
    searched_files gives that reading alone (the robustness analysis' proof, on the tiny
    grids; docs/inference.md, "Every reading's search in lockstep"); and so with the
    robustness chunk's memo, which runs fewer strokes."""
    from conftest import assert_same_results
    from tiny import TINY

    config = copy.deepcopy(TINY)
    config.update(with_defaults(config, load_schema(ROOT / "workflow/schemas/config.schema.yaml")))
    models = [
        {"k_contact": 7800.0, "ball_mass": 0.058, "inertia": "uniform_rod"},
        {
            "k_contact": 300.0,
            "ball_mass": 0.057,
            "inertia": "paper_text",
            "contact_lead_rule": "half_period",
            "collision_coupling": "paper_eq8",
        },
        {
            "k_contact": 15000.0,
            "ball_mass": 0.059,
            "inertia": "uniform_rod",
            "contact_lead_rule": "zero",
            "collision_coupling": "newton",
        },
    ]
    for m in models:  # every reading names every unknown, as experiment_config gives them
        m.setdefault("contact_lead_rule", "quarter_period")
        m.setdefault("collision_coupling", "newton")
    l1_max = [None, 0.2, 0.5]
    together = tg.searched_files_of([config] * 3, models, SETTINGS, l1_max)
    for model, top, files in zip(models, l1_max, together, strict=True):
        alone = tg.searched_files(config, model, SETTINGS, top)
        assert files.keys() == alone.keys() == set(search_plan.SEARCHED)
        for key in alone:
            assert_same_results(files[key], alone[key])
    # the readings differ, so the lockstep did not give every reading one answer
    assert not together[0]["fig9"]["best_v_out"].equals(together[1]["fig9"]["best_v_out"])
    # the robustness chunk's searches run no stroke twice: the same files (the strokes
    # asked for and failed counted alike), fewer strokes run
    before = rhs_evaluations()
    remembered = tg.searched_files_of([config] * 3, models, SETTINGS, l1_max, memo=True)
    run = rhs_evaluations() - before
    for files, memo in zip(together, remembered, strict=True):
        for key in files:
            assert_same_results(memo[key], files[key])
    before = rhs_evaluations()
    tg.searched_files_of([config] * 3, models, SETTINGS, l1_max)
    assert run < rhs_evaluations() - before


def test_the_curve_files_of_readings_at_once_are_each_reading_s_datasets():
    """curve_files_of: the curve files (Figs. 4, 10-12) of three readings (discrete and
    continuous unknowns), every stroke of every reading in one call per file, bit for
    bit each reading's own dataset (paper_results, one reading at a time) in every
    variable the stack holds, under both curves; the stack holds every variable a
    claim can read (the dataset's, less the labels and the delay's ``tau``)."""
    from tiny import TINY

    from tennis_stroke.inference.multiverse import paper_results
    from tennis_stroke.inference.reading_space import CURVE_FILES

    config = copy.deepcopy(TINY)
    config.update(with_defaults(config, load_schema(ROOT / "workflow/schemas/config.schema.yaml")))
    models = [
        {"k_contact": 7800.0, "ball_mass": 0.058},
        {"k_contact": 300.0, "inertia": "paper_text", "contact_lead_rule": "half_period"},
        {"k_contact": 15000.0, "ball_mass": 0.056, "collision_coupling": "paper_eq8"},
    ]
    stacks = tg.curve_files_of([config] * 3, models, SETTINGS, strokes.CURVES)
    assert set(stacks) == {f"{k}/{c}" for k in CURVE_FILES for c in strokes.CURVES}
    skip = [k for k in EXPERIMENTS if k not in CURVE_FILES]
    for r, model in enumerate(models):
        alone = paper_results(config, model, SETTINGS, strokes.CURVES, skip=skip)
        for key, stack in stacks.items():
            ds = alone[key]
            assert set(stack.data_vars) == set(ds.data_vars) - {"tau"}
            for name in [*stack.data_vars, "stroke", "t", "theta0", "delta0"]:
                mine, theirs = stack[name][r], ds[name].values
                assert stack.dims(name) == ds[name].dims, name
                assert mine.dtype == theirs.dtype and mine.shape == theirs.shape, name
                assert mine.tobytes() == theirs.tobytes(), (key, name)  # bit for bit
    # the readings differ, and so do their curves
    assert not np.array_equal(
        stacks["fig4/with_ball"]["omega2"][0], stacks["fig4/with_ball"]["omega2"][1]
    )


def test_the_number_files_of_readings_at_once_are_each_reading_s_files():
    """number_files_of: the k sensitivity and Table I's numbers of three readings (model
    readings, unknowns and Table I's force delay differing), each one batch for all the
    readings, bit for bit each reading's own file (the workflow's k sensitivity,
    table1_numbers) in every variable the stack holds."""
    from tiny import TINY

    config = copy.deepcopy(TINY)
    config.update(with_defaults(config, load_schema(ROOT / "workflow/schemas/config.schema.yaml")))
    models = [
        {"k_contact": 7800.0, "ball_mass": 0.058, "inertia": "uniform_rod"},
        {"k_contact": 300.0, "ball_mass": 0.057, "inertia": "paper_text"},
        {"k_contact": 15000.0, "ball_mass": 0.058, "inertia": "uniform_rod"},
    ]
    configs = [copy.deepcopy(config) for _ in models]
    for c, delay in zip(configs, (-0.03, 0.0, 0.02), strict=True):
        c["elbow_force"]["table1_tau_F"] = delay
    stacks = tg.number_files_of(configs, models, SETTINGS)
    for r, (c, model) in enumerate(zip(configs, models, strict=True)):
        k_args = EXPERIMENTS["k_sensitivity"].arguments(c)
        alone = {
            "k_sensitivity": maps.k_sensitivity_map(**k_args, params=model, settings=SETTINGS),
            "elbow": tg.table1_numbers(
                args("elbow", {**c, "figure_curves": "free_swing"}), model, SETTINGS
            ),
        }
        for key, stack in stacks.items():
            ds = alone[key]
            assert set(stack.data_vars) == set(ds.data_vars), key
            for name in [*stack.data_vars, *ds.coords]:
                mine, theirs = stack[name][r], ds[name].values
                assert stack.dims(name) == ds[name].dims, name
                assert mine.dtype == theirs.dtype and mine.shape == theirs.shape, name
                assert mine.tobytes() == theirs.tobytes(), (key, name)  # bit for bit
    for key in stacks:  # the readings differ
        assert not np.array_equal(stacks[key]["v_out"][0], stacks[key]["v_out"][1])
