"""The fixed-step RK4 path: its order of convergence and a contact shorter than its step."""

import numpy as np
import pytest

from tennis_stroke.solver.rk4 import MISSED_CONTACT, fixed_step_stroke
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import strike


@pytest.mark.parametrize(("theta0", "delta0"), [(120.0, 81.5), (75.0, 39.0)])
def test_fixed_step_rk4_converges_at_fourth_order(theta0, delta0):
    """v_out's error against a tight compiled stroke falls as h**4 (the slope of log error
    over log step, issue 36's 4 +- 0.3): the events are located on each step's Hermite
    cubic; with the linear interpolation they had before the slope was 2.1."""
    ref = strike(theta0, delta0, settings=SolverSettings(rtol=1e-12, atol=1e-12))["v_out_kmh"]
    steps = np.array([4e-4, 2e-4, 1e-4])
    errors = [abs(fixed_step_stroke(theta0, delta0, {}, h)["v_out_kmh"] - ref) for h in steps]
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.3)


def test_fixed_step_rk4_jumps_over_a_contact_shorter_than_its_step():
    assert fixed_step_stroke(120.0, 81.5, {}, 1e-2)["status"] == MISSED_CONTACT
