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
