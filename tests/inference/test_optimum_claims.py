"""The claims that locate an optimum and the two rules every one of them is judged by
(tennis_stroke.inference.optimum_claims): an optimum on the edge of its search range
says so, and flatness is one rule for every such claim, passing or not (issue 66, case
23: fig3_best_delta0_at_120 passed, robust, at the lower end of its delta0 range on a
flat objective, and nothing said so)."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.optimum_claims import located
from tennis_stroke.replication.claims import evaluate

ROOT = Path(__file__).resolve().parents[2]
FLAT_GAP = 1.0  # km/h, as config/readings.yaml declares it


@pytest.fixture(scope="module")
def claims():
    return {c["id"]: c for c in load_claims(ROOT / "config" / "claims.yaml")}


def angle_map(curvature: float) -> xr.Dataset:
    """A Fig. 3 map whose best delta0 at theta0 = 120 deg lies beyond the range's lower
    end (-2.17 deg), at 90 deg inside it (26 deg)."""
    theta0, delta0 = np.array([60.0, 90.0, 120.0]), np.linspace(0.0, 100.0, 401)
    peak = np.array([40.0, 26.0, -2.17])[:, None]
    v = 150.0 - curvature * (delta0[None, :] - peak) ** 2
    best = np.where(peak[:, 0] > 0, peak[:, 0], 0.0)  # the search clips to the range
    return xr.Dataset(
        {
            "v_out": (("theta0", "delta0"), v),
            "status": (("theta0", "delta0"), np.zeros(v.shape, int)),
            "best_delta0": ("theta0", best),
        },
        coords={"theta0": theta0, "delta0": delta0},
    )


def row(claim, files, **changed):
    return evaluate([{**claim, **changed}], files, flat_gap=FLAT_GAP).iloc[0]


def test_the_claims_that_locate_an_optimum_follow_from_their_measures(claims):
    found = {k for k, c in claims.items() if located(c["measure"]) is not None}
    assert {"fig3_best_delta0_at_120", "fig8_tau_opt", "fig14_worst_direction"} <= found
    assert {"fig9_v_H", "fig9_gain", "fig7_threshold", "fig4_v_a"}.isdisjoint(found)


def test_an_optimum_on_the_edge_of_its_search_range_says_so(claims):
    files = {"fig3": angle_map(2.5e-3)}
    at_120 = row(claims["fig3_best_delta0_at_120"], files)
    assert at_120["status"] == "pass"  # the verdict stays what it is
    assert at_120["edge"] == (
        "delta0 = 0 degree, the lower end of the search range [0, 100] degree"
    )
    assert row(claims["fig3_best_delta0_at_90"], files)["edge"] == ""


def test_flatness_is_one_rule_for_passing_and_deviating_optima(claims):
    """The rule that makes fig8_tau_opt ill conditioned (v_out at the paper's argument
    within flat_gap of the optimum) judges fig3_best_delta0_at_120 too."""
    claim = claims["fig3_best_delta0_at_120"]
    flat = row(claim, {"fig3": angle_map(2.5e-3)}, paper_value=1.0)
    assert flat["status"] == "pass" and str(flat["flat"]) == "True"
    assert flat["objective_gap"] == pytest.approx(2.5e-3 * (3.17**2 - 2.17**2), rel=1e-9)
    steep = row(claim, {"fig3": angle_map(1.0)}, paper_value=1.0)
    assert steep["status"] == "pass" and str(steep["flat"]) == "False"  # 5.3 km/h below
    other = row(claims["fig4_v_a"], {"fig4": xr.Dataset({"v_out": ("stroke", [156.0, 141.0])})})
    assert other["flat"] == "" and other["edge"] == "" and np.isnan(other["objective_gap"])


def elbow_map(sign: float) -> xr.Dataset:
    """A Fig. 13 map whose largest (``sign`` 1) or smallest (-1) v_out lies at psi_F = 0
    deg (a full turn: no edge) and beyond tau_F = -0.1 s (the range's lower end)."""
    psi, tau = np.linspace(0.0, 360.0, 181), np.linspace(-0.1, 0.1, 41)
    shape = np.cos(np.radians(psi))[:, None] - 5.0 * tau[None, :]
    v = 150.0 + sign * shape
    return xr.Dataset(
        {
            "v_out": (("psi_F", "tau_F"), v),
            "status": (("psi_F", "tau_F"), np.zeros(v.shape, int)),
        },
        coords={"psi_F": psi, "tau_F": tau},
    )


def test_every_searched_coordinate_of_an_optimum_is_judged_a_full_turn_has_no_edge(claims):
    end = "tau_F = -0.1 s, the lower end of the search range [-0.1, 0.1] s"
    best = row(claims["fig13_best_direction"], {"elbow_map": elbow_map(1.0)})
    assert best["reproduced_value"] == 0.0 and best["edge"] == end
    worst = row(claims["fig14_worst_direction"], {"elbow_map": elbow_map(-1.0)})
    assert worst["reproduced_value"] == 0.0 and worst["edge"] == end
    assert worst["objective_gap"] == pytest.approx(1.0 - np.cos(np.radians(276.0)), abs=1e-9)


def test_a_targeted_file_is_no_map_to_judge_on(claims):
    """The explorer evaluates on the searches' files alone: they hold the points found,
    not the objective around them, so neither rule is applied there."""
    targeted = angle_map(2.5e-3)[["best_delta0"]].assign_attrs(targeted="search")
    out = row(claims["fig3_best_delta0_at_120"], {"fig3": targeted})
    assert out["flat"] == "" and out["edge"] == ""
