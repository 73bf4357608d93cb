"""A stroke over time in the lab frame (io/trajectory.py, solver/reference.py
``lab_frame``): checked against physics, the compiled path and closed forms, not shapes.

The velocities are checked against the derivatives of the positions (an independent
path: no equation of motion), the ball's motion in the contact against Newton's law with
the spring, its exit against the compiled solver's rebound speed, and the hitting
point's speed against its closed form from the angles and rates."""

import numpy as np
import pytest
from conftest import FIG4_A

from tennis_stroke import solve_stroke, strike, stroke_dataset
from tennis_stroke.io.trajectory import sample_times
from tennis_stroke.io.units import VARIABLES
from tennis_stroke.model.dynamics import MS_TO_KMH
from tennis_stroke.model.params import ParameterError, resolve_params
from tennis_stroke.solver.settings import SolverSettings

#: A moving elbow with the pulse of Eq. 14 on top, so the frame change matters.
PULSE = {"F0": 20.0, "psi_F_deg": 76.0}
#: An elbow at rest: the hitting point's lab velocity is then its velocity about the elbow.
FIXED_ELBOW = {"vx_t1": 0.0, "vx_t2": 0.0, "vy_t1": 0.0, "vy_t2": 0.0}
#: The compiled path at the scipy path's tolerance (its default is within 1e-5 km/h).
TIGHT = SolverSettings(rtol=1e-12, atol=1e-12)


@pytest.fixture(scope="module")
def pulse_stroke():
    return solve_stroke(*FIG4_A, PULSE, follow_through=0.03)


def _boundaries(stroke):
    """Every phase boundary of the stroke (s): where accelerations may jump."""
    return np.array([t for seg in stroke.segments for t in (seg.t0, seg.t1)])


def test_velocities_are_the_time_derivatives_of_the_positions(pulse_stroke):
    """Every point's velocity (elbow, wrist, racket end, hitting point, and the ball
    in the contact) equals the central difference of its position, away from the phase
    boundaries (where an acceleration may jump)."""
    h = 1e-6
    t = np.linspace(0.0, pulse_stroke.segments[-1].t1, 4001)[1:-1]
    t_c = pulse_stroke.result["t_contact_start"]
    t_sep = pulse_stroke.result["t_separation"]
    t = np.union1d(t, np.linspace(t_c, t_sep, 401)[1:-1])  # the contact, finely
    t = t[np.min(np.abs(t[:, None] - _boundaries(pulse_stroke)), axis=1) > 2 * h]
    mid, lo, hi = (pulse_stroke.lab_frame(t + d) for d in (0.0, -h, h))
    checked = 0
    for point in ("elbow", "wrist", "racket", "hit", "ball"):
        for axis in ("x", "y") if point != "ball" else ("x",):
            velocity = mid[f"v{axis}_{point}"]
            derivative = (hi[f"{axis}_{point}"] - lo[f"{axis}_{point}"]) / (2 * h)
            both = np.isfinite(velocity) & np.isfinite(derivative)
            assert both.sum() > 300, (point, axis)
            np.testing.assert_allclose(velocity[both], derivative[both], atol=1e-5, rtol=0)
            checked += 1
    assert checked == 9
    assert np.nanmax(mid["speed_hit"]) > 20.0  # the check is of a fast racket


def test_the_hitting_points_speed_is_its_closed_form_from_angles_and_rates():
    """With the elbow at rest, |v_H|^2 = (L1 w1)^2 + (l_H w2)^2 + 2 L1 l_H w1 w2
    cos(phi - theta), l_H = L2/2 + h_H, from the dataset's own angles (degrees) and
    rates."""
    ds = stroke_dataset(solve_stroke(*FIG4_A, FIXED_ELBOW, follow_through=0.03))
    p = resolve_params(FIXED_ELBOW)
    l1, lh = p["L1"], p["L2"] / 2 + p["h_hit"]
    w1, w2 = ds["omega1"].values, ds["omega2"].values
    delta = np.radians(ds["phi"].values - ds["theta"].values)
    closed = np.sqrt((l1 * w1) ** 2 + (lh * w2) ** 2 + 2 * l1 * lh * w1 * w2 * np.cos(delta))
    speed = ds["speed_hit"].values
    assert np.isfinite(speed).sum() > 1500 and np.nanmax(speed) > 20.0
    np.testing.assert_allclose(speed, closed, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(ds["vx_elbow"].fillna(0.0), 0.0)


def test_in_the_contact_the_ball_obeys_newtons_law_with_the_spring(pulse_stroke):
    """m_b dv_b/dt = -k (x_b - x_H) in the lab frame (the elastic ball): the ball's lab
    acceleration differentiated from its velocity is the spring's force over its mass,
    although the integrated state is relative to an accelerating elbow."""
    res, p = pulse_stroke.result, pulse_stroke.params
    t = np.linspace(res["t_contact_start"], res["t_separation"], 2001)
    lab = pulse_stroke.lab_frame(t)
    acceleration = np.gradient(lab["vx_ball"], t)
    spring = -p["k_contact"] * (lab["x_ball"] - lab["x_hit"]) / p["ball_mass"]
    inner = slice(2, -2)
    assert np.max(np.abs(spring)) > 1e3  # a hard push: km/s^2
    np.testing.assert_allclose(
        acceleration[inner], spring[inner], atol=1e-4 * np.max(np.abs(spring)), rtol=0
    )


def test_the_ball_leaves_at_the_compiled_paths_rebound_speed(pulse_stroke):
    """The ball's lab velocity just before separation (the integrated state) is the
    compiled path's ``v_out`` towards -x; it is at the hitting point at the contact's
    start and end, arrives at ``ball_speed`` and keeps its exit velocity after."""
    res = pulse_stroke.result
    compiled = strike(*FIG4_A, PULSE, TIGHT)
    assert compiled["status_name"] == "ok" == res["status_name"]
    t_c, t_sep = res["t_contact_start"], res["t_separation"]
    eps = 1e-9
    lab = pulse_stroke.lab_frame(np.array([t_c - 0.01, t_c, t_sep - eps, t_sep + 0.01]))
    assert abs(-lab["vx_ball"][2] * MS_TO_KMH - compiled["v_out_kmh"]) < 1e-6
    assert lab["vx_ball"][0] == pytest.approx(resolve_params(PULSE)["ball_speed"])
    assert lab["x_ball"][1] == pytest.approx(lab["x_hit"][1], abs=1e-12)  # no compression
    assert lab["x_ball"][2] == pytest.approx(lab["x_hit"][2], abs=1e-6)  # 1 ns before: none
    assert lab["vx_ball"][3] == pytest.approx(lab["vx_ball"][2], abs=1e-6)
    # the free legs join the contact where the ball is
    edges = pulse_stroke.lab_frame(np.array([t_c - eps, t_c, t_sep - eps, t_sep + eps]))
    np.testing.assert_allclose(edges["x_ball"][[0, 2]], edges["x_ball"][[1, 3]], atol=1e-6)


def test_an_instantaneous_impact_reverses_the_ball_at_phi_zero():
    """The model ladder's impact: no contact phase; the ball arrives at ``ball_speed``,
    meets the hitting point at t0 and leaves at the compiled path's ``v_out``."""
    params = {"contact_model": "impact"}
    stroke = solve_stroke(*FIG4_A, params, follow_through=0.02)
    t0 = stroke.result["t_phi0"]
    assert stroke.result["t_contact_start"] == t0 == stroke.result["t_separation"]
    lab = stroke.lab_frame(np.array([t0 - 0.01, t0, t0 + 0.01]))
    assert lab["vx_ball"][0] == pytest.approx(resolve_params(params)["ball_speed"])
    v_out = strike(*FIG4_A, params, TIGHT)["v_out_kmh"]
    assert abs(-lab["vx_ball"][2] * MS_TO_KMH - v_out) < 1e-6
    assert lab["x_ball"][1] == pytest.approx(lab["x_hit"][1], abs=1e-12)


def test_the_datasets_values_are_those_of_sample_and_its_attributes_those_of_the_table():
    stroke = solve_stroke(*FIG4_A, follow_through=0.02)
    ds = stroke_dataset(stroke)
    t = ds["t"].values
    assert np.all(np.diff(t) > 0) and t[0] == 0.0 and t[-1] == stroke.segments[-1].t1
    sampled = stroke.sample(t)
    for name in ("theta", "phi"):
        np.testing.assert_array_equal(ds[name].values, np.degrees(sampled[name]))
    for name in ("omega1", "omega2"):
        np.testing.assert_array_equal(ds[name].values, sampled[name])
    for name in [*ds.data_vars, *ds.coords]:
        units, long_name = VARIABLES[name]
        assert ds[name].attrs["units"] == units and ds[name].attrs["long_name"] == long_name
    assert float(ds["v_out"]) == stroke.result["v_out_kmh"]
    assert ds["status"].attrs["flag_meanings"].split()[int(ds["status"])] == "ok"
    assert ds.attrs["solver_path"] == "scipy solve_ivp" and ds.attrs["param_k_contact"] == 7800
    # the contact is sampled finely: as many samples inside it as over the whole stroke
    inside = (t >= float(ds["t_contact_start"])) & (t <= float(ds["t_separation"]))
    assert inside.sum() >= len(sample_times(stroke)) // 2


def test_a_failed_stroke_gives_its_status_and_nan_where_nothing_was_computed():
    stroke = solve_stroke(*FIG4_A, t_max=0.05)  # phi does not reach 0 so soon
    ds = stroke_dataset(stroke, [0.0, 0.02, 0.04, 0.06, 0.08])
    assert stroke.result["status_name"] == "no_phi_zero"
    assert int(ds["status"]) == stroke.result["status"]
    assert ds["vx_ball"].isnull().all()  # never met
    assert ds["theta"][:3].notnull().all() and ds["theta"][3:].isnull().all()


@pytest.mark.parametrize(
    "times, fragment",
    [
        ([[0.0, 0.1]], "one-dimensional"),
        ([0.1, 0.1], "increase strictly"),
        ([0.2, 0.1], "increase strictly"),
        ([0.0, np.nan], "finite"),
        ("0.1", "number"),
    ],
)
def test_bad_sample_times_are_a_parameter_error(times, fragment):
    stroke = solve_stroke(*FIG4_A, rtol=1e-6, atol=1e-6)
    with pytest.raises(ParameterError, match=fragment):
        stroke_dataset(stroke, times)


def test_a_dataset_of_anything_but_a_solved_stroke_is_a_parameter_error():
    """``stroke_dataset({})`` was ``AttributeError: 'segments'`` (issue 66, case 18)."""
    with pytest.raises(ParameterError, match="stroke must be a ReferenceStroke .*, got dict"):
        stroke_dataset({})
