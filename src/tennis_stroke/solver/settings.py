"""Settings of the compiled solver: methods, tolerances and limits, validated."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ..model.params import ParameterError

#: Method ids (runtime integers of the compiled code) and orders of the solution.
METHOD_DP54, METHOD_DOP853 = 0, 1
METHOD_IDS = {"DP54": METHOD_DP54, "DOP853": METHOD_DOP853}
ORDERS = {"DP54": 5, "DOP853": 8}

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
        Relative and absolute tolerance of the local error (scaled RMS norm).  The
        defaults keep every stroke of the benchmark grid within 1e-5 km/h of an rtol
        1e-12 solution (``benchmarks/bench_sweep.py``).
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

    def __post_init__(self) -> None:
        if self.method not in METHOD_IDS:
            raise ParameterError(
                f"solver method must be one of {', '.join(METHOD_IDS)}, got {self.method!r}"
            )
        for name in ("rtol", "atol", "t_max", "first_step", "contact_min_steps"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise ParameterError(f"solver setting {name!r} must be > 0, got {value!r}")
        if not (math.isfinite(self.follow_through) and self.follow_through >= 0):
            raise ParameterError(
                f"solver setting 'follow_through' must be >= 0, got {self.follow_through!r}"
            )
        for name in ("max_steps", "history"):
            if int(getattr(self, name)) < 1:
                raise ParameterError(f"solver setting {name!r} must be >= 1")

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
        """Plain dict (for file attributes and JSON)."""
        return asdict(self)
