"""The rungs of the model ladder (contact_model, restitution): closed forms, conservation
laws, the stiff-spring limit that joins the impact to the spring contact, the scipy path
against the compiled one, and the bad inputs a user will type."""

import math

import numpy as np
import pytest
from conftest import coefficient_row
from scipy.integrate import solve_ivp

from tennis_stroke import strike, strike_batch
from tennis_stroke.model.dynamics import (
    CF_COUPLING,
    CF_DAMP,
    CF_L1,
    CF_LH,
    CF_M11,
    CF_M12,
    CF_M22,
    CF_VBALL,
    contact_damping,
    damping_ratio,
    dissipated_power,
    effective_mass,
    elbow_velocity,
    hit_offset,
    input_power,
    mechanical_energy,
    rhs_angles,
    to_trig,
)
from tennis_stroke.model.impact import impact_restitution, instant_contact
from tennis_stroke.model.params import ParameterError, resolve_params
from tennis_stroke.solver.reference import solve_stroke
from tennis_stroke.solver.results import OK

RUNGS = ("spring", "impact", "swing_speed", "swing_omega2")


@pytest.mark.parametrize("e", [0.3, 0.75, 0.85, 0.999])
def test_dashpot_gives_the_restitution_of_two_free_bodies(e):
    """Ball and free racket (Eq. 12's pair) joined by the spring and the dashpot of
    ``restitution = e``, integrated on their own: they part with -e times the closing
    speed."""
    mb, m2, k = 0.058, 0.3, 7800.0
    c = float(contact_damping(e, mb, m2, k))

    def fun(t, z):  # compression x and its rate
        force = k * z[0] + c * z[1]
        return [z[1], -force * (1.0 / mb + 1.0 / m2)]

    def parted(t, z):
        return z[0]

    parted.terminal, parted.direction = True, -1
    sol = solve_ivp(fun, (0, 1), [0.0, 30.0], events=parted, rtol=1e-12, atol=1e-14)
    # leave the start: the event function starts at 0
    assert sol.status == 1
    ratio = sol.y_events[0][-1][1] / 30.0
    assert ratio == pytest.approx(-e, rel=1e-8)


def test_elastic_ball_has_no_dashpot():
    assert contact_damping(1.0, 0.058, 0.3, 7800.0) == 0.0
    assert damping_ratio(1.0) == 0.0
    assert coefficient_row()[CF_DAMP] == 0.0
    assert impact_restitution(0.05, tuple(coefficient_row())) == 1.0


def _state(theta_deg=-11.5, w1=11.3, w2=38.0):
    return to_trig(np.array([math.radians(theta_deg), 0.0, w1, w2]))


@pytest.mark.parametrize(
    ("e", "coupling"), [(1.0, "newton"), (0.8, "newton"), (1.0, "paper_eq8"), (0.8, "paper_eq8")]
)
def test_impact_reverses_the_closing_speed_and_keeps_momentum(e, coupling):
    """The closing speed at the hitting point reverses with the restitution of the
    dashpot for the relative motion; the racket's momentum change at the hitting point
    (through the effective mass) is the ball's times the coupling factor (Newton's third
    law: momentum kept); the elastic impact under Newton's law keeps the kinetic energy of
    rods and ball in the elbow's frame."""
    cf = tuple(coefficient_row(restitution=e, contact_model="impact", collision_coupling=coupling))
    g = cf[CF_COUPLING]
    t, y = 0.2, _state()
    st, ct, sp, cp = y[:4]
    m = effective_mass(st, ct, sp, cp, cf)
    vex = elbow_velocity(t, cf)[0]

    def v_hit(w1, w2):
        return vex - cf[CF_L1] * ct * w1 - cf[CF_LH] * cp * w2

    v_out, w1, w2 = instant_contact(t, y, cf)
    vb0, vb1 = cf[CF_VBALL], -v_out / 3.6
    u0, u1 = vb0 - v_hit(y[4], y[5]), vb1 - v_hit(w1, w2)
    mu = 0.058 * m / (m + g * 0.058)
    assert u1 / u0 == pytest.approx(-impact_restitution(mu, cf), rel=1e-12)
    racket = m * (v_hit(w1, w2) - v_hit(y[4], y[5]))
    assert racket == pytest.approx(-g * 0.058 * (vb1 - vb0), rel=1e-12)
    # kinetic energy in the elbow's frame (the driven elbow's impulse does work in the lab)
    mc = cf[CF_M12] * (cp * ct + sp * st)

    def energy(w1, w2, vb):
        rods = cf[CF_M11] * w1 * w1 + 2.0 * mc * w1 * w2 + cf[CF_M22] * w2 * w2
        return 0.5 * rods + 0.5 * 0.058 * (vb - vex) ** 2

    energy0, energy1 = energy(y[4], y[5], vb0), energy(w1, w2, vb1)
    if e == 1.0 and g == 1.0:
        assert energy1 == pytest.approx(energy0, rel=1e-12)
    elif g == 1.0:
        assert energy1 < energy0 * (1 - 1e-3)
    else:  # Eq. 8 as printed does not keep energy, as its spring contact does not
        assert abs(energy1 - energy0) > 1e-3 * energy0


def test_swing_rungs_score_the_swing_by_their_closed_forms():
    """Without a ball, v_out is the elastic rebound from an immovable racket moving as the
    hitting point (swing_speed) or turning at omega2 about a fixed wrist (swing_omega2),
    from the swing's state at phi = 0; the swing is the spring stroke's to the last bit."""
    spring = strike(120.0, 81.5)
    cf = coefficient_row(120.0, 81.5)
    t0, theta = spring["t_phi0"], math.radians(spring["theta_deg_at_phi0"])
    w1, w2 = spring["omega1_phi0"], spring["omega2_phi0"]
    v_hit = elbow_velocity(t0, cf)[0] - cf[CF_L1] * math.cos(theta) * w1 - cf[CF_LH] * w2
    speed = strike(120.0, 81.5, {"contact_model": "swing_speed"})
    omega = strike(120.0, 81.5, {"contact_model": "swing_omega2"})
    for res in (speed, omega):
        assert res["t_phi0"] == spring["t_phi0"] and res["omega2_phi0"] == w2
        assert res["t_contact_start"] == res["t_separation"] == res["t_phi0"]
    # cos(theta), cos(phi) are states of the compiled solver, integrated to its rtol 5e-8
    assert speed["v_out_kmh"] == pytest.approx(3.6 * (5.0 - 2.0 * v_hit), rel=1e-7)
    assert omega["v_out_kmh"] == pytest.approx(3.6 * (2.0 * 0.5 * w2 + 5.0), rel=1e-12)
    # no ball: the follow-through's peak is the free swing's, whatever the restitution
    lossy = strike(120.0, 81.5, {"contact_model": "swing_speed", "restitution": 0.5})
    assert lossy["omega2_max"] == speed["omega2_max"]


@pytest.mark.parametrize("e", [1.0, 0.8])
@pytest.mark.parametrize("coupling", ["newton", "paper_eq8"])
def test_stiff_spring_contact_tends_to_the_impact(e, coupling):
    """The spring contact of a stiffer and stiffer spring (shorter contact, centred on
    phi = 0) tends to the instantaneous impact with the same ball and the same reading of
    the collision force, at first order in the contact time (~ k^-1/2): the error shrinks
    by at least 2 per decade of k (from k = 1e6 N/m: below it, under paper_eq8, the
    error still changes sign)."""
    base = {"restitution": e, "collision_coupling": coupling}
    impact = strike(120.0, 81.5, {**base, "contact_model": "impact"})["v_out_kmh"]
    errors = [
        abs(strike(120.0, 81.5, {**base, "k_contact": k})["v_out_kmh"] - impact)
        for k in (1e6, 1e7, 1e8)
    ]
    assert errors[0] > 2 * errors[1] > 4 * errors[2]


def test_work_energy_balance_of_a_lossy_contact():
    """With a dashpot, the work of the torques and the elbow drive equals the change of
    mechanical energy plus the energy the dashpot dissipates; the dissipated energy is a
    real share of the collision's."""
    cf = coefficient_row(restitution=0.75)
    s0 = hit_offset(math.sin(-0.15), math.sin(0.05), cf)
    y0 = np.array([-0.15, 0.05, 11.3, 37.9, s0, 5.0 + 3.0])

    def fun(t, z):
        dydt = np.empty(6)
        rhs_angles(t, z[:6], cf, 2.5, True, dydt)
        work = input_power(t, z[:6], cf, 2.5, True)
        return [*dydt, work, dissipated_power(z[:6], cf)]

    sol = solve_ivp(fun, (0.19, 0.196), [*y0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12)
    y1, work, lost = sol.y[:6, -1], sol.y[6, -1], sol.y[7, -1]
    gained = mechanical_energy(0.196, y1, cf, True) - mechanical_energy(0.19, y0, cf, True)
    assert lost > 1.0  # joules: a ball at tens of m/s loses a real share of its energy
    assert gained == pytest.approx(work - lost, rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("rung", RUNGS)
@pytest.mark.parametrize("e", [1.0, 0.8])
def test_scipy_path_agrees_on_every_rung(rung, e):
    params = {"contact_model": rung, "restitution": e}
    got = strike(75.0, 39.0, params)
    ref = solve_stroke(75.0, 39.0, params, rtol=1e-11, atol=1e-11).result
    assert got["status"] == ref["status"] == OK
    for key in ("v_out_kmh", "t_separation", "omega2_contact"):
        assert got[key] == pytest.approx(ref[key], rel=1e-6), key


def test_a_lossy_ball_is_slower_and_the_cheap_rungs_cost_less():
    th, de = np.array([120.0, 75.0, 90.0]), np.array([81.5, 39.0, 45.0])
    res = {r: strike_batch(th, de, {"contact_model": r}) for r in RUNGS}
    lossy = strike_batch(th, de, {"restitution": 0.75})
    assert np.all(lossy["v_out_kmh"] < res["spring"]["v_out_kmh"] - 5.0)
    for rung in RUNGS[1:]:
        assert np.all(res[rung]["rhs_evals"] < res["spring"]["rhs_evals"])


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"contact_model": "hertz"}, "model option 'contact_model' must be one of"),
        ({"restitution": 0.0}, "'restitution' must be > 0"),
        ({"restitution": 1.2}, "'restitution' must be <= 1"),
        ({"restitution": "soft"}, "'restitution' must be a number"),
    ],
)
def test_bad_rungs_are_refused_in_one_line(overrides, message):
    with pytest.raises(ParameterError, match=message) as err:
        resolve_params(overrides)
    assert "\n" not in str(err.value)
