"""Equations of motion: derived from a Lagrangian with sympy, checked against the paper's
Eqs. 6-8, the compiled right-hand side, energy balances and closed forms."""

import math

import numpy as np
import pytest
import sympy as sp
from conftest import coefficient_row
from scipy.integrate import quad, solve_ivp

from tennis_stroke.model.dynamics import (
    CF_A1,
    CF_A2,
    CF_C1,
    CF_COUPLING,
    CF_H1,
    CF_H2,
    CF_I1,
    CF_I2,
    CF_K,
    CF_L1,
    CF_LH,
    CF_M1,
    CF_M2,
    CF_M11,
    CF_M12,
    CF_M22,
    OMEGA1,
    OMEGA2,
    effective_mass,
    elbow_acceleration,
    elbow_position,
    elbow_velocity,
    hit_offset,
    input_power,
    mechanical_energy,
    rhs_angles,
    rhs_trig,
    rod_points,
)

t = sp.symbols("t")
M1, M2, L1, h1, h2, hH, I1, I2, C1, C2, ax, ay, F = sp.symbols(
    "M1 M2 L1 h1 h2 h_H I1 I2 C1 C2 a_x a_y F_r"
)
th, ph = sp.Function("theta")(t), sp.Function("phi")(t)
xE, yE = sp.Function("x_E")(t), sp.Function("y_E")(t)


def lagrangian_accelerations():
    """``(omega1', omega2')`` from the Lagrangian of the driven double pendulum.

    ``F_r`` is the ball's force along +x on the racket at the hitting point.
    """
    r1 = sp.Matrix([xE + h1 * sp.sin(th), yE - h1 * sp.cos(th)])
    r2 = sp.Matrix([xE + L1 * sp.sin(th) + h2 * sp.sin(ph), yE - L1 * sp.cos(th) - h2 * sp.cos(ph)])
    v1, v2 = r1.diff(t), r2.diff(t)
    kinetic = (M1 * v1.dot(v1) + I1 * th.diff(t) ** 2 + M2 * v2.dot(v2) + I2 * ph.diff(t) ** 2) / 2
    x_hit = xE + L1 * sp.sin(th) + (h2 + hH) * sp.sin(ph)
    # Clockwise torques: -C1 + C2 on theta, -C2 on phi; the ball force does F dx_H.
    forces = {th: -C1 + C2 + F * x_hit.diff(th), ph: -C2 + F * x_hit.diff(ph)}
    eqs = [sp.diff(kinetic.diff(q.diff(t)), t) - kinetic.diff(q) - forces[q] for q in (th, ph)]
    dd = sp.symbols("thdd phdd")
    subs = {xE.diff(t, 2): ax, yE.diff(t, 2): ay, th.diff(t, 2): dd[0], ph.diff(t, 2): dd[1]}
    matrix, rhs = sp.linear_eq_to_matrix([sp.expand(e.subs(subs)) for e in eqs], dd)
    sol = matrix.LUsolve(rhs)  # linear in the second derivatives
    w1, w2 = sp.symbols("omega1 omega2")
    back = {th.diff(t): -w1, ph.diff(t): -w2}
    return [-sol[i].subs(back) for i in range(2)], (w1, w2)


@pytest.fixture(scope="module")
def lagrangian():
    (dw1, dw2), (w1, w2) = lagrangian_accelerations()
    a, b = sp.symbols("a b")
    args = (a, b, w1, w2, ax, ay, F, M1, M2, L1, h1, h2, hH, I1, I2, C1, C2)
    plain = {th: a, ph: b}
    return (
        sp.lambdify(args, dw1.subs(plain)),
        sp.lambdify(args, dw2.subs(plain)),
        dw1.subs(plain),
        dw2.subs(plain),
        args,
    )


def _trig_state(theta, phi, w1, w2, cf, compression=0.0, w=0.0):
    s = hit_offset(math.sin(theta), math.sin(phi), cf) + compression
    return (
        math.sin(theta),
        math.cos(theta),
        math.sin(phi),
        math.cos(phi),
        w1,
        w2,
        theta,
        phi,
        s,
        w,
    )


@pytest.mark.parametrize("contact", [False, True])
def test_compiled_rhs_matches_lagrangian(lagrangian, contact):
    f1, f2, *_ = lagrangian
    rng = np.random.default_rng(1)
    for _ in range(20):
        cf = coefficient_row(
            C2=rng.uniform(-5, 5),
            L1=rng.uniform(0.2, 0.5),
            M2=rng.uniform(0.2, 0.5),
            h_hit=rng.uniform(-0.2, 0.3),
        )
        theta, phi, w1, w2 = rng.uniform(-3, 3, 4) * [1, 1, 10, 10]
        tt = rng.uniform(0, 0.3)
        compression = rng.uniform(0, 0.01) if contact else 0.0
        d = rhs_trig(tt, _trig_state(theta, phi, w1, w2, cf, compression), cf, cf[14], contact)
        a_x, a_y = elbow_acceleration(tt, cf)
        f_racket = cf[CF_K] * compression if contact else 0.0
        args = (
            theta,
            phi,
            w1,
            w2,
            a_x,
            a_y,
            f_racket,
            cf[CF_M1],
            cf[CF_M2],
            cf[CF_L1],
            cf[CF_H1],
            cf[CF_H2],
            cf[CF_LH] - cf[CF_H2],
            cf[CF_I1],
            cf[CF_I2],
            cf[CF_C1],
            cf[14],
        )
        assert d[OMEGA1] == pytest.approx(f1(*args), rel=1e-11, abs=1e-9)
        assert d[OMEGA2] == pytest.approx(f2(*args), rel=1e-11, abs=1e-9)


def _paper_eq6(collision):
    """Eqs. 6-8 exactly as printed; ``collision`` is F_col of Eq. 9 (force on the ball)."""
    a, b, w1, w2 = sp.symbols("a b omega1 omega2")
    m11 = I1 + M1 * h1**2 + M2 * L1**2
    m22 = I2 + M2 * h2**2
    den = m22 * m11 - M2**2 * h2**2 * L1**2 * sp.cos(b - a) ** 2
    p = (
        C1
        - C2
        - M2 * h2 * L1 * w2**2 * sp.sin(b - a)
        + (M1 * h1 + M2 * L1) * (ax * sp.cos(a) + ay * sp.sin(a))
    )
    q = C2 + M2 * h2 * L1 * w1**2 * sp.sin(b - a) + M2 * h2 * (ax * sp.cos(b) + ay * sp.sin(b))
    s1 = (
        collision
        * L1
        * ((2 * I2 + h2 * (h2 - hH) * M2) * sp.cos(a) - h2 * (h2 + hH) * M2 * sp.cos(a - 2 * b))
    )
    s2 = collision * (
        (2 * hH * m11 + h2 * (2 * I1 + 2 * M1 * h1**2 + M2 * L1**2)) * sp.cos(b)
        - h2 * M2 * L1**2 * sp.cos(2 * a - b)
    )
    mc = M2 * h2 * L1 * sp.cos(b - a)
    return (p * m22 - q * mc + s1) / den, (q * m11 - p * mc + s2) / den


def _vanishes(expr, samples=6, digits=40):
    """Whether ``expr`` is identically zero: evaluated at random points (rationals) in
    mpmath with 50 digits, below ``10**-(digits - 10)`` at each.

    (A non-zero analytic expression vanishes at random points with probability 0; mpmath
    through ``lambdify`` rather than ``subs`` then ``N``: the same numbers, about ten
    times faster on these expressions.)
    """
    import mpmath

    rng = np.random.default_rng(7)
    symbols = sorted(expr.free_symbols, key=str)
    f = sp.lambdify(symbols, expr, "mpmath")
    values = []
    with mpmath.workdps(digits + 10):
        for _ in range(samples):
            point = [
                mpmath.mpf(int(rng.integers(1, 10**6))) / 10**6 + mpmath.mpf(1) / 10
                for _ in symbols
            ]
            values.append(abs(f(*point)))
    return max(values) < mpmath.mpf(10) ** (-(digits - 10))


def test_paper_eqs_6_7_without_ball_agree_term_by_term(lagrangian):
    *_, dw1, dw2, _ = lagrangian
    p1, p2 = _paper_eq6(0)
    assert _vanishes(p1 - dw1.subs(F, 0))
    assert _vanishes(p2 - dw2.subs(F, 0))


def test_paper_eq8_is_twice_the_lagrangian_collision_terms(lagrangian):
    """Recorded disagreement (docs/equations.md): S_1, S_2 as printed are 2x too large.

    With F_col the force on the ball (Eq. 9), the racket feels F_r = -F_col.
    """
    *_, dw1, dw2, _ = lagrangian
    f_col = sp.symbols("F_col")
    p1, p2 = _paper_eq6(f_col)
    lag1 = dw1.subs(F, -f_col) - dw1.subs(F, 0)
    lag2 = dw2.subs(F, -f_col) - dw2.subs(F, 0)
    paper1 = p1 - _paper_eq6(0)[0]
    paper2 = p2 - _paper_eq6(0)[1]
    assert _vanishes(paper1 - 2 * lag1)
    assert _vanishes(paper2 - 2 * lag2)
    assert not _vanishes(paper1 - lag1)


def test_inline_elbow_acceleration_matches_function():
    """rhs_trig writes the elbow acceleration out; the ball's w' exposes a_x."""
    cf = coefficient_row(F0=20.0, psi_F_deg=76.0, t_F=0.2)
    for tt in np.linspace(0, 0.4, 9):
        y = _trig_state(0.3, 0.2, 0.0, 0.0, cf, 0.0)
        d = rhs_trig(tt, y, cf, 0.0, True)
        assert -d[9] == pytest.approx(elbow_acceleration(tt, cf)[0], rel=1e-13, abs=1e-12)


def test_elbow_closed_forms_integrate_the_acceleration():
    cf = coefficient_row(F0=20.0, psi_F_deg=250.0, t_F=0.15, t_d=0.05)
    for tt in (0.05, 0.17, 0.3):
        for axis in (0, 1):
            v = quad(lambda s, a=axis: elbow_acceleration(s, cf)[a], 0, tt, epsabs=1e-13)[0]
            x = quad(lambda s, a=axis: elbow_velocity(s, cf)[a], 0, tt, epsabs=1e-13)[0]
            assert elbow_velocity(tt, cf)[axis] == pytest.approx(v, rel=1e-10, abs=1e-12)
            assert elbow_position(tt, cf)[axis] == pytest.approx(x, rel=1e-10, abs=1e-12)
    # Eq. 13 itself: v_x = -33 t + 69 t^2, v_y = -42 t + 174 t^2.
    cf0 = coefficient_row()
    assert elbow_velocity(0.2, cf0) == pytest.approx(
        (-33 * 0.2 + 69 * 0.04, -42 * 0.2 + 174 * 0.04)
    )


def test_effective_mass_from_mass_matrix():
    cf = coefficient_row()
    for theta, phi in [(0.3, 0.1), (-0.5, 0.0), (1.0, 0.7)]:
        cd = math.cos(phi - theta)
        mass = np.array([[cf[CF_M11], cf[CF_M12] * cd], [cf[CF_M12] * cd, cf[CF_M22]]])
        jac = np.array([cf[CF_L1] * math.cos(theta), cf[CF_LH] * math.cos(phi)])
        expected = 1.0 / (jac @ np.linalg.solve(mass, jac))
        got = effective_mass(math.sin(theta), math.cos(theta), math.sin(phi), math.cos(phi), cf)
        assert got == pytest.approx(expected, rel=1e-12)


def _energy_and_work(cf, y0, t0, t1, c2, contact):
    def fun(tt, z):
        dydt = np.empty(z.size - 1)
        rhs_angles(tt, z[:-1], cf, c2, contact, dydt)
        return np.append(dydt, input_power(tt, z[:-1], cf, c2, contact))

    sol = solve_ivp(fun, (t0, t1), np.append(y0, 0.0), method="DOP853", rtol=1e-12, atol=1e-12)
    y1 = sol.y[:-1, -1]
    gained = mechanical_energy(t1, y1, cf, contact) - mechanical_energy(t0, y0, cf, contact)
    return gained, sol.y[-1, -1]


@pytest.mark.parametrize("extra", [{}, {"F0": 20.0, "psi_F_deg": 76.0, "t_F": 0.1}])
def test_work_energy_balance_over_the_swing(extra):
    """Work of the joint torques and of the elbow drive = change of kinetic energy."""
    cf = coefficient_row(120.0, 81.5, **extra)
    y0 = np.array([math.radians(120.0), math.radians(201.5), 0.0, 0.0])
    gained, work = _energy_and_work(cf, y0, 0.0, 0.19, 2.5, False)
    assert gained > 10.0  # the swing gains tens of joules
    assert gained == pytest.approx(work, rel=1e-9)


def test_work_energy_balance_during_contact():
    cf = coefficient_row()
    s0 = hit_offset(math.sin(-0.15), math.sin(0.05), cf)
    y0 = np.array([-0.15, 0.05, 11.3, 37.9, s0, 5.0 + 3.0])
    gained, work = _energy_and_work(cf, y0, 0.19, 0.196, 2.5, True)
    assert gained == pytest.approx(work, rel=1e-9, abs=1e-9)


def test_contact_spring_conserves_energy_and_paper_eq8_does_not():
    """Without torques or elbow motion the contact conserves energy (Newton's third law);
    Eq. 8 as printed (``paper_eq8``) creates energy."""
    still = {"C1": 0.0, "C2": 0.0, "vx_t1": 0.0, "vx_t2": 0.0, "vy_t1": 0.0, "vy_t2": 0.0}
    for coupling, conserved in (("newton", True), ("paper_eq8", False)):
        cf = coefficient_row(collision_coupling=coupling, **still)
        s0 = hit_offset(math.sin(-0.15), math.sin(0.05), cf)
        y0 = np.array([-0.15, 0.05, 11.0, 38.0, s0, 5.0])
        e0 = mechanical_energy(0.0, y0, cf, True)
        gained, _ = _energy_and_work(cf, y0, 0.0, 0.004, 0.0, True)
        if conserved:
            assert abs(gained) < 1e-9 * e0
        else:
            assert abs(gained) > 1e-3 * e0


def test_coupling_factor_of_paper_reading():
    assert coefficient_row(collision_coupling="paper_eq8")[CF_COUPLING] == 2.0
    assert coefficient_row()[CF_A1] == pytest.approx(2.0 * 0.15 + 0.3 * 0.3)
    assert coefficient_row()[CF_A2] == pytest.approx(0.3 * 0.35)


def test_the_stick_figure_has_the_rods_lengths_and_eq_10s_hitting_point():
    """Wrist at L1 from the elbow, racket end at L2 from the wrist, the hitting point on
    rod 2 at h2 + h_H, its x offset from the elbow Eq. 10's (hit_offset)."""
    cf = coefficient_row(L1=0.35, L2=0.68, h_hit=0.12)
    theta, phi = np.linspace(-2, 2, 7), np.linspace(-1, 3, 7)
    xe, ye = np.linspace(-0.3, 0.2, 7), np.linspace(0.1, -0.4, 7)
    p = rod_points(theta, phi, xe, ye, cf)
    np.testing.assert_allclose(np.hypot(p["x_wrist"] - xe, p["y_wrist"] - ye), 0.35)
    np.testing.assert_allclose(
        np.hypot(p["x_racket"] - p["x_wrist"], p["y_racket"] - p["y_wrist"]), 0.68
    )
    np.testing.assert_allclose(
        np.hypot(p["x_hit"] - p["x_wrist"], p["y_hit"] - p["y_wrist"]), 0.34 + 0.12
    )
    offsets = [hit_offset(np.sin(a), np.sin(b), cf) for a, b in zip(theta, phi, strict=True)]
    np.testing.assert_allclose(p["x_hit"] - xe, offsets, rtol=1e-14)
    # angles from -y, counter-clockwise: theta = 0 hangs straight down
    down = rod_points(0.0, np.pi / 2, 0.0, 0.0, cf)
    assert (down["x_wrist"], down["y_wrist"]) == pytest.approx((0.0, -0.35))
    assert (down["x_racket"], down["y_racket"]) == pytest.approx((0.68, -0.35))
