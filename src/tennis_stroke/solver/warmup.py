"""Compile (and cache) one group of the solver's entry points: ``python -m
tennis_stroke.solver.warmup GROUP``, the process
:func:`tennis_stroke.solver.compiled.ensure_compiled` starts when the cache lacks the
group.  Each group's exercise (the calls that compile it, with the argument types the
package passes) lives in the module that owns its entry points; this module, above them,
finds it by group, and so does a caller above the solver that wants a group loaded
before it times anything (:func:`ready`).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from functools import partial

from .compiled import GROUPS, ensure_compiled


def exercise(group: str) -> Callable[[], object]:
    """The function that calls the entry points of ``group`` (one of
    :data:`~tennis_stroke.solver.compiled.GROUPS`); scipy is imported by the
    ``reference`` and ``rk4`` groups only."""
    if group not in GROUPS:
        raise ValueError(f"unknown group of compiled entry points {group!r}")
    if group == "rk4":
        from .rk4 import exercise_rk4

        return exercise_rk4
    if group == "reference":
        from .reference import exercise_reference

        return exercise_reference
    if group == "curves":
        from .curves import exercise_curves

        return exercise_curves
    from .stroke import exercise_batch, exercise_contact

    kind, method = group.split(":")
    return partial(exercise_batch if kind == "batch" else exercise_contact, method)


def ready(group: str) -> None:
    """Load ``group`` from the compiled code's cache now (compiling it first if the cache
    lacks it), for a caller that times what follows."""
    ensure_compiled(group, exercise(group))


if __name__ == "__main__":
    exercise(sys.argv[1])()
