"""The integrators a study can name: ``family.NAME``, checked against those that exist."""

from __future__ import annotations

import math

from ..solver.settings import METHOD_IDS, SolverSettings

#: The initial angles (degree) over which the optimum-cost study searches the Figs. 5-6
#: optimum (:func:`tennis_stroke.studies.optimum_cost.optimum_cost`): the paper's ranges.
OPTIMUM_THETA0_RANGE = (60.0, 120.0)
OPTIMUM_DELTA0_RANGE = (0.0, 100.0)

#: Method names by family: the compiled solver, scipy's ``solve_ivp``, fixed-step RK4.
METHODS = {
    "tennis_stroke": tuple(METHOD_IDS),
    "scipy": ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA"),
    "fixed": ("RK4",),
}
#: The smallest step (s) of fixed-step RK4 a study may take: 5e4 steps over the 0.5 s of
#: the stability study's contact, each a Python call.  A smaller step is a typo whose job
#: would compute for days (``rk4_steps: [1.0e-12]``, issue 56), refused before any job.
MIN_RK4_STEP = 1.0e-5


def parse_method(method: str) -> tuple[str, str]:
    """``"family.NAME"`` -> ``(family, NAME)``; a ``ValueError`` (one line) names the
    methods that exist when ``method`` is not one of them."""
    family, _, name = str(method).partition(".")
    if name not in METHODS.get(family, ()):
        known = ", ".join(f"{f}.{n}" for f, names in METHODS.items() for n in names)
        raise ValueError(f"unknown method {method!r} (known: {known})")
    return family, name


def check_case(method: str, setting: float) -> tuple[str, str]:
    """``(family, name)`` of a stability case ``(method, setting)``, or a one-line
    ``ValueError``: the method must exist (:func:`~tennis_stroke.studies.methods.parse_method`)
    and the setting be a tolerance or RK4 step > 0 (compiled methods: any
    :class:`~tennis_stroke.solver.settings.SolverSettings` tolerance, the accuracy bound
    lifted: this study measures how loose tolerances fail)."""
    family, name = parse_method(method)
    if not (
        isinstance(setting, int | float)
        and not isinstance(setting, bool)
        and math.isfinite(setting)
        and setting > 0
    ):
        what = "RK4 step (s)" if family == "fixed" else "tolerance"
        raise ValueError(f"{what} of case {method!r} must be a number > 0, got {setting!r}")
    if family == "fixed" and setting < MIN_RK4_STEP:
        raise ValueError(
            f"RK4 step of case {method!r} must be at least {MIN_RK4_STEP:g} s "
            f"(studies.methods.MIN_RK4_STEP), got {setting!r}"
        )
    if family == "tennis_stroke":
        SolverSettings(method=name, rtol=setting, atol=setting, accuracy_bound=False)
    return family, name
