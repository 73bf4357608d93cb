"""Failed strokes: counted by status; a map above the failure share is refused."""

import numpy as np
import pytest

from tennis_stroke import SolverSettings
from tennis_stroke.experiments.maps import angle_map, mass_length_map
from tennis_stroke.experiments.optima import mass_length_optimum
from tennis_stroke.io.failures import FailureShareError, check_failure_share, failure_counts

THETA0 = np.array([60.0, 90.0, 120.0])
DELTA0 = np.array([10.0, 50.0])


def test_a_good_map_has_no_failures():
    ds = angle_map(THETA0, DELTA0, {}, SolverSettings(), 1)
    counts = check_failure_share(ds, 0.0, "good map")
    assert counts["total"] == 6 and counts["failed"] == 0
    assert counts["no_phi_zero"] == 0 and "ok" not in counts


def test_strokes_cut_short_are_statuses_and_the_map_is_refused():
    # phi reaches 0 after about 0.2 s: with t_max = 0.05 s every stroke fails.
    ds = angle_map(THETA0, DELTA0, {}, SolverSettings(t_max=0.05), 1)
    assert np.all(np.isnan(ds["v_out"].values))
    counts = failure_counts(ds)
    assert counts == {**counts, "total": 6, "failed": 6, "no_phi_zero": 6}
    with pytest.raises(FailureShareError) as err:
        check_failure_share(ds, 0.5, "results/angle_maps/L1_0.3.nc")
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith("results/angle_maps/L1_0.3.nc: 6 of 6 strokes failed (100.00 %)")
    assert "no_phi_zero 6" in message and "above max_failure_share 50 %" in message
    assert check_failure_share(ds, 1.0, "allowed")["failed"] == 6


def test_the_share_is_a_strict_limit():
    ds = angle_map(THETA0, DELTA0, {}, SolverSettings(), 1)
    status = ds["status"].values.copy()
    status[0, 0] = 4  # one no_release of six strokes
    ds["status"].values = status
    assert check_failure_share(ds, 1 / 6, "m")["no_release"] == 1
    with pytest.raises(FailureShareError, match="1 of 6 strokes failed"):
        check_failure_share(ds, 0.16, "m")


def test_optimum_map_counts_the_strokes_of_its_searches():
    ds = mass_length_map(
        np.array([0.3]),
        np.array([0.3, 0.4]),
        30.0,
        15.0,
        (60.0, 120.0),
        (0.0, 90.0),
        {},
        SolverSettings(t_max=0.05),
        1,
    )
    per_point = 3 * 4 + 5 * 5  # coarse grid + fine grid of +-1 coarse step
    assert ds.attrs["strokes_per_point"] == per_point
    assert failure_counts(ds) == {"total": 2 * per_point, "failed": 2 * per_point}
    with pytest.raises(FailureShareError, match="74 of 74 strokes failed"):
        check_failure_share(ds, 0.01, "mass_length")


def test_the_searched_optimum_map_counts_every_stroke_it_ran():
    ds = mass_length_optimum(
        np.array([0.3]),
        np.array([0.3, 0.4]),
        30.0,
        5.0,
        (60.0, 120.0),
        (0.0, 90.0),
        {},
        SolverSettings(t_max=0.05),  # no stroke reaches its release
        1,
    )
    counts = failure_counts(ds)
    assert counts["total"] == int(ds["evaluated_strokes"].sum()) >= 2 * 3 * 4
    assert counts["failed"] == counts["total"]  # every stroke failed, and was counted
    assert np.isnan(ds["v_out_best"]).all()


def test_bad_share_is_refused():
    with pytest.raises(ValueError, match=r"max_share must be in \[0, 1\]"):
        check_failure_share(angle_map(THETA0[:1], DELTA0[:1], {}, SolverSettings(), 1), 2.0, "m")
