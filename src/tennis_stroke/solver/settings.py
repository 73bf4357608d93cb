"""Settings of the compiled solver: methods, tolerances and limits, validated."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, fields

import numpy as np

from ..model.params import ParameterError

#: Method ids (compile-time literals of the compiled code) and orders of the solution.
METHOD_DP54, METHOD_DOP853 = 0, 1
METHOD_IDS = {"DP54": METHOD_DP54, "DOP853": METHOD_DOP853}
ORDERS = {"DP54": 5, "DOP853": 8}

#: Loosest tolerances (rtol, atol) a result may be computed with.  Measured: every stroke
#: of the maps of Figs. 2 and 3 (241 x 181), 8 (201 x 121) and 13 (181 x 41), both
#: methods, against rtol = atol = 1e-12 (``benchmarks/tolerance_bound.py``).  At
#: rtol = atol = 1e-4 the largest errors are 0.16 km/h (v_out), 0.11 rad/s (omega),
#: 0.14 degree (theta) and 0.07 ms (event times): at least six times below the claims'
#: tolerances (1 km/h, 0.5 rad/s, 1 degree, 2 ms).  At 1e-3 DP54 misses 1 km/h (1.3 km/h
#: on Fig. 8) and DOP853 0.5 rad/s (0.58); at 1e-2 DOP853 is 2.3 km/h off on Fig. 2; from
#: 0.3 strokes blow up (v_out 7e14 km/h) while reporting ``ok``.  atol alone (rtol 5e-8):
#: 1e-3 stays within 0.012 km/h, 1e-2 is 1.9 degree off.
MAX_RTOL = 1e-4
MAX_ATOL = 1e-4
#: Tightest relative tolerance: 100 machine epsilons, the floor scipy's ``solve_ivp``
#: raises a smaller ``rtol`` to (a step's error cannot be held below the rounding of its
#: arithmetic: ``rtol = atol = 1e-300`` ended every stroke in ``step_failure``).  A tiny
#: ``atol`` is fine beside it (rtol 1e-12, atol 1e-300: the same stroke within 3e-12 km/h).
MIN_RTOL = 100 * float(np.finfo(float).eps)
#: Why the bounds are what they are, for the one-line message.
ACCURACY_REASON = (
    "the loosest tolerance at which the paper's maps stay well within the claims' "
    "tolerances of 1 km/h, 0.5 rad/s and 1 degree"
)


class SolverSettingError(ParameterError):
    """A solver setting is out of range; ``setting`` names it (message is one line)."""

    def __init__(self, setting: str, message: str) -> None:
        super().__init__(message)
        self.setting = setting


# Layout of the settings array.
S_RTOL, S_ATOL, S_TMAX, S_FIRST_STEP, S_MAX_STEPS, S_CONTACT_STEPS, S_FOLLOW = range(7)


@dataclass(frozen=True)
class SolverSettings:
    """Settings of the compiled solver.

    Attributes
    ----------
    method : {"DOP853", "DP54"}
        Embedded Runge-Kutta pair.
    rtol, atol : float
        Relative and absolute tolerance of the local error (scaled RMS norm), at most
        :data:`MAX_RTOL` and :data:`MAX_ATOL` (the accuracy bound); ``rtol`` at least
        :data:`MIN_RTOL`.  The defaults keep
        every stroke of the benchmark grid within 1e-5 km/h of an rtol 1e-12 solution
        (``benchmarks/bench_sweep.py``).
    t_max : float
        Longest simulated stroke (s); no ``phi = 0`` or no release before it is a status.
    first_step : float
        First trial step (s).
    max_steps : int
        Largest number of accepted steps per stroke.
    contact_min_steps : float
        The contact phase takes steps no longer than (two-body contact duration at the
        hitting point's effective mass) / ``contact_min_steps``, so no step can jump over
        the contact.
    follow_through : float
        Free swing simulated after separation for ``omega2_max`` (s).
    history : int
        Swing steps remembered to restart at the contact start.
    accuracy_bound : bool
        ``rtol`` and ``atol`` at most :data:`MAX_RTOL` and :data:`MAX_ATOL` (default).
        ``False`` lifts the bound, only for studies that measure how the solver fails at
        loose tolerances (:mod:`tennis_stroke.studies.stability`): such results are not
        within the claims' accuracy.

    Raises
    ------
    SolverSettingError
        A setting out of range (a :class:`tennis_stroke.model.params.ParameterError`).
    """

    method: str = "DOP853"
    rtol: float = 5e-8
    atol: float = 5e-8
    t_max: float = 1.0
    first_step: float = 0.02
    max_steps: int = 100_000
    contact_min_steps: float = 2.0
    follow_through: float = 0.0
    history: int = 512
    accuracy_bound: bool = field(default=True, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.method, str) or self.method not in METHOD_IDS:
            raise SolverSettingError(
                "method",
                f"solver method must be one of {', '.join(METHOD_IDS)}, got {self.method!r}",
            )
        for name in ("rtol", "atol", "t_max", "first_step", "contact_min_steps"):
            value = getattr(self, name)
            if not (_is_number(value) and math.isfinite(value) and value > 0):
                raise SolverSettingError(
                    name, f"solver setting {name!r} must be > 0, got {value!r}"
                )
        if self.rtol < MIN_RTOL:
            raise SolverSettingError(
                "rtol",
                f"solver setting 'rtol' must be >= {MIN_RTOL:.3g} (100 machine epsilons: no "
                f"step's error can be held below the rounding), got {self.rtol!r}",
            )
        if self.accuracy_bound:
            for name, bound in (("rtol", MAX_RTOL), ("atol", MAX_ATOL)):
                if getattr(self, name) > bound:
                    raise SolverSettingError(
                        name,
                        f"solver setting {name!r} must be <= {bound:g} ({ACCURACY_REASON}), "
                        f"got {getattr(self, name)!r}",
                    )
        if not (
            _is_number(self.follow_through)
            and math.isfinite(self.follow_through)
            and self.follow_through >= 0
        ):
            raise SolverSettingError(
                "follow_through",
                f"solver setting 'follow_through' must be >= 0, got {self.follow_through!r}",
            )
        for name in ("max_steps", "history"):
            value = getattr(self, name)
            if not (_is_number(value) and math.isfinite(value) and value == int(value) >= 1):
                raise SolverSettingError(
                    name, f"solver setting {name!r} must be a whole number >= 1, got {value!r}"
                )

    def as_array(self) -> np.ndarray:
        """The numeric settings in the compiled layout ``S_*``."""
        return np.array(
            [
                self.rtol,
                self.atol,
                self.t_max,
                self.first_step,
                float(self.max_steps),
                self.contact_min_steps,
                self.follow_through,
            ]
        )

    def as_dict(self) -> dict[str, object]:
        """Plain dict (for file attributes and JSON); ``accuracy_bound`` only when lifted."""
        out = asdict(self)
        if out.pop("accuracy_bound"):
            return out
        return {**out, "accuracy_bound": 0}


def _is_number(value: object) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)


def solver_settings(value: object) -> SolverSettings:
    """``value`` as :class:`SolverSettings`: None gives the defaults, a mapping its
    keyword arguments; anything else is refused with :class:`SolverSettingError`."""
    if value is None:
        return SolverSettings()
    if isinstance(value, SolverSettings):
        return value
    if isinstance(value, Mapping):
        unknown = sorted(set(map(str, value)) - {f.name for f in fields(SolverSettings)})
        if unknown:
            raise SolverSettingError(
                unknown[0],
                f"unknown solver setting {unknown[0]!r} (known: "
                f"{', '.join(f.name for f in fields(SolverSettings))})",
            )
        return SolverSettings(**value)
    raise SolverSettingError(
        "settings", f"settings must be a SolverSettings or a mapping, got {value!r}"
    )


def thread_count(value: object) -> int:
    """``value`` as a number of threads (a whole number >= 1), or :class:`ParameterError`."""
    if not (_is_number(value) and math.isfinite(value) and value == int(value) and value >= 1):
        raise ParameterError(f"threads must be a whole number >= 1, got {value!r}")
    return int(value)
