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


def test_fixed_step_rk4_gives_the_event_times():
    """The event times of a fixed-step stroke (the work-precision study's event error)
    are the tight compiled stroke's within 1e-6 s at a 0.1 ms step."""
    ref = strike(120.0, 81.5, settings=SolverSettings(rtol=1e-12, atol=1e-12))
    res = fixed_step_stroke(120.0, 81.5, {}, 1e-4)
    for key in ("t_phi0", "t_contact_start", "t_separation"):
        assert res[key] == pytest.approx(ref[key], abs=1e-6), key


@pytest.mark.parametrize("rung", ["impact", "swing_speed", "swing_omega2"])
def test_fixed_step_rk4_meets_the_ball_as_the_cheap_rungs_do(rung):
    """A cheap rung of the model ladder has no spring contact on any path: RK4's v_out is
    the compiled stroke's, its contact start and separation its phi = 0."""
    ref = strike(120.0, 81.5, {"contact_model": rung}, SolverSettings(rtol=1e-12, atol=1e-12))
    res = fixed_step_stroke(120.0, 81.5, {"contact_model": rung}, 1e-4)
    assert res["v_out_kmh"] == pytest.approx(ref["v_out_kmh"], abs=1e-3)
    assert res["t_separation"] == res["t_contact_start"] == res["t_phi0"]


def test_fixed_step_rk4_takes_the_rule_of_the_initial_angles():
    """A start more than a turn before the hit (theta0 + delta0 = 380 deg) is refused on
    this path too: it would pass phi = 360 deg and hit a turn later (issue 66, case 2)."""
    from tennis_stroke.model.params import ParameterError

    with pytest.raises(ParameterError, match="theta0 \\+ delta0 must be < 360 degree"):
        fixed_step_stroke(300.0, 80.0, {}, 1e-4)


@pytest.mark.parametrize("contact", [False, True])
def test_the_compiled_steps_are_rk4_step_on_the_models_rhs_bit_for_bit(contact):
    """fixed_phase steps compiled: the same bits as :func:`rk4_step` of ``angle_rhs``
    stepped from Python, through a torque switch (``tau``) and a short last step."""
    from tennis_stroke.model.dynamics import (
        angle_rhs,
        coefficients,
        next_switch,
        wrist_torque,
    )
    from tennis_stroke.model.params import resolve_params
    from tennis_stroke.solver.rk4 import fixed_phase, rk4_step

    cf = coefficients(resolve_params({"tau": 0.0123}), 120.0, 81.5)[0]
    y = np.array([2.0, 1.0, -3.0, 5.0, 0.01, 4.0][: 6 if contact else 4])
    t, t_stop, h = 0.0, 0.0305, 1e-3
    while t < t_stop:
        t_seg = next_switch(t, cf, t_stop)
        fun = angle_rhs(cf, wrist_torque(t, t_seg, cf), contact)
        while t < t_seg:
            step = min(h, t_seg - t)
            t, y = t + step, rk4_step(fun, t, y, step)
    start = np.array([2.0, 1.0, -3.0, 5.0, 0.01, 4.0][: 6 if contact else 4])
    t_end, y_end, hit, evals = fixed_phase(cf, 0.0, start, t_stop, h, contact)
    # 13 steps to tau, 19 after it, the last of each short
    assert (t_end, hit, evals) == (t, False, 4 * 32)
    np.testing.assert_array_equal(y_end, y)
