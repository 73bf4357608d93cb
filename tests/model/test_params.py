"""Parameters: defaults with units, derived quantities, readings, bad values."""

import math
import re

import numpy as np
import pytest

from tennis_stroke.model.params import (
    PARAMETERS,
    READINGS,
    ParameterError,
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
