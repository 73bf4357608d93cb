"""The check of the targeted evaluation against the maps
(tennis_stroke.inference.validation): its rules, and the default reading's claims."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.inference import validation as va
from tennis_stroke.inference.claims import load_claims

ROOT = Path(__file__).resolve().parents[2]
CLAIMS = load_claims(ROOT / "config" / "claims.yaml")


def test_difference_is_in_tolerances_and_qualitative_claims_must_match():
    assert va.difference(1.3, 1.0, 0.5) == pytest.approx(0.6)
    assert va.difference(1.0, 0.0, 0.0) == 1.0 and va.difference(1.0, 1.0, 0.0) == 0.0
    assert va.agrees([1.04, 1.06], [1.0, 1.0], [0.5, 0.5]).tolist() == [True, False]
    assert va.agrees(1.0, 0.0, 0.0) == np.False_
    assert not va.agrees(np.nan, 1.0, 1.0)


def test_a_difference_within_half_the_grid_step_is_the_grid():
    # a map optimum on a 2-degree grid: 0.9 deg off is the grid, 1.5 deg off is not
    got = va.cause([232.9, 233.5, 232.05], [232.0, 232.0, 232.0], [2.0] * 3, [1.0] * 3)
    assert got.tolist() == ["grid_step", "unexplained", "agrees"]
    assert va.cause(1.564, 1.575, 0.05, 0.0) == "unexplained"  # no grid to blame


def test_grid_half_step_reads_the_map_the_claim_reads():
    ds = xr.Dataset(coords={"psi_F": np.arange(0.0, 361.0, 2.0), "C2": np.arange(0, 1.01, 0.05)})
    files = {"elbow_map": ds, "fig7": ds}
    by_id = {c["id"]: c for c in CLAIMS}
    assert va.grid_half_step(by_id["fig13_best_direction"], files) == pytest.approx(1.0)
    assert va.grid_half_step(by_id["fig7_threshold"], files) == pytest.approx(0.025)
    assert va.grid_half_step(by_id["fig2_best_delta0_at_120"], files) == 0.0  # refined


def test_the_checked_claims_are_those_that_read_a_searched_file():
    ids = {c["id"] for c in va.searched_claims(CLAIMS)}
    assert {"fig2_best_delta0_at_120", "fig7_threshold", "fig13_best_direction"} <= ids
    assert "fig3_delta0_smaller_than_fig2" in ids  # reads fig2 and fig3
    assert not ids & {"fig4_t_a", "table1_v_76", "fig10_hit_before_peak"}


def test_the_chosen_readings_spread_over_the_kept_ones():
    assert va.chosen_readings(8, 60).tolist() == [0, 8, 17, 25, 34, 42, 51, 59]
    assert va.chosen_readings(8, 3).tolist() == [0, 1, 2]
