"""The model ladder claim by claim (tennis_stroke.inference.ladder): every claim under
each rung of the tiny config, what a rung can answer, the costs, and bad ladders."""

import copy
from pathlib import Path

import numpy as np
import pytest
from tiny import TINY

from tennis_stroke import strike
from tennis_stroke.inference import ladder as ld
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.ladder_plan import LadderError, check_ladder, rung_model
from tennis_stroke.pipeline.config_check import load_schema, with_defaults

ROOT = Path(__file__).resolve().parents[2]
CLAIMS = load_claims(ROOT / "config" / "claims.yaml")


@pytest.fixture(scope="module")
def tiny_ladder():
    config = copy.deepcopy(TINY)
    config.update(with_defaults(config, load_schema(ROOT / "workflow/schemas/config.schema.yaml")))
    return ld.evaluate_ladder(CLAIMS, config, threads=1)


def _claim(ds, rung, claim, var="value"):
    return float(ds[var].sel(rung=rung, claim=claim))


def test_every_claim_under_every_rung(tiny_ladder):
    ds = tiny_ladder
    assert list(ds["rung"].values) == ["swing_omega2", "impact", "spring", "lossy", "dp54"]
    assert ds["value"].shape == (5, len(CLAIMS))
    # the reference rung is the paper's model: the claims' strokes as strike computes them
    assert _claim(ds, "spring", "fig4_v_a") == strike(120.0, 81.5)["v_out_kmh"]
    own = ds["from_reference"].sel(rung="spring").values
    value = ds["value"].sel(rung="spring").values
    assert np.array_equal(np.isnan(own), np.isnan(value)) and np.all(own[~np.isnan(own)] == 0)
    # a lossy ball returns the ball slower; the impact within a km/h of the spring
    assert _claim(ds, "lossy", "fig4_v_a") < _claim(ds, "spring", "fig4_v_a") - 5.0
    assert abs(_claim(ds, "impact", "fig4_v_a") - _claim(ds, "spring", "fig4_v_a")) < 1.0
    assert (
        _claim(ds, "impact", "fig4_v_a")
        == strike(120, 81.5, {"contact_model": "impact"})["v_out_kmh"]
    )


def test_a_rung_answers_only_what_it_models(tiny_ladder):
    ds = tiny_ladder
    # no spring: no answer on the spring constant; no ball: no ball speed
    assert _claim(ds, "impact", "sec2_k_barely_changes_v_out", "comparable") == 0
    assert _claim(ds, "lossy", "sec2_k_barely_changes_v_out", "comparable") == 1
    assert _claim(ds, "swing_omega2", "fig4_v_a", "comparable") == 0
    assert _claim(ds, "swing_omega2", "fig4_v_a", "within") == 0
    assert _claim(ds, "impact", "fig4_v_a", "comparable") == 1
    assert _claim(ds, "swing_omega2", "fig9_gain", "comparable") == 0  # a ratio of speeds
    # optima, thresholds and trends are answered by every rung
    for rung in ds["rung"].values:
        assert _claim(ds, rung, "fig7_threshold", "comparable") == 1


def test_cheap_rungs_cost_fewer_evaluations_and_costs_are_counted(tiny_ladder):
    evals = tiny_ladder["rhs_evals"]
    assert np.all(evals.values > 0)  # every file ran compiled strokes under every rung
    fig4 = evals.sel(file="fig4")
    for rung in ("swing_omega2", "impact"):
        assert float(fig4.sel(rung=rung)) < float(fig4.sel(rung="spring"))
    assert tiny_ladder["seconds"].attrs["timing"] == 1


def test_a_rung_keeps_the_configs_ball_unless_it_names_one():
    model = {"restitution": 0.9, "L1": 0.4}
    assert rung_model(model, {"contact_model": "impact"}) == {
        "restitution": 0.9,
        "L1": 0.4,
        "contact_model": "impact",
    }
    lossy = rung_model(model, {"contact_model": "spring", "restitution": 0.75})
    assert lossy["restitution"] == 0.75


def test_comparability_rule():
    speed = {"unit": "km/h", "measure": {"file": "fig4"}}
    gain = {"unit": "%", "measure": {"function": "fig9", "file": "fig9"}}
    k = {"unit": "%", "measure": {"function": "k_spread", "file": "k_sensitivity"}}
    angle = {"unit": "degree", "measure": {"file": ["fig2", "fig3"]}}
    assert ld.comparable(speed, "impact") and not ld.comparable(speed, "swing_speed")
    assert ld.comparable(gain, "impact") and not ld.comparable(gain, "swing_omega2")
    assert not ld.comparable(k, "impact") and ld.comparable(k, "spring")
    assert all(ld.comparable(angle, m) for m in ("swing_omega2", "impact", "spring"))


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"reference": "paper"}, "model_ladder.reference 'paper' is not a rung"),
        ({"rungs": [{"name": "a", "contact_model": "spring"}] * 2}, "'a' is used twice"),
    ],
)
def test_a_bad_ladder_is_refused_in_one_line(change, message):
    ladder = {**TINY["model_ladder"], **change}
    with pytest.raises(LadderError, match=message):
        check_ladder(ladder)


def test_files_read_together_form_one_group_through_any_chain():
    """A claim reading a and b and another reading b and c put a, b and c in one group
    (the connected components of the files-read-together graph); a file no claim reads
    is in no group; groups and their members follow the order of the keys."""
    from tennis_stroke.inference.ladder import file_groups

    def claim(*files):
        return {"measure": {"file": list(files) if len(files) > 1 else files[0]}}

    keys = ["e", "d", "c", "b", "a", "x"]
    claims = [claim("a", "b"), claim("d"), claim("c", "b"), claim("e")]
    assert file_groups(claims, keys) == [["e"], ["d"], ["c", "b", "a"]]
    assert file_groups([], keys) == []
