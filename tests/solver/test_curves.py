"""The strokes' curves from the compiled solver (solver/curves.py) against scipy's
``solve_ivp`` (solver/reference.py, DOP853 at rtol = atol = 1e-10, its own dense output),
the path that drew them before: many seeded strokes over the figures' ranges and the
readings, both choices of ``figure_curves``."""

import numpy as np
import pytest

from tennis_stroke.model.dynamics import coefficients, elbow_position, mechanical_energy
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver.curves import COLUMNS, CURVE_TOLERANCE, stroke_curves
from tennis_stroke.solver.reference import free_swing, solve_stroke
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import strike

#: The bound of the agreement (docs/solver.md): the angles in rad, the angular
#: velocities in rad/s.  The curve claims' tolerances are 1 degree (0.017 rad) and
#: 2 rad/s, or a comparison of two curves' values (config/claims.yaml): the bound is at
#: least 1e4 times below them.
ANGLE_BOUND = 1e-7
RATE_BOUND = 1e-6
#: Sample times of the test: Figs. 4 and 10-12's span (0.32 s) at 1 ms.
TIMES = np.linspace(0.0, 0.32, 321)
READINGS = {
    "inertia": ("uniform_rod", "paper_text"),
    "contact_lead_rule": ("half_period", "quarter_period", "zero"),
    "collision_coupling": ("newton", "paper_eq8"),
}


def seeded_strokes(n=64, seed=20261206):
    """``n`` strokes ``(theta0, delta0, params)`` over the figures' ranges: Fig. 4's
    angles (L1 0.3 m) or the Sec. V stroke's (L1 0.4 m, C2 5 N m, tau up to 0.3 s), a
    quarter of them with Eq. 14's elbow force (Table I, Fig. 14), each with a random
    reading: the discrete readings, k over the paper's 188-19000 N/m (log), the ball's
    mass over 56-59.4 g."""
    rng = np.random.default_rng(seed)
    strokes = []
    for i in range(n):
        p = {name: str(rng.choice(choices)) for name, choices in READINGS.items()}
        p["k_contact"] = float(np.exp(rng.uniform(np.log(188.0), np.log(19000.0))))
        p["ball_mass"] = float(rng.uniform(0.056, 0.0594))
        if i % 2 == 0:  # Fig. 4
            theta0, delta0 = rng.uniform(60.0, 120.0), rng.uniform(0.0, 100.0)
            p["L1"] = 0.3
        else:  # Figs. 10-12, Table I and Fig. 14
            theta0, delta0 = 90.0, rng.uniform(30.0, 80.0)
            p.update(L1=0.4, C2=5.0, tau=float(rng.uniform(0.0, 0.3)))
            if i % 4 == 1:
                tau_f = float(rng.uniform(-0.1, 0.1))
                p.update(F0=20.0, t_d=0.05, t_F=p["tau"] + tau_f)
                p.update(psi_F_deg=float(rng.uniform(0.0, 360.0)))
                p["elbow_force_mass"] = float(np.exp(rng.uniform(np.log(0.3), np.log(2.3))))
        strokes.append((float(theta0), float(delta0), p))
    return strokes


def _reference(theta0, delta0, p, with_ball, t_max=1.0, times=TIMES, tol=1e-10):
    """The curves by ``solve_ivp`` at the sample ``times`` (angles in rad)."""
    if with_ball:
        ref = solve_stroke(
            theta0, delta0, p, rtol=tol, atol=tol, t_max=t_max, follow_through=times[-1]
        )
    else:
        ref = free_swing(theta0, delta0, times[-1], p, rtol=tol, atol=tol)
    return ref.sample(times), ref.result.get("status_name")


def _assert_agree(ours, ref, i):
    """The compiled curves of stroke ``i`` within the bound of the reference's, and NaN
    exactly where the reference's are."""
    for name in ("theta", "phi", "omega1", "omega2"):
        bound = ANGLE_BOUND if name in ("theta", "phi") else RATE_BOUND
        mine = ours[name][i]
        np.testing.assert_array_equal(np.isnan(mine), np.isnan(ref[name]), err_msg=name)
        finite = np.isfinite(mine)
        assert finite.sum() > 10, (i, name)
        assert np.max(np.abs(mine[finite] - ref[name][finite])) < bound, (i, name)


@pytest.mark.parametrize("with_ball", [False, True], ids=["free_swing", "with_ball"])
def test_the_compiled_curves_agree_with_solve_ivp_on_many_strokes(with_ball):
    """64 seeded strokes in one call: every curve within the bound of the reference, and
    NaN (a stroke that ended before its contact, or the samples after its contact start
    when the racket does not close in on the ball) exactly where the reference's is."""
    strokes = seeded_strokes()
    rows = np.array([coefficients(resolve_params(p), a, b)[0] for a, b, p in strokes])
    curves = stroke_curves(rows, TIMES, with_ball, SolverSettings())
    for i, (theta0, delta0, p) in enumerate(strokes):
        _assert_agree(curves, _reference(theta0, delta0, p, with_ball)[0], i)


#: Strokes with the ball that end otherwise than ``ok`` (tests/solver/test_stroke.py),
#: and the cheap rungs of the model ladder (the collision at ``phi = 0`` in no time),
#: sampled every 0.25 ms until 0.8 s (the racket that does not close in on the ball
#: reaches ``phi = 0`` at 0.79 s, 4 ms after its contact start).  Over so long a swing
#: ``solve_ivp`` at 1e-10 drifts from itself at 1e-13 by 2e-7 rad and 4e-6 rad/s
#: (the compiled curves by 1.1e-9 rad and 2.3e-8 rad/s): the reference is at 1e-12.
ENDING_TIMES = np.linspace(0.0, 0.8, 3201)
ENDINGS = [
    (120.0, 81.5, {"contact_lead": 0.5}, 1.0, "early_contact"),
    (120.0, 81.5, {"k_contact": 188.0, "contact_lead": 0.001}, 0.2, "no_release"),
    (70.0, -60.0, {"C1": 0.0, "C2": 0.0}, 1.0, "no_approach"),
    (120.0, 81.5, {"contact_model": "impact"}, 1.0, "ok"),
    (75.0, 39.0, {"contact_model": "swing_speed", "tau": 0.1, "C2": 5.0}, 1.0, "ok"),
]


@pytest.mark.parametrize("theta0, delta0, p, t_max, status", ENDINGS)
def test_the_curves_of_every_ending_agree_with_solve_ivp(theta0, delta0, p, t_max, status):
    """What a stroke that ends early, or the ladder's instantaneous collision, leaves of
    the curves (NaN after the contact start where the racket does not close in on the
    ball, after phi = 0 where the contact would start before t = 0) is the reference's."""
    rows = coefficients(resolve_params(p), theta0, delta0)
    ours = stroke_curves(rows, ENDING_TIMES, True, SolverSettings(t_max=t_max))
    ref, ref_status = _reference(theta0, delta0, p, True, t_max, ENDING_TIMES, 1e-12)
    assert ref_status == status
    _assert_agree(ours, ref, 0)
    ends = {"early_contact": "t_phi0", "no_approach": "t_contact_start", "no_release": None}
    if ends.get(status):  # NaN from where the stroke ends, and only there
        end = strike(theta0, delta0, p)[ends[status]]
        np.testing.assert_array_equal(np.isnan(ours["omega2"][0]), ENDING_TIMES > end)


def test_the_elbow_and_the_energy_are_the_models_at_each_sample():
    """The elbow's position and the rods' kinetic energy are the model's functions
    (``elbow_position``, ``mechanical_energy`` without the ball) at each sample's state."""
    strokes = seeded_strokes(8)
    rows = np.array([coefficients(resolve_params(p), a, b)[0] for a, b, p in strokes])
    curves = stroke_curves(rows, TIMES, True)
    for i, cf in enumerate(rows):
        for k, t in enumerate(TIMES):
            assert (curves["x_elbow"][i, k], curves["y_elbow"][i, k]) == elbow_position(t, cf)
            state = np.array([curves[c][i, k] for c in COLUMNS[:4]] + [0.0, 0.0])
            if np.isnan(state[0]):
                assert np.isnan(curves["kinetic_energy"][i, k])
            else:
                assert curves["kinetic_energy"][i, k] == mechanical_energy(t, state, cf, False)


def test_the_curves_take_their_own_method_and_tolerance():
    """The stroke numbers' settings lend the curves their limits only: DP54 at a loose
    tolerance gives the same curves, bit for bit, as the default settings."""
    rows = coefficients(resolve_params({}), np.array([120.0, 75.0]), np.array([81.5, 39.0]))
    loose = SolverSettings(method="DP54", rtol=1e-4, atol=1e-4)
    a = stroke_curves(rows, TIMES, True, loose)
    b = stroke_curves(rows, TIMES, True, SolverSettings())
    for name in COLUMNS:
        np.testing.assert_array_equal(a[name], b[name])
    assert CURVE_TOLERANCE <= 1e-10


@pytest.mark.parametrize(
    "times",
    [np.array([]), np.array([0.0, 0.2, 0.1]), np.array([-0.1, 0.1]), np.array([0.0, np.nan])],
    ids=["empty", "descending", "negative", "nan"],
)
def test_bad_sample_times_are_refused_in_one_line(times):
    rows = coefficients(resolve_params({}), 120.0, 81.5)
    with pytest.raises(ValueError, match="sample times must be") as err:
        stroke_curves(rows, times, False)
    assert "\n" not in str(err.value)
