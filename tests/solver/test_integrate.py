"""The compiled integrator: convergence order, dense output, reversibility, failures."""

import math

import numpy as np
import pytest
from conftest import by_entry, coefficient_row, coefficient_tup
from scipy.integrate import solve_ivp

from tennis_stroke.model.dynamics import OMEGA1, OMEGA2, rhs_angles, rhs_trig
from tennis_stroke.solver import integrate
from tennis_stroke.solver.integrate import (
    HISTORY_COLS,
    MAX_FACTOR,
    MIN_FACTOR,
    N_STATS,
    PHASE_END,
    PHASE_EVENT,
    PHASE_FAIL,
    PREDICTIVE_ERR_FLOOR,
    SAFETY,
    ST_NREJECT,
    ST_NSTEP,
    error_root,
    peak_omega2,
    step_factor,
)
from tennis_stroke.solver.settings import METHOD_IDS, ORDERS

# The compiled functions with a literal method, called from Python in loops.
dense_coefficients = by_entry(integrate.dense_coefficients)
dense_value = by_entry(integrate.dense_value)
integrate_phase = by_entry(integrate.integrate_phase)
rk_step = by_entry(integrate.rk_step)

T_END = 0.15


def _start(theta0=100.0, delta0=40.0):
    th, ph = math.radians(theta0), math.radians(theta0 + delta0)
    return (math.sin(th), math.cos(th), math.sin(ph), math.cos(ph), 0.0, 0.0, th, ph, 0.0, 0.0)


@pytest.fixture(scope="module")
def reference_omegas():
    """omega1, omega2 at T_END from scipy (angle layout) at rtol 1e-13: independent."""
    cf = coefficient_row(100.0, 40.0)

    def fun(t, y):
        d = np.empty(4)
        rhs_angles(t, y, cf, 2.5, False, d)
        return d

    y0 = [math.radians(100.0), math.radians(140.0), 0.0, 0.0]
    sol = solve_ivp(fun, (0, T_END), y0, method="DOP853", rtol=1e-13, atol=1e-13)
    return sol.y[2, -1], sol.y[3, -1]


def _fixed_steps(method, n):
    cf = coefficient_tup(100.0, 40.0)
    y = _start()
    f = rhs_trig(0.0, y, cf, 2.5, False)
    h = T_END / n
    for i in range(n):
        y, f, _ = rk_step(METHOD_IDS[method], False, i * h, y, f, h, cf, 2.5, 1e-8, 1e-8)
    return y


@pytest.mark.parametrize("method, steps", [("DP54", (10, 20, 40)), ("DOP853", (6, 9, 14))])
def test_observed_convergence_order(method, steps, reference_omegas):
    errors = []
    for n in steps:
        y = _fixed_steps(method, n)
        errors.append(
            max(abs(y[OMEGA1] - reference_omegas[0]), abs(y[OMEGA2] - reference_omegas[1]))
        )
    slope = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(ORDERS[method], abs=0.6), (method, errors)


#: Order of the dense output (its local error is O(h^(order + 1))).
DENSE_ORDERS = {"DP54": 4, "DOP853": 7}


@pytest.mark.parametrize("method", sorted(METHOD_IDS))
def test_dense_output_is_consistent_and_of_its_order(method):
    mid = METHOD_IDS[method]
    cf = coefficient_tup(100.0, 40.0)
    y0 = _start()
    f0 = rhs_trig(0.0, y0, cf, 2.5, False)
    gaps = []
    for h in (0.01, 0.005):
        y1, f1, _ = rk_step(mid, False, 0.0, y0, f0, h, cf, 2.5, 1e-8, 1e-8)
        z = dense_coefficients(mid, False, 0.0, y0, f0, h, cf, 2.5, y1, f1)
        assert dense_value(mid, 0.0, y0, z) == pytest.approx(y0, abs=1e-15)
        assert dense_value(mid, 1.0, y0, z) == pytest.approx(y1, rel=1e-13, abs=1e-13)
        y_half, _, _ = rk_step(mid, False, 0.0, y0, f0, h / 2, cf, 2.5, 1e-8, 1e-8)
        interp = dense_value(mid, 0.5, y0, z)
        gaps.append(max(abs(a - b) for a, b in zip(interp, y_half, strict=True)))
    assert math.log2(gaps[0] / gaps[1]) == pytest.approx(DENSE_ORDERS[method] + 1, abs=1.0)


def test_backward_integration_returns_to_the_start():
    cf = coefficient_tup(100.0, 40.0)
    y0 = _start()
    stats = np.zeros(N_STATS)
    history = np.zeros((1, HISTORY_COLS))
    args = (cf, 2.5, 1e-11, 1e-11, 1e6, False, stats, history)
    f0 = rhs_trig(0.0, y0, cf, 2.5, False)
    status, t, y1, f1, h = integrate_phase(1, False, 0.0, y0, f0, T_END, 0.01, np.inf, *args)
    assert status == PHASE_END and t == T_END
    status, t, y2, _, _ = integrate_phase(1, False, T_END, y1, f1, 0.0, h, np.inf, *args)
    assert status == PHASE_END and t == 0.0
    assert y2 == pytest.approx(y0, abs=1e-9)


def test_too_many_steps_is_a_failure_status():
    cf = coefficient_tup(100.0, 40.0)
    y0 = _start()
    stats = np.zeros(N_STATS)
    f0 = rhs_trig(0.0, y0, cf, 2.5, False)
    status, *_ = integrate_phase(
        1,
        False,
        0.0,
        y0,
        f0,
        T_END,
        0.001,
        np.inf,
        cf,
        2.5,
        1e-9,
        1e-9,
        3,
        False,
        stats,
        np.zeros((1, HISTORY_COLS)),
    )
    assert status == PHASE_FAIL and stats[1] == 3


def test_peak_of_omega2_inside_a_step():
    # omega2(s) = 1 - (s - 0.3)^2 on a step of size 1: peak 1 at s = 0.3.
    def state(s):
        return (0, 0, 0, 0, 0, 1 - (s - 0.3) ** 2, 0, 0, 0, 0)

    def deriv(s):
        return (0, 0, 0, 0, 0, -2 * (s - 0.3), 0, 0, 0, 0)

    best = peak_omega2(state(0.0), state(1.0), deriv(0.0), deriv(1.0), 1.0, -1.0)
    assert best == pytest.approx(1.0, abs=1e-12)
    assert peak_omega2(state(0.0), state(0.2), deriv(0.0), deriv(0.2), 0.2, -1.0) == pytest.approx(
        state(0.2)[5]
    )


def test_error_root_is_the_norm_s_root_and_keeps_order():
    for err in (1e-30, 1e-8, 0.3, 1.0, 7.5, 1e12):
        assert error_root(err, -1.0 / 8.0) == pytest.approx(err ** (1 / 8), rel=1e-15)
        assert error_root(err, -0.2) == pytest.approx(err**0.2, rel=1e-15)
    # Order is kept, so the integrator floors the root instead of the norm.
    errs = np.geomspace(1e-3, 1e-1, 2001)
    roots = [error_root(err, -1.0 / 8.0) for err in errs]
    assert all(a <= b for a, b in zip(roots, roots[1:], strict=False))
    floor = error_root(PREDICTIVE_ERR_FLOOR, -1.0 / 8.0)
    for err in errs:
        root = error_root(max(err, PREDICTIVE_ERR_FLOOR), -1.0 / 8.0)
        assert root == max(error_root(err, -1.0 / 8.0), floor)


def test_step_factor_closed_forms():
    e = -1.0 / 8.0

    def root(err):
        return error_root(err, e)

    classical = SAFETY * 0.3**e
    assert step_factor(root(0.3), 1e-3, 0.0, 0.0) == pytest.approx(classical, rel=1e-15)
    assert step_factor(0.0, 1e-3, 1e-3, root(0.5)) == MAX_FACTOR
    assert step_factor(root(1e-30), 1e-3, 0.0, 0.0) == MAX_FACTOR
    # The error doubled over two equal steps: the step shrinks by a further 2**(1/8).
    assert step_factor(root(0.6), 1e-3, 1e-3, root(0.3)) == pytest.approx(
        SAFETY * 0.6**e * 0.5 ** (1 / 8), rel=1e-15
    )
    # A falling error never grows the step beyond the classical rule ...
    assert step_factor(root(0.1), 1e-3, 1e-3, root(0.5)) == pytest.approx(
        SAFETY * 0.1**e, rel=1e-15
    )
    # ... and a steeply rising one never shrinks it below MIN_FACTOR.
    assert step_factor(root(0.9), 1e-3, 1e-2, root(1e-2)) == MIN_FACTOR


def _classical_attempts(cf, y, f, t_end, h, rtol):
    """Accepted + rejected DOP853 steps to the swing's phi = 0 under the classical rule
    (``SAFETY * err**(-1/8)``, no predictive term): an independent loop over rk_step."""
    t, attempts, rejected = 0.0, 0, False
    while True:
        attempts += 1
        dt = min(h, t_end - t)
        y_new, f_new, err = rk_step(1, False, t, y, f, dt, cf, 2.5, rtol, rtol)
        if err > 1.0:
            h, rejected = dt * max(MIN_FACTOR, SAFETY * err ** (-1 / 8)), True
            continue
        factor = min(MAX_FACTOR, SAFETY * err ** (-1 / 8)) if err > 0 else MAX_FACTOR
        h, rejected = dt * (min(1.0, factor) if rejected else factor), False
        if y_new[7] <= 0.0:  # phi fell through 0
            return attempts
        t, y, f = t + dt, y_new, f_new


def test_predictive_controller_saves_step_attempts_in_the_accelerating_swing():
    # Not every swing gains (a few take one attempt more), so the check is over a grid
    # of the paper's initial angles: fewer attempts in all.
    ours = classical = 0
    for theta0 in (60.0, 75.0, 90.0, 105.0, 120.0):
        for delta0 in (0.0, 30.0, 60.0, 90.0):
            cf = coefficient_tup(theta0, delta0)
            y0 = _start(theta0, delta0)
            f0 = rhs_trig(0.0, y0, cf, 2.5, False)
            stats = np.zeros(N_STATS)
            args = (cf, 2.5, 5e-8, 5e-8, 1e5, True, stats, np.zeros((1, HISTORY_COLS)))
            status, *_ = integrate_phase(1, False, 0.0, y0, f0, 1.0, 0.02, np.inf, *args)
            assert status == PHASE_EVENT
            ours += stats[ST_NSTEP] + stats[ST_NREJECT]
            classical += _classical_attempts(cf, y0, f0, 1.0, 0.02, 5e-8)
    assert ours < classical


def _replayed_steps(cf, y, f, h, rtol, floor):
    """Accepted DOP853 step sizes to the swing's phi = 0 under the documented rule
    (classical, and from the second accepted step Gustafsson's predictive rule on the
    previous norm floored at ``floor``), replayed in Python with ``pow`` over rk_step;
    also how often the floor changed the growth factor."""
    t, steps, rejected, h_acc, err_acc, floored = 0.0, [], False, 0.0, 0.0, 0
    while True:
        y_new, f_new, err = rk_step(1, False, t, y, f, h, cf, 2.5, rtol, rtol)
        if not err <= 1.0:
            h, rejected = h * max(MIN_FACTOR, SAFETY * err ** (-1 / 8)), True
            continue
        factor = MAX_FACTOR if err == 0.0 else min(MAX_FACTOR, SAFETY * err ** (-1 / 8))
        if h_acc > 0.0 and err > 0.0:
            grow = factor * (h / h_acc)
            with_floor = min(factor, max(MIN_FACTOR, grow * (max(err_acc, floor) / err) ** (1 / 8)))
            without = min(factor, max(MIN_FACTOR, grow * (err_acc / err) ** (1 / 8)))
            floored += with_floor != without
            factor = with_floor
        steps.append(h)
        if y_new[7] <= 0.0:  # phi fell through 0
            return steps, floored
        h_acc, err_acc = h, err
        t, y, f = t + h, y_new, f_new
        h, rejected = h * (min(1.0, factor) if rejected else factor), False


def test_integrator_takes_the_steps_of_the_documented_rule_with_its_floor():
    # The integrator's accepted steps (its history) against the rule replayed in Python.
    # The floor of the predictive rule must matter somewhere on this grid, or the check
    # could not tell a rule without it.
    floored = 0
    for theta0 in (60.0, 90.0, 120.0):
        for delta0 in (0.0, 45.0, 90.0):
            cf = coefficient_tup(theta0, delta0)
            y0 = _start(theta0, delta0)
            f0 = rhs_trig(0.0, y0, cf, 2.5, False)
            history = np.zeros((257, HISTORY_COLS))
            args = (cf, 2.5, 5e-8, 5e-8, 1e5, True, np.zeros(N_STATS), history)
            status, *_ = integrate_phase(1, False, 0.0, y0, f0, 1.0, 0.02, np.inf, *args)
            assert status == PHASE_EVENT
            taken = history[: int(history[-1, 0]), 1]
            steps, n = _replayed_steps(cf, y0, f0, 0.02, 5e-8, PREDICTIVE_ERR_FLOOR)
            floored += n
            # The error norm is a difference of stage sums: its last digits differ between
            # the kernel compiled into the integrator and rk_step called alone (fused
            # differently), so the steps agree to about 1e-9, not to the bit; the floor
            # changes a factor by (floor / norm) ** (1/8), far more.
            assert taken == pytest.approx(steps, rel=1e-6)
    assert floored > 0, "the floor never mattered: the check cannot see it"


def test_no_caller_uses_the_derivative_integrate_phase_returns():
    """At an event integrate_phase returns the interpolated state but the derivative at
    the end of the step that crossed (its docstring says so): safe only while no caller
    reads it.  Every call in the package must discard it: the returned ``f`` is never read
    before the caller assigns it again from the right-hand side."""
    import ast
    from pathlib import Path

    import tennis_stroke

    callers = []
    for path in Path(tennis_stroke.__file__).parent.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for func in ast.walk(tree):
            if not isinstance(func, ast.FunctionDef):
                continue
            for call in ast.walk(func):
                if (
                    isinstance(call, ast.Call)
                    and getattr(call.func, "id", None) == "integrate_phase"
                    and func.name != "integrate_phase"
                ):
                    callers.append((path.name, func))
    assert callers, "integrate_phase has no caller: the test looks in the wrong place"
    for name, func in callers:
        assigns = [
            node
            for node in ast.walk(func)
            if isinstance(node, ast.Assign)
            and any(isinstance(t, ast.Tuple) for t in node.targets)
            and getattr(getattr(node.value, "func", None), "id", None) == "integrate_phase"
        ]
        assert assigns, (name, func.name)
        derivative = assigns[0].targets[0].elts[3].id  # status, t, y, f, h
        reads = [
            node
            for node in ast.walk(func)
            if isinstance(node, ast.Name)
            and node.id == derivative
            and isinstance(node.ctx, ast.Load)
        ]
        # the only read is the argument of integrate_phase itself, after the caller set
        # it from the right-hand side at the phase start
        arguments = [a for a in assigns[0].value.args if isinstance(a, ast.Name)]
        assert all(any(r is a for a in arguments) for r in reads), (name, func.name)
        fresh = [
            node
            for node in ast.walk(func)
            if isinstance(node, ast.Assign)
            and any(getattr(t, "id", None) == derivative for t in node.targets)
            and getattr(getattr(node.value, "func", None), "id", None) == "rhs_trig"
        ]
        assert fresh, (name, func.name)
