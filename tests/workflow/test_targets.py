"""The targets make report names (tennis_stroke.pipeline.targets): every result file,
figure, the claims table and the report page, each once.  Checked against what the
workflow's rules plan (a dry run of ``report``), not against the tables targets() is
built from."""

import re
from pathlib import Path

import pytest
import yaml
from conftest import ROOT

from tennis_stroke.experiments.specs import EXPERIMENTS
from tennis_stroke.pipeline.targets import targets

#: What the plan writes besides the targets: the chunks of the maps and of the
#: robustness analysis (intermediate: the gathered file is the target), and the claims
#: job's record of its configuration (written with results/claims.csv, a target, so
#: rebuilt with it).
NOT_TARGETS = re.compile(r"results/chunks/.+\.nc|results/configuration\.yaml")

#: The paper's figures, by hand from the paper (Youn, arXiv:1505.01916): Figs. 2-14;
#: Fig. 1 is the model's sketch, nothing computed.  A figure dropped from the registry
#: would drop its job from the plan without any other test noticing.
PAPER_FIGURES = range(2, 15)


def test_every_target_is_written_by_one_planned_job(report_plan):
    names = targets()
    assert len(names) == len(set(names))
    writers = {name: report_plan.writers(name) for name in names}
    assert {name: rules for name, rules in writers.items() if len(rules) != 1} == {}


def test_every_file_the_plan_writes_is_a_target_but_the_chunks(report_plan):
    """A file no target names is not rebuilt when deleted by hand while those after it
    are present (snakemake/snakemake#1978): only the intermediate chunks may be one."""
    written = {path for _, _, outputs in report_plan.jobs for path in outputs}
    assert sorted(p for p in written - set(targets()) if not NOT_TARGETS.fullmatch(p)) == []
    assert [t for t in targets() if NOT_TARGETS.fullmatch(t)] == []


def test_every_rule_but_the_scenarios_has_a_job_in_the_report(report_plan):
    """A rule whose files no target needs would be missing from the plan (the refusals of
    a name no rule makes, unknown_*, plan no job)."""
    planned = {rule for rule, _, _ in report_plan.jobs}
    scenario = re.compile(r"scenario_\w+|unknown_\w+")
    expected = {r for r in report_plan.rules if not scenario.fullmatch(r)} - {"all"}
    assert planned == expected


def test_the_report_draws_every_figure_of_the_paper(report_plan):
    drawn = [p for rule, _, outputs in report_plan.jobs if rule == "figure" for p in outputs]
    for number in PAPER_FIGURES:
        assert [p for p in drawn if p.startswith(f"results/figures/fig{number:02d}_")], number


def test_the_work_precision_study_runs_one_job_per_scene(report_plan):
    """Its scenes were one job, the workflow's longest: now each scene of the config is
    a chunk job of its own, and one gathering writes the study's file."""
    scenes = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["solver_study"]["scenes"]
    row = EXPERIMENTS["work_precision"]
    folder = f"results/chunks/{row.stem}/"
    parts = sorted(o for _, _, out in report_plan.jobs for o in out if o.startswith(folder))
    n = len(scenes)
    assert n > 1 and parts == [f"{folder}{i}-of-{n}.nc" for i in range(n)]
    assert all(report_plan.writers(p) == ["simulate_chunk"] for p in parts)
    assert report_plan.writers(row.path) == ["gather_map"]


def test_damaged_results_are_listed_and_a_results_file_is_one(tmp_path):
    from tennis_stroke.pipeline.targets import damaged_results

    (tmp_path / "results" / "chunks").mkdir(parents=True)
    (tmp_path / "results" / "chunks" / "0-of-1.nc").write_bytes(b"garbage")
    (tmp_path / "results" / "note.txt").write_text("not a result")
    found = damaged_results(tmp_path / "results")
    assert [p for p, _ in found] == [str(tmp_path / "results" / "chunks" / "0-of-1.nc")]
    (tmp_path / "plain").write_text("a file")
    assert damaged_results(tmp_path / "plain") == [
        (str(tmp_path / "plain"), "a file where the results folder should be")
    ]


def test_a_figure_job_s_code_is_its_own_drawing_and_no_other(report_plan):
    """A figure job's code inputs hold the drawing module of its registry entry and none
    of the other drawings (figures.py imports the drawing by name), so an edit of one
    drawing reruns only the figures it draws; the report job reads no drawing code."""
    from tennis_stroke.replication.registry import FIGURES

    drawings = {f.draw for f in FIGURES.values()}
    figure_jobs = 0
    for rule, inputs, outputs in report_plan.jobs:
        used = {
            Path(p).stem
            for p in inputs
            if Path(p).parent.name == "drawing" and Path(p).stem in drawings
        }
        if rule == "figure":
            (png,) = outputs
            assert used == {FIGURES[Path(png).stem].draw}, png
            figure_jobs += 1
        else:
            assert not used, rule
    assert figure_jobs == len(FIGURES)


def test_every_job_asks_for_memory_and_time_from_its_points(report_plan):
    """Every planned job declares mem_mb and runtime (a cluster enforces them); a job's
    request grows with its points: Fig. 2's map (241 x 401 strokes) asks more than Fig.
    9's delay curve (601) and than a figure (none)."""
    from tennis_stroke.pipeline.resources import asked

    asks = report_plan.resources
    assert len(asks) == len(report_plan.jobs)
    missing = [job for job, r in asks.items() if not {"mem_mb", "runtime"} <= set(r)]
    assert missing == []
    fig2 = asks["results/chunks/angle_maps/fig2/0-of-1.nc"]
    fig9 = asks["results/chunks/torque_delay/fig9/0-of-1.nc"]
    figure = asks["results/figures/fig02_angle_map.png"]
    assert int(fig2["mem_mb"]) == asked(241 * 401)["mem_mb"] > int(fig9["mem_mb"])
    assert int(fig9["mem_mb"]) > int(figure["mem_mb"]) == asked(0)["mem_mb"]


def _result(path, variables, key):
    """A small netCDF file at ``path`` holding ``variables``, its provenance naming
    experiment ``key`` (None: no provenance, as ``tennis-stroke sweep`` writes)."""
    import json

    import numpy as np
    import xarray as xr

    ds = xr.Dataset({v: ("x", np.zeros(2)) for v in variables})
    if key is not None:
        ds.attrs["config"] = json.dumps({"experiment": {"key": key}})
    path.parent.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(path, engine="netcdf4")


def test_a_row_s_file_its_job_did_not_write_is_named_at_planning(tmp_path, monkeypatch):
    """Was: ``sweep --out results/angle_maps/fig2.nc``, then the claims and figure jobs
    failed with ``KeyError: 'best_delta0'`` (issue 66, case 16)."""
    from tennis_stroke.experiments.specs import EXPERIMENTS
    from tennis_stroke.pipeline.runs import PlanningError, guard_checkout
    from tennis_stroke.pipeline.targets import foreign_results

    results = tmp_path / "results"
    fig2, fig4 = EXPERIMENTS["fig2"], EXPERIMENTS["fig4"]
    stroke_variables = [v for v in fig2.variables if v not in ("best_delta0", "best_v_out")]
    _result(tmp_path / fig2.path, stroke_variables, None)  # a sweep's
    _result(tmp_path / fig4.path, fig4.variables, "fig3")  # all its variables, another's
    _result(tmp_path / EXPERIMENTS["fig3"].path, EXPERIMENTS["fig3"].variables, "fig3")
    found = dict(foreign_results(results))
    assert sorted(found) == [str(tmp_path / fig2.path), str(tmp_path / fig4.path)]
    assert (
        "lacks the variables best_delta0, best_v_out of experiment 'fig2'"
        in found[str(tmp_path / fig2.path)]
    )
    assert "names experiment 'fig3', not 'fig4'" in found[str(tmp_path / fig4.path)]
    monkeypatch.chdir(tmp_path)
    with pytest.raises(PlanningError) as refused:
        guard_checkout(tmp_path, ["-n"])
    line = refused.value.line()
    assert line.startswith(
        "tennis-stroke results error: results/angle_maps/fig2.nc is not this workflow's file"
    )
    assert "\n" not in line
