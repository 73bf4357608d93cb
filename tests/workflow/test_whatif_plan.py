"""The plan of a what-if run (tennis_stroke.pipeline.whatif), as data: the files it asks
Snakemake for and Snakemake's command line, for a declared scenario and a new one.  What
``tennis-stroke whatif`` prints and refuses is tests/workflow/test_scenarios.py's."""

import pytest
import yaml
from conftest import ROOT

from tennis_stroke.pipeline.scenarios import ScenarioError
from tennis_stroke.pipeline.whatif import plan_whatif


def test_a_declared_scenario_is_run_by_name_for_its_page_and_article(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the project is ``root``, wherever the caller stands
    plan = plan_whatif("heavy_racket", root=ROOT)
    pages = "report/scenarios/heavy_racket"
    assert plan.overrides is None  # the workflow reads its declaration
    assert plan.targets == (f"{pages}/index.html", f"{pages}/article.pdf")
    resume = "--rerun-incomplete"  # what an interrupted run left is made again
    assert plan.snakemake_args(2) == ["--cores", "2", *plan.targets, "--quiet", "rules", resume]
    assert plan.snakemake_args(3, dry_run=True) == [
        "--cores",
        "3",
        *plan.targets,
        "--quiet",
        "rules",
        resume,
        "-n",
    ]


def test_a_new_scenario_gives_snakemake_its_overrides_and_only_its_figures():
    sets = ["M2=0.35", "torque_delay.base_stroke.C2=8"]
    plan = plan_whatif("x", sets, ["fig2", "fig09_v_tau"], root=ROOT)
    overrides = {"model": {"M2": 0.35}, "torque_delay": {"base_stroke": {"C2": 8}}}
    assert plan.overrides == overrides
    assert plan.targets == (
        "results/scenarios/x/figures/fig02_angle_map.png",
        "results/scenarios/x/figures/fig09_v_tau.png",
    )
    args = plan.snakemake_args(4, dry_run=True)
    start = ["--cores", "4", *plan.targets, "--quiet", "rules", "--rerun-incomplete"]
    assert args[: len(start)] == start
    assert args[-3:-1] == ["--config", args[-2]] and args[-1] == "-n"
    key, _, flow = args[-2].partition("=")  # one argument: Snakemake reads it as YAML
    assert key == "scenarios" and yaml.safe_load(flow) == {"x": overrides}


@pytest.mark.parametrize(
    "name, sets, figures, message",
    [
        ("heavy_racket", ["M2=0.4"], [], "is declared in config/scenarios.yaml: --set would"),
        ("nosuch", [], [], "'nosuch' is not declared in config/scenarios.yaml"),
        ("x", ["M2=0.4"], ["fig99"], "no figure 'fig99'"),  # the registry's KeyError
    ],
)
def test_a_refused_plan_is_one_scenario_error(name, sets, figures, message):
    with pytest.raises(ScenarioError, match=message):
        plan_whatif(name, sets, figures, root=ROOT)
