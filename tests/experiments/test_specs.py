"""The table of experiments (tennis_stroke.experiments.specs): every row names a function
that takes what the row gives it, reads keys the shipped config has, and splits along
one of its arguments; the workflow writes every registered result file with one rule,
an experiment's with the rule of its kind."""

import inspect
from pathlib import Path

import pytest
import yaml

from tennis_stroke.experiments.specs import (
    EXPERIMENTS,
    RESULT_FILES,
    sorted_data,
)
from tennis_stroke.io.config_files import ConfigKeyError, value_at

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
SCHEMA = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())


@pytest.mark.parametrize("key", sorted(EXPERIMENTS))
def test_every_row_calls_a_function_that_takes_what_it_gives(key):
    e = EXPERIMENTS[key]
    kwargs = dict.fromkeys(e.args)
    if e.model:
        kwargs.update(params={}, settings=None)
    if e.chunks:
        kwargs["rows"] = None
    if e.threaded:
        kwargs["threads"] = 1
    inspect.signature(e.callable()).bind(**kwargs)  # raises TypeError if not


@pytest.mark.parametrize("key", sorted(EXPERIMENTS))
def test_every_row_reads_keys_of_the_shipped_config(key):
    e = EXPERIMENTS[key]
    args = e.arguments(CONFIG)
    assert set(args) == set(e.args)
    if e.chunks:
        assert e.rows in e.args and e.row_count(args) >= 1
        assert 1 <= e.requested_chunks(CONFIG)
        if e.chunks == e.key_of(e.rows):  # one job per entry of its axis (the scenes)
            assert e.requested_chunks(CONFIG) == e.row_count(args) > 1
        else:
            assert e.chunks.split(".")[1] in SCHEMA["properties"]["chunks"]["properties"]
    value_at(CONFIG, e.section)  # the key its messages name exists
    assert e.path == RESULT_FILES[key] and e.path.startswith("results/")


def test_every_result_file_is_written_by_one_job_of_the_workflow(report_plan):
    """The registry against the workflow's rules (a dry run of ``report``): each file
    has one writer, so no two rules claim it and none is left to no rule."""
    writers = {key: report_plan.writers(path) for key, path in RESULT_FILES.items()}
    assert {key: rules for key, rules in writers.items() if len(rules) != 1} == {}


@pytest.mark.parametrize("key", sorted(EXPERIMENTS))
def test_every_row_s_file_is_made_by_the_rule_of_its_kind(key, report_plan):
    """A chunked map is gathered from the chunks of its own stem, each written by the
    chunk rule; any other row's file is written by the rule of its family (a paper
    experiment's by ``simulate``, a solver study's by ``study``)."""
    e = EXPERIMENTS[key]
    (writer,) = report_plan.writers(e.path)
    if not e.chunks:
        assert writer == ("study" if e.family == "study" else "simulate")
        return
    assert writer == "gather_map"
    (inputs,) = [i for rule, i, outputs in report_plan.jobs if e.path in outputs]
    chunks = [path for path in inputs if path.startswith("results/chunks/")]
    assert chunks and all(c.startswith(f"results/chunks/{e.stem}/") for c in chunks)
    assert {w for c in chunks for w in report_plan.writers(c)} == {"simulate_chunk"}


def test_keys_are_dotted_paths_with_list_indices():
    assert value_at(CONFIG, "angle_maps.L1.1") == CONFIG["angle_maps"]["L1"][1]
    assert value_at(CONFIG, "torque_delay.fig9.tau.step") == 0.0005
    for bad in ("angle_maps.L1.7", "angle_maps.nothing", "fig4.t_end.x"):
        with pytest.raises(ConfigKeyError, match=f"config key '{bad}' is missing"):
            value_at(CONFIG, bad)


def test_arguments_are_plain_data_in_a_fixed_order():
    """Snakemake compares params by repr: the same config gives the same text."""
    a = sorted_data({"b": (1, 2), "a": {"y": 1, "x": [3]}})
    assert a == {"a": {"x": [3], "y": 1}, "b": [1, 2]} and list(a) == ["a", "b"]
    reordered = {k: CONFIG[k] for k in reversed(list(CONFIG))}
    for e in EXPERIMENTS.values():
        assert repr(e.arguments(reordered)) == repr(e.arguments(CONFIG))


def test_memory_batches_follow_the_grids():
    a = EXPERIMENTS["fig2"].arguments(CONFIG)
    assert EXPERIMENTS["fig2"].strokes(a) == (241 * 401,)
    ml = EXPERIMENTS["ml"]
    # the search's bracket: 60-120 deg and 0-100 deg at most 10 deg apart, all points at once
    assert ml.strokes(ml.arguments(CONFIG)) == (13 * 13 * 7 * 11,)


#: A value of each parameter a row may set, other than the paper's and the tiny config's.
OTHER_VALUE = {
    "L1": 0.55,
    "M2": 0.45,
    "C2": 3.3,
    "tau": 0.05,
    "k_contact": 5000.0,
    "F0": 7.0,
    "t_d": 0.03,
    "psi_F_deg": 33.0,
    "t_F": 0.12,
}


@pytest.mark.parametrize(
    ("key", "override"),
    [
        (key, {name: OTHER_VALUE[name] for name in e.sets})
        for key, e in EXPERIMENTS.items()
        if e.sets
    ],
)
def test_a_row_that_sets_a_parameter_itself_ignores_its_override(key, override):
    """A row's ``sets`` (the model parameters its function sets at every stroke) may be
    left out of its job's model overrides only if the override indeed changes none of
    its numbers: computed on the tiny grid with and without it."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tiny import TINY

    from tennis_stroke.experiments.specs import EXPERIMENTS, compute
    from tennis_stroke.solver.settings import SolverSettings

    experiment = EXPERIMENTS[key]
    assert set(override) <= set(experiment.sets)
    for name in experiment.sets:  # the key it reads instead is one of its own
        assert experiment.reads_instead(name) in experiment.keys()
    args = experiment.arguments({"figure_curves": "free_swing", **TINY})
    plain_run = compute(experiment, args, {}, SolverSettings(), None, 1)
    overridden = compute(experiment, args, override, SolverSettings(), None, 1)
    assert plain_run.data_vars.keys() == overridden.data_vars.keys()
    for name in plain_run.data_vars:
        assert plain_run[name].equals(overridden[name]), name
