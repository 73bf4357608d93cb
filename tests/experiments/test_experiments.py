"""Experiment helpers: grids, peak refinement, the nested optimum of Figs. 5-6."""

import numpy as np
import pytest

from tennis_stroke.experiments.maps import grid, mass_length_map, refine_peak
from tennis_stroke.solver.results import OK
from tennis_stroke.solver.stroke import SolverSettings, strike_batch


def test_grid_is_inclusive_and_exact():
    g = grid(60.0, 120.0, 0.25)
    assert g[0] == 60.0 and g[-1] == 120.0 and len(g) == 241
    assert grid(0.0, 0.3, 0.0025)[-1] == 0.3


def test_refine_peak_is_exact_on_a_parabola():
    x = grid(0.0, 10.0, 1.0)
    v = 5.0 - (x - 3.3) ** 2
    loc, val = refine_peak(x, v)
    assert loc == pytest.approx(3.3) and val == pytest.approx(5.0)
    assert refine_peak(x, -x) == (0.0, 0.0)  # on the edge: the sample itself
    v[2] = np.nan
    assert refine_peak(x, v)[0] == 3.0  # no parabola through a failed stroke
    assert np.isnan(refine_peak(x, np.full(11, np.nan))[0])


def test_nested_optimum_matches_a_brute_force_search():
    """Coarse + fine + parabola finds the optimum of a dense grid at one (M2, L1)."""
    ds = mass_length_map(
        np.array([0.3]),
        np.array([0.4]),
        4.0,
        0.2,
        (80.0, 100.0),
        (10.0, 40.0),
        {},
        SolverSettings(),
        1,
    )
    theta0, delta0 = np.arange(80.0, 100.01, 0.5), np.arange(10.0, 40.01, 0.5)
    dense = strike_batch(theta0[:, None], delta0[None, :], {"M2": 0.3, "L1": 0.4})
    v = np.where(dense["status"] == OK, dense["v_out_kmh"], np.nan)
    assert float(ds["v_out_best"][0, 0]) >= np.nanmax(v) - 1e-3
    i, j = np.unravel_index(np.nanargmax(v), v.shape)
    assert float(ds["theta0_best"][0, 0]) == pytest.approx(theta0[i], abs=0.5)
    assert float(ds["delta0_best"][0, 0]) == pytest.approx(delta0[j], abs=0.5)


@pytest.mark.parametrize(
    "start, stop, step, last",
    [
        (0.0, 0.3, 0.5, 0.0),
        (60.0, 120.0, 0.7, 119.5),
        (0.0, 0.3, 0.0025, 0.3),
        (-0.1, 0.1, 0.005, 0.1),
    ],
)
def test_a_grid_never_leaves_its_range(start, stop, step, last):
    """It ends on stop when the step lands there, else at the last point before it."""
    from tennis_stroke.experiments.grids import grid_size, lands_on_stop

    g = grid(start, stop, step)
    assert (
        g[-1] == pytest.approx(last)
        and g[-1] <= stop + 1e-12
        and g.size == grid_size(start, stop, step)
    )
    assert lands_on_stop(start, stop, step) == (g[-1] == pytest.approx(stop))
