"""The checks before any job of the workflow's runs (tennis_stroke.pipeline.runs)."""

import copy

import pytest
import yaml
from conftest import ROOT

from tennis_stroke.pipeline.runs import PlanningError, Runs, checked_config

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
PAPER = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())


def test_a_config_whose_grid_leaves_a_claim_off_its_axis_is_refused(monkeypatch):
    """The claims are checked against the config's grids before any job (issue 66, case
    1): Fig. 2's map cut at 100 deg would read its claim at 120 deg at the 100 deg row."""
    monkeypatch.chdir(ROOT)
    config = copy.deepcopy(PAPER)
    config["angle_maps"]["theta0"]["stop"] = 100.0
    with pytest.raises(PlanningError) as error:
        checked_config(config, SCHEMA)
    assert error.value.kind == "claims"
    assert str(error.value).startswith(
        "config/claims.yaml: claim 'fig2_best_delta0_at_120': theta0 = 120 lies off the "
        "theta0 axis of file 'fig2', 60 to 100 (config key 'angle_maps.theta0')"
    )
    checked_config(copy.deepcopy(PAPER), SCHEMA)  # the paper's config passes


def test_a_scenario_whose_grid_leaves_a_claim_off_its_axis_is_refused(monkeypatch, capsys):
    """The same check of every scenario: refused in one warning line, the paper's run
    goes on."""
    monkeypatch.chdir(ROOT)
    config = copy.deepcopy(PAPER)
    _, space = checked_config(config, SCHEMA)
    short = {"angle_maps": {"theta0": {"start": 60.0, "stop": 100.0, "step": 0.25}}}
    runs = Runs.declared(config, space, {"short": short}, SCHEMA)
    assert "short" not in runs.configs
    assert runs.errors["short"].startswith(
        "scenario 'short': config/claims.yaml: claim 'fig2_best_delta0_at_120': theta0 = 120 "
        "lies off the theta0 axis of file 'fig2', 60 to 100"
    )
    assert capsys.readouterr().err.count("scenario 'short'") == 1


def test_an_unknown_figure_is_told_with_the_nearest_names():
    """Was: ``snakemake -n results/figures/fig9.png`` a 46-line traceback, ``fig09_v_tua``
    a 10-line KeyError (issue 66, case 20): rule unknown_figure takes every name of
    ``results/figures/`` the registry lacks, and no name it has."""
    import re

    from tennis_stroke.pipeline.runs import UNKNOWN_FIGURE, nearest_figures
    from tennis_stroke.replication.registry import FIGURES

    output = re.compile(rf"results/figures/(?P<name>{UNKNOWN_FIGURE})\.png$")  # the rule's
    assert not [f for f in FIGURES if output.match(f"results/figures/{f}.png")]
    for guess in ("fig9", "fig99", "fig09_v_tua", "fig09_v_tau.old"):
        assert output.match(f"results/figures/{guess}.png"), guess
    assert nearest_figures("fig9") == ["fig09_v_tau"]
    assert nearest_figures("fig09_v_tua")[0] == "fig09_v_tau"
    assert len(nearest_figures("fig99")) == 3
