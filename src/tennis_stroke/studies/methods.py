"""The integrators a study can name: ``family.NAME``, checked against those that exist."""

from __future__ import annotations

from ..solver.settings import METHOD_IDS

#: Method names by family: the compiled solver, scipy's ``solve_ivp``, fixed-step RK4.
METHODS = {
    "tennis_stroke": tuple(METHOD_IDS),
    "scipy": ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA"),
    "fixed": ("RK4",),
}


def parse_method(method: str) -> tuple[str, str]:
    """``"family.NAME"`` -> ``(family, NAME)``; a ``ValueError`` (one line) names the
    methods that exist when ``method`` is not one of them."""
    family, _, name = str(method).partition(".")
    if name not in METHODS.get(family, ()):
        known = ", ".join(f"{f}.{n}" for f, names in METHODS.items() for n in names)
        raise ValueError(f"unknown method {method!r} (known: {known})")
    return family, name
