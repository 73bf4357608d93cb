"""Model parameters and the readings of the paper's ambiguities, validated, with units.

Every number of the model has one entry in :data:`PARAMETERS` (name, SI unit, default,
bounds, meaning).  Every point where the paper can be read in more than one way has one
entry in :data:`READINGS`, whose first choice is the project's default and whose
``literal`` choice is the paper read word for word.  The evidence behind each default is in
``docs/assumptions.md``.

Values may be scalars or numpy arrays that broadcast against each other (one value per
stroke); :func:`resolve_params` validates them and fills the derived quantities
(moments of inertia, contact lead).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np


class ParameterError(ValueError):
    """A parameter or option has a bad name or value (message is one line)."""


@dataclass(frozen=True)
class ParamSpec:
    """One numeric model parameter.

    ``lower``/``upper`` are bounds (``None``: unbounded); ``strict`` makes ``lower``
    exclusive.  ``derived`` parameters default to a value computed from the others
    (see :func:`resolve_params`) but may be overridden on purpose.
    """

    name: str
    default: float | None
    unit: str
    description: str
    lower: float | None = None
    upper: float | None = None
    strict: bool = False
    derived: bool = False


#: The model parameters, in SI units (angles in degrees only where the name says ``_deg``).
PARAMETERS: dict[str, ParamSpec] = {
    s.name: s
    for s in [
        ParamSpec(
            "L1",
            0.3,
            "m",
            "length of rod 1 (elbow to hand, projected)",
            lower=0,
            upper=5,
            strict=True,
        ),
        ParamSpec("M1", 2.0, "kg", "mass of rod 1 (arm+forearm)", lower=0, upper=100, strict=True),
        ParamSpec("L2", 0.7, "m", "length of rod 2 (hand+racket)", lower=0, upper=5, strict=True),
        ParamSpec("M2", 0.3, "kg", "mass of rod 2 (hand+racket)", lower=0, upper=100, strict=True),
        ParamSpec(
            "I1_cm",
            None,
            "kg m2",
            "moment of inertia of rod 1 about its centre",
            lower=0,
            upper=None,
            strict=True,
            derived=True,
        ),
        ParamSpec(
            "I2_cm",
            None,
            "kg m2",
            "moment of inertia of rod 2 about its centre",
            lower=0,
            upper=None,
            strict=True,
            derived=True,
        ),
        ParamSpec("C1", 25.0, "N m", "elbow torque on rod 1 (clockwise positive)"),
        ParamSpec("C2", 2.5, "N m", "wrist torque on rod 2 (clockwise positive)"),
        ParamSpec("tau", 0.0, "s", "delay after which C2 switches on (Sec. V)", lower=0, upper=10),
        ParamSpec(
            "C2_off", 0.5, "s", "time at which C2 switches off (paper: '0.5 ms')", lower=0, upper=10
        ),
        ParamSpec(
            "h_hit", 0.15, "m", "hitting point beyond the centre of rod 2 (h_H)", lower=-5, upper=5
        ),
        ParamSpec(
            "ball_mass",
            0.058,
            "kg",
            "ball mass (not stated in the paper; fitted)",
            lower=0,
            upper=10,
            strict=True,
        ),
        ParamSpec("ball_speed", 5.0, "m/s", "incoming ball speed along +x", lower=0, upper=100),
        ParamSpec(
            "k_contact",
            7800.0,
            "N/m",
            "ball-racket spring constant (fitted)",
            lower=0,
            upper=1e12,
            strict=True,
        ),
        ParamSpec(
            "restitution",
            1.0,
            "1",
            "coefficient of restitution of the ball on the strings of a free racket of mass "
            "M2 (1: the paper's elastic ball; below 1: a dashpot in the contact)",
            lower=0,
            upper=1,
            strict=True,
        ),
        ParamSpec(
            "contact_lead",
            None,
            "s",
            "time from contact start to phi = 0 (t0 - t_c)",
            lower=0,
            upper=1,
            derived=True,
        ),
        ParamSpec("vx_t1", -33.0, "m/s2", "elbow velocity vx = vx_t1 t + vx_t2 t^2 (Eq. 13)"),
        ParamSpec("vx_t2", 69.0, "m/s3", "elbow velocity, quadratic x coefficient (Eq. 13)"),
        ParamSpec("vy_t1", -42.0, "m/s2", "elbow velocity vy = vy_t1 t + vy_t2 t^2 (Eq. 13)"),
        ParamSpec("vy_t2", 174.0, "m/s3", "elbow velocity, quadratic y coefficient (Eq. 13)"),
        ParamSpec(
            "F0", 0.0, "N", "amplitude of the extra elbow force (Eq. 14)", lower=0, upper=1e4
        ),
        ParamSpec("psi_F_deg", 0.0, "degree", "direction of the extra elbow force from +x, ccw"),
        ParamSpec(
            "t_F",
            0.185,
            "s",
            "centre time of the extra elbow force (tau_H + tau_F)",
            lower=0,
            upper=10,
        ),
        ParamSpec(
            "t_d",
            0.05,
            "s",
            "width of the extra elbow force pulse (Eq. 14)",
            lower=0,
            upper=10,
            strict=True,
        ),
        ParamSpec(
            "elbow_force_mass",
            0.97,
            "kg",
            "mass the extra elbow force accelerates (fitted to Table I)",
            lower=0,
            upper=1e3,
            strict=True,
        ),
    ]
}


#: The initial angles of a stroke (degrees, counter-clockwise from -y, Fig. 1): not model
#: parameters (every stroke of a map has its own: they are the maps' axes), declared as
#: they are, each within one turn either way.  The racket swings clockwise from
#: ``phi0 = theta0 + delta0`` to the hit at ``phi = 0`` (the first time it gets there),
#: so it must start less than one turn before it: ``phi0 <`` :data:`MAX_PHI0`.  Beyond,
#: it would pass ``phi = 360`` deg, the hitting position, and hit a turn later (issue
#: 66: ``theta0 = 480`` gave 258 km/h where ``120`` gives 156).  The paper's strokes lie
#: far inside (``theta0`` 60-120 deg, ``delta0`` 0-100 deg).  Every entry point goes
#: through :func:`initial_angles`: the solvers' (``strike_batch`` and so ``strike``,
#: ``solve_stroke``, ``free_swing``, the fixed-step ``fixed_step_stroke``), ``sweep``,
#: the config check and the explorer's controls.
INITIAL_ANGLES: dict[str, ParamSpec] = {
    s.name: s
    for s in [
        ParamSpec(
            "theta0", None, "degree", "initial angle of rod 1 (the arm)", lower=-360, upper=360
        ),
        ParamSpec(
            "delta0",
            None,
            "degree",
            "initial angle of rod 2 to rod 1 (phi0 - theta0)",
            lower=-360,
            upper=360,
        ),
    ]
}
#: The initial racket angle ``phi0 = theta0 + delta0`` is below this (degrees): the
#: racket starts less than one turn before the hit (:data:`INITIAL_ANGLES`).
MAX_PHI0 = 360.0


def initial_angle(name: str, value: object) -> np.ndarray:
    """Initial angle ``name`` (``theta0`` or ``delta0``; degrees, a number or an array)
    as an array of floats, finite and within its bounds (:data:`INITIAL_ANGLES`), or
    :class:`ParameterError` naming it."""
    arr = real_array(f"initial angle {name!r}", value)
    _check_bounds(INITIAL_ANGLES[name], arr, "initial angle")
    return arr


def initial_angles(theta0: object, delta0: object) -> tuple[np.ndarray, np.ndarray]:
    """``theta0`` and ``delta0`` (degrees; numbers or arrays that broadcast) as arrays of
    floats, checked by the rule of :data:`INITIAL_ANGLES`: finite, each within its
    bounds, and ``theta0 + delta0 <`` :data:`MAX_PHI0`.  Raises :class:`ParameterError`
    naming the angle."""
    th, de = initial_angle("theta0", theta0), initial_angle("delta0", delta0)
    try:
        phi0 = th + de
    except ValueError:
        raise ParameterError(
            f"the initial angles do not broadcast to one shape: {th.shape}, {de.shape}"
        ) from None
    if not np.all(phi0 < MAX_PHI0):
        at = np.unravel_index(np.argmax(phi0), phi0.shape)
        t, d = np.broadcast_to(th, phi0.shape)[at], np.broadcast_to(de, phi0.shape)[at]
        raise ParameterError(
            f"initial angles theta0 + delta0 must be < {MAX_PHI0:g} degree (the racket "
            f"starts less than a turn before the hit at phi = 0; beyond, it passes phi = "
            f"{MAX_PHI0:g} deg and hits a turn later), got {t:g} + {d:g} = {t + d:g}"
        )
    return th, de


@dataclass(frozen=True)
class Reading:
    """One ambiguity of the paper: the named choices, the default and the literal one."""

    name: str
    choices: tuple[str, ...]
    default: str
    literal: str
    description: str


#: The readings of the paper's ambiguities.  Defaults are chosen by evidence
#: (docs/assumptions.md); ``literal`` is the paper read word for word.
READINGS: dict[str, Reading] = {
    r.name: r
    for r in [
        Reading(
            "inertia",
            ("uniform_rod", "paper_text"),
            "uniform_rod",
            "paper_text",
            "I_cm of each rod: M L^2/12 (uniform rod) or M L^2/2 (Sec. III text)",
        ),
        Reading(
            "contact_lead_rule",
            ("half_period", "quarter_period", "zero"),
            "quarter_period",
            "half_period",
            "contact starts T/2, T/4 or 0 before phi = 0, T from Eq. 12",
        ),
        Reading(
            "collision_coupling",
            ("newton", "paper_eq8"),
            "newton",
            "paper_eq8",
            "ball force on the racket: Newton's third law (Lagrangian) or Eq. 8 as "
            "printed (twice the Lagrangian terms)",
        ),
    ]
}


#: Model options that are not ambiguities of the paper: the rungs of the model ladder
#: (:mod:`tennis_stroke.model.impact`; ``docs/solver.md``, "The model ladder").  Set
#: like a reading (``--set contact_model=impact``, ``{"contact_model": "impact"}``); the
#: default is the paper's model.
MODEL_OPTIONS: dict[str, Reading] = {
    r.name: r
    for r in [
        Reading(
            "contact_model",
            ("spring", "impact", "swing_speed", "swing_omega2"),
            "spring",
            "spring",
            "how the ball meets the racket: the spring contact (Sec. II), an instantaneous "
            "impact at phi = 0 with the racket's effective mass, or no ball, the swing "
            "scored by the hitting point's speed or by omega2 at phi = 0",
        ),
    ]
}
#: Every named choice :func:`resolve_params` accepts: the readings and the model options.
CHOICES: dict[str, Reading] = {**READINGS, **MODEL_OPTIONS}


def _has_bool(value: object) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return True
    if isinstance(value, (list, tuple)):
        return any(_has_bool(v) for v in value)
    if isinstance(value, np.ndarray):
        return value.dtype.kind == "b" or (
            value.dtype == object and any(_has_bool(v) for v in value.ravel())
        )
    return False


def real_array(what: str, value: object) -> np.ndarray:
    """``value`` as an array of finite floats, or :class:`ParameterError` naming ``what``:
    a boolean, a string, None or an array holding one is not a number (numpy would take
    ``True`` for 1 and ``'2'`` for 2), nor is a ragged list; a masked array is refused
    (numpy would compute its masked entries)."""
    if value is None or isinstance(value, (str, bytes)) or _has_bool(value):
        raise _not_a_number(what, value)
    if isinstance(value, np.ma.MaskedArray):  # numpy would drop the mask silently
        raise ParameterError(
            f"{what} must not be a masked array (its masked entries would be computed as "
            "numbers): give the values to compute, e.g. values.compressed()"
        )
    try:
        arr = np.asarray(value)
        if arr.dtype == object:
            arr = np.asarray(arr.tolist())
    except (TypeError, ValueError):
        raise _not_a_number(what, value) from None
    if arr.dtype.kind not in "iuf":
        raise _not_a_number(what, value)
    arr = arr.astype(float)
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{what} must be finite, got {_brief(value)}")
    return arr


def _not_a_number(what: str, value: object) -> ParameterError:
    """The error of a value that is not a number (made only when raised: the value's
    ``repr`` costs more than the check on every stroke batch of a search)."""
    return ParameterError(f"{what} must be a number or an array of numbers, got {_brief(value)}")


def _brief(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _as_float_array(name: str, value: object) -> np.ndarray:
    return real_array(f"parameter {name!r}", value)


def _checked(spec: ParamSpec, value: object) -> float | np.ndarray:
    """``value`` of parameter ``spec`` as a float (a scalar) or an array of floats,
    checked.  A finite Python or numpy float (or int) within the bounds takes a short
    path with the same result: a search's stroke batches check some 25 scalars each."""
    if type(value) in _PLAIN_NUMBERS:
        number = float(value)
        if math.isfinite(number) and _above_lower(spec, number) and _below_upper(spec, number):
            return number
    arr = _as_float_array(spec.name, value)
    _check_bounds(spec, arr)
    return _scalar(arr)


#: The types :func:`_checked` takes the short path for (exact types: not bool).
_PLAIN_NUMBERS = (float, int, np.float64)


def _above_lower(spec: ParamSpec, x):
    """Whether ``x`` (a float, or elementwise an array) is within the lower bound."""
    if spec.lower is None:
        return True
    return x > spec.lower if spec.strict else x >= spec.lower


def _below_upper(spec: ParamSpec, x):
    """Whether ``x`` (a float, or elementwise an array) is within the upper bound."""
    return True if spec.upper is None else x <= spec.upper


def _check_bounds(spec: ParamSpec, arr: np.ndarray, kind: str = "parameter") -> None:
    lo, hi = spec.lower, spec.upper
    unit = "" if spec.unit == "1" else f" {spec.unit}"  # a dimensionless bound reads bare
    if not np.all(_above_lower(spec, arr)):
        rel = ">" if spec.strict else ">="
        raise ParameterError(f"{kind} {spec.name!r} must be {rel} {lo:g}{unit}, got {_show(arr)}")
    if not np.all(_below_upper(spec, arr)):
        raise ParameterError(f"{kind} {spec.name!r} must be <= {hi:g}{unit}, got {_show(arr)}")


def _show(arr: np.ndarray) -> str:
    return f"{arr.item():g}" if arr.size == 1 else f"values in [{arr.min():g}, {arr.max():g}]"


def parse_value(name: str, text: str) -> float | str:
    """Parse a ``--set KEY=VALUE`` value: a float for parameters, a choice for readings."""
    if name in CHOICES:
        return text
    if name not in PARAMETERS:
        raise ParameterError(f"unknown parameter {name!r} (known: {', '.join(known_names())})")
    try:
        value = float(text)
    except ValueError:
        raise ParameterError(f"parameter {name!r} must be a number, got {text!r}") from None
    return value


def known_names() -> list[str]:
    """All names accepted by :func:`resolve_params`."""
    return [*PARAMETERS, *CHOICES]


def two_body_period(ball_mass, racket_mass, k_contact):
    """Period ``T`` of the ball-racket oscillator, Eq. 12: ``2 pi sqrt(mu/k)`` (s).

    ``mu = m_b M2 / (m_b + M2)`` is the reduced mass; the contact of two free bodies
    lasts ``T/2``.
    """
    mu = ball_mass * racket_mass / (ball_mass + racket_mass)
    return 2.0 * math.pi * np.sqrt(mu / k_contact)


_LEAD_FRACTION = {"half_period": 0.5, "quarter_period": 0.25, "zero": 0.0}
#: I_cm / (M L^2) of each rod by the ``inertia`` reading.
_INERTIA_FACTOR = {"uniform_rod": 1.0 / 12.0, "paper_text": 0.5}


def choice_value(table: Mapping[str, float], choice: str | np.ndarray) -> float | np.ndarray:
    """The number ``table`` gives a checked choice: a float for one choice, an array of
    floats for one choice per stroke (the same numbers element by element)."""
    if isinstance(choice, str):
        return table[choice]
    return np.array([table[c] for c in choice.ravel().tolist()], float).reshape(choice.shape)


def _choice(reading: Reading, choice: object) -> str | np.ndarray:
    """A checked choice of ``reading``: one string, or an array of strings (one per
    stroke: several readings computed in one batch)."""
    if isinstance(choice, np.ndarray) and choice.dtype.kind in "UO":
        values = choice.astype(object)
        for value in dict.fromkeys(values.ravel().tolist()):
            _one_choice(reading, value)
        return values
    return _one_choice(reading, choice)


def _one_choice(reading: Reading, choice: object) -> str:
    if not isinstance(choice, str) or choice not in reading.choices:
        kind = "reading" if reading.name in READINGS else "model option"
        raise ParameterError(
            f"{kind} {reading.name!r} must be one of {', '.join(reading.choices)}, got {choice!r}"
        )
    return choice


def resolve_params(overrides: Mapping[str, object] | None = None) -> dict[str, object]:
    """Validate parameters and readings and fill in the derived quantities.

    Parameters
    ----------
    overrides : mapping, optional
        Parameter values (scalars or arrays that broadcast together) and reading choices
        (strings, or arrays of strings: one choice per stroke, as the claims' searches
        give several readings in one batch) that replace the defaults.

    Returns
    -------
    dict
        Every parameter of :data:`PARAMETERS` (float or ndarray, SI units) and every
        reading and model option of :data:`CHOICES` (str, or an object array of str).
        Derived values: ``I1_cm = f M1 L1^2`` and ``I2_cm = f M2 L2^2`` with ``f =
        1/12`` (``uniform_rod``) or ``1/2`` (``paper_text``); ``contact_lead`` = the
        fraction of ``T`` (Eq. 12) set by ``contact_lead_rule``.

    Raises
    ------
    ParameterError
        Not a mapping; unknown name, non-numeric, non-finite or out-of-bounds value,
        unknown choice.
    """
    if overrides is None:
        overrides = {}
    if not isinstance(overrides, Mapping):
        raise ParameterError(
            "params must be a mapping of names to values, e.g. {'M2': 0.5}, got "
            f"{_brief(overrides)}"
        )
    overrides = dict(overrides)
    out: dict[str, object] = {}
    for name, reading in CHOICES.items():
        out[name] = _choice(reading, overrides.pop(name, reading.default))

    unknown = [k for k in overrides if k not in PARAMETERS]
    if unknown:
        raise ParameterError(
            f"unknown parameter {unknown[0]!r} (known: {', '.join(known_names())})"
        )
    for name, spec in PARAMETERS.items():
        if name in overrides:
            out[name] = _checked(spec, overrides[name])
        else:
            out[name] = spec.default
    factor = choice_value(_INERTIA_FACTOR, out["inertia"])
    if out["I1_cm"] is None:
        out["I1_cm"] = _scalar(factor * np.asarray(out["M1"]) * np.asarray(out["L1"]) ** 2)
    if out["I2_cm"] is None:
        out["I2_cm"] = _scalar(factor * np.asarray(out["M2"]) * np.asarray(out["L2"]) ** 2)
    if out["contact_lead"] is None:
        period = two_body_period(out["ball_mass"], out["M2"], out["k_contact"])
        fraction = choice_value(_LEAD_FRACTION, out["contact_lead_rule"])
        out["contact_lead"] = _scalar(fraction * period)
    try:
        np.broadcast_shapes(*(np.shape(out[n]) for n in PARAMETERS))
    except ValueError:
        raise ParameterError("parameter arrays do not broadcast to one shape") from None
    return out


def _scalar(arr: np.ndarray) -> float | np.ndarray:
    """A 0-d array becomes a Python float (so JSON and netCDF attributes stay plain)."""
    arr = np.asarray(arr, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def one_stroke(caller: str, resolved: Mapping[str, object], theta0: object, delta0: object) -> None:
    """Refuse arrays where ``caller`` computes one stroke (``strike``, ``solve_stroke``):
    the initial angles and every resolved parameter and choice must be one value each
    (an array's other values would be dropped); :class:`ParameterError` naming the
    first that is not."""
    named = {"initial angle 'theta0'": theta0, "initial angle 'delta0'": delta0}
    named.update((f"parameter {k!r}", v) for k, v in resolved.items())
    for what, value in named.items():
        try:
            size = np.size(value)
        except ValueError:  # a ragged list: real_array names it
            size = 1
        if size != 1:
            raise ParameterError(
                f"{caller} computes one stroke: {what} must be one value, got "
                f"{_brief(value)} (strike_batch takes arrays)"
            )


def scalar_params(params: Mapping[str, object]) -> dict[str, object]:
    """The resolved parameters that are scalars (for file attributes and JSON)."""
    return {k: v for k, v in params.items() if np.ndim(v) == 0}
