"""Parameters: defaults with units, derived quantities, readings, bad values."""

import math
import re

import numpy as np
import pytest

from tennis_stroke.model.params import (
    INITIAL_ANGLES,
    PARAMETERS,
    READINGS,
    ParameterError,
    initial_angles,
    parse_value,
    resolve_params,
    two_body_period,
)


def test_every_parameter_has_unit_and_description():
    for spec in PARAMETERS.values():
        assert spec.unit and spec.description
    for reading in READINGS.values():
        assert reading.default in reading.choices and reading.literal in reading.choices


def test_paper_defaults():
    p = resolve_params()
    assert (p["L1"], p["M1"], p["L2"], p["M2"]) == (0.3, 2.0, 0.7, 0.3)
    assert (p["C1"], p["C2"], p["h_hit"], p["ball_speed"]) == (25.0, 2.5, 0.15, 5.0)


def test_inertia_readings():
    uniform = resolve_params()
    literal = resolve_params({"inertia": "paper_text"})
    assert uniform["I1_cm"] == pytest.approx(2.0 * 0.3**2 / 12)
    assert literal["I2_cm"] == pytest.approx(0.3 * 0.7**2 / 2)
    assert resolve_params({"I1_cm": 0.1})["I1_cm"] == 0.1  # override on purpose


def test_contact_lead_and_two_body_period_match_paper_range():
    # Sec. II: k = 188 ... 19000 N/m gives contact times 50 ... 5 ms (T/2, Eq. 12).
    assert two_body_period(0.057, 0.3, 188.0) / 2 == pytest.approx(0.050, abs=0.5e-3)
    assert two_body_period(0.057, 0.3, 19000.0) / 2 == pytest.approx(0.005, abs=0.05e-3)
    half = resolve_params({"contact_lead_rule": "half_period"})["contact_lead"]
    quarter = resolve_params({"contact_lead_rule": "quarter_period"})["contact_lead"]
    assert quarter == pytest.approx(half / 2)
    assert resolve_params({"contact_lead_rule": "zero"})["contact_lead"] == 0.0


def test_arrays_broadcast_and_derive_per_stroke():
    p = resolve_params({"M2": np.array([0.2, 0.3, 0.4])})
    assert p["I2_cm"].shape == (3,)
    assert p["I2_cm"][2] == pytest.approx(0.4 * 0.7**2 / 12)


@pytest.mark.parametrize(
    "overrides, fragment",
    [
        ({"M2": -1.0}, "'M2' must be > 0"),
        ({"L1": 0.0}, "'L1' must be > 0"),
        ({"L1": math.nan}, "'L1' must be finite"),
        ({"k_contact": math.inf}, "'k_contact' must be finite"),
        ({"tau": -0.1}, "'tau' must be >= 0"),
        ({"M2": "abc"}, "'M2' must be a number"),
        ({"bogus": 1.0}, "unknown parameter 'bogus'"),
        ({"inertia": "hollow"}, "reading 'inertia' must be one of"),
        ({"M2": np.array([0.2, 0.3]), "L1": np.array([0.3, 0.4, 0.5])}, "do not broadcast"),
    ],
)
def test_bad_values_are_one_line_errors(overrides, fragment):
    with pytest.raises(ParameterError, match=fragment) as info:
        resolve_params(overrides)
    assert "\n" not in str(info.value)


def test_parse_value():
    assert parse_value("M2", "0.25") == 0.25
    assert parse_value("inertia", "paper_text") == "paper_text"
    with pytest.raises(ParameterError, match="unknown parameter"):
        parse_value("nope", "1")


def _probes(spec):
    """Values of a parameter at, just beside and between its bounds."""
    values = [spec.default if spec.default is not None else 1.0]
    for bound in (spec.lower, spec.upper):
        if bound is not None:
            nudge = 1e-9 * max(abs(bound), 1.0)
            values += [bound, bound - nudge, bound + nudge]
    return values


@pytest.mark.parametrize("name", sorted(PARAMETERS))
def test_scalar_short_path_equals_the_array_path(name):
    """A plain float (the short path of the checks) and the same value as a 1-element
    array are accepted or refused alike, with the same float."""
    for value in _probes(PARAMETERS[name]):
        for kind in (float, np.float64):
            try:
                scalar = resolve_params({name: kind(value)})[name]
            except ParameterError as exc:
                with pytest.raises(ParameterError, match=re.escape(str(exc).split(", got")[0])):
                    resolve_params({name: np.array([value])})
                continue
            assert type(scalar) is float
            assert scalar == resolve_params({name: np.array([value])})[name][0]


def test_a_reading_given_per_stroke_gives_each_stroke_the_rows_of_its_own_choice():
    """Several readings in one batch (the claims' searches in lockstep): every stroke's
    coefficient row is bit for bit the row of its choices given alone."""
    from tennis_stroke.model.dynamics import coefficients

    combos = [
        ("uniform_rod", "half_period", "newton", "spring"),
        ("paper_text", "quarter_period", "paper_eq8", "impact"),
        ("uniform_rod", "zero", "paper_eq8", "swing_omega2"),
    ]
    names = ("inertia", "contact_lead_rule", "collision_coupling", "contact_model")
    k = np.array([188.0, 7800.0, 19000.0])
    per_stroke = {n: np.array([c[i] for c in combos], dtype=object) for i, n in enumerate(names)}
    rows = coefficients(resolve_params({**per_stroke, "k_contact": k}), 90.0, 30.0)
    for i, combo in enumerate(combos):
        one = {**dict(zip(names, combo, strict=True)), "k_contact": k[i]}
        alone = coefficients(resolve_params(one), 90.0, 30.0)
        assert rows[i].tobytes() == alone[0].tobytes(), combo
    # the choices matter: the rows differ where the readings do
    assert len({r.tobytes() for r in rows}) == 3


def test_a_bad_choice_among_per_stroke_choices_is_named():
    bad = np.array(["uniform_rod", "hollow"], dtype=object)
    with pytest.raises(ParameterError, match="reading 'inertia' must be one of .* got 'hollow'"):
        resolve_params({"inertia": bad})
    with pytest.raises(ParameterError, match="reading 'inertia' must be one of"):
        resolve_params({"inertia": np.array([1.0, 2.0])})


@pytest.mark.parametrize(
    "theta0, delta0, fragment",
    [
        (480.0, 81.5, "initial angle 'theta0' must be <= 360 degree, got 480"),
        (120.0, 801.5, "initial angle 'delta0' must be <= 360 degree, got 801.5"),
        (-1000.0, 81.5, "initial angle 'theta0' must be >= -360 degree, got -1000"),
        # each within a turn, but the racket more than a turn before the hit
        (300.0, 81.5, "theta0 + delta0 must be < 360 degree (the racket starts less than"),
        (180.0, 180.0, "got 180 + 180 = 360"),  # at the hitting position, a turn early
        # one of many strokes is enough, and the message names it
        (np.array([60.0, 300.0]), np.array([[20.0], [70.0]]), "got 300 + 70 = 370"),
    ],
)
def test_an_initial_angle_beyond_a_turn_is_refused(theta0, delta0, fragment):
    """The swing passed phi = 360 deg and hit a turn later: theta0 = 480 deg gave 258.2
    km/h with status ok where 120 deg gives 155.7 (issue 66, case 2)."""
    with pytest.raises(ParameterError, match=re.escape(fragment)):
        initial_angles(theta0, delta0)


@pytest.mark.parametrize(
    "theta0, delta0",
    [
        (60.0, 0.0),  # the corners of the paper's maps (Figs. 2-3, 5-6, 8)
        (120.0, 100.0),
        (90.0, -2.17),  # a delta0 below the maps' (the unbounded optimum of issue 66)
        (-30.0, -20.0),  # a racket past the hit: a status (no_phi_zero), not a refusal
        (359.0, -360.0),
        (179.0, 180.9999),
    ],
)
def test_every_start_less_than_a_turn_before_the_hit_is_accepted(theta0, delta0):
    th, de = initial_angles(theta0, delta0)
    assert (float(th), float(de)) == (theta0, delta0)


def test_the_initial_angles_are_declared_as_the_parameters_are():
    """One table states the rule: units and bounds, read by the explorer and the docs."""
    assert {n: (s.unit, s.lower, s.upper) for n, s in INITIAL_ANGLES.items()} == {
        "theta0": ("degree", -360, 360),
        "delta0": ("degree", -360, 360),
    }


@pytest.mark.parametrize("params", ["M2=0.5", 0, [("M2", 0.5)], 0.5])
def test_params_that_are_not_a_mapping_are_refused(params):
    """A string failed inside dict(), and 0 (falsy) was ignored: the paper's stroke came
    back for 'params=0' (issue 66, case 18)."""
    with pytest.raises(ParameterError, match="params must be a mapping of names to values"):
        resolve_params(params)


def test_a_masked_array_is_refused_not_computed_unmasked():
    """numpy drops the mask: the masked entries were computed (issue 66, case 19)."""
    masked = np.ma.masked_array([0.3, 0.4], mask=[False, True])
    with pytest.raises(ParameterError, match="parameter 'M2' must not be a masked array"):
        resolve_params({"M2": masked})
    with pytest.raises(ParameterError, match="initial angle 'theta0' must not be a masked"):
        initial_angles(np.ma.masked_array([90.0, 120.0], mask=[0, 1]), 30.0)
