"""Compile (and cache) one group of the solver's entry points: ``python -m
tennis_stroke.solver.warmup GROUP`` (:func:`tennis_stroke.solver.compiled.ensure_compiled`
runs it in a process of its own, then calls :func:`warm_up` in its own process to load
the group from the cache and check the load).
"""

from __future__ import annotations

import sys


def warm_up(group: str) -> None:
    """Compile (and cache) the entry points of ``group`` with the argument types the
    package passes."""
    import numpy as np

    from ..model.dynamics import coefficients
    from ..model.params import resolve_params
    from .settings import SolverSettings
    from .stroke import solve_contact, strike_batch

    if group == "rk4":  # the model functions RK4 and the studies call from Python
        import math

        from ..model.dynamics import (
            compression_angles,
            contact_duration,
            effective_mass,
            hit_offset,
            mechanical_energy,
        )
        from .rk4 import contact_missed, fixed_phase, fixed_step_stroke

        fixed_step_stroke(120.0, 81.5, {}, 1e-3)  # the work-precision study's strokes
        cf_row = coefficients(resolve_params({}), 120.0, 81.5)[0]
        y0 = np.array([1.0, 0.0, 10.0, 30.0, 0.0, 20.0])
        trig = (math.sin(1.0), math.cos(1.0), math.sin(0.0), math.cos(0.0))
        hit_offset(trig[0], trig[2], cf_row)  # the stability study's isolated contact
        effective_mass(*trig, cf_row)
        contact_duration(*trig, cf_row)
        mechanical_energy(0.0, y0, cf_row, True)
        contact_missed(cf_row, 0.0, y0, 1e-4, 0.01)
        fixed_phase(cf_row, 0.0, y0, 0.01, 1e-4, True, compression_angles)
        from scipy.integrate import solve_ivp

        from ..model.dynamics import angle_rhs

        for method in ("Radau", "LSODA"):  # their Jacobians pass states of another layout
            solve_ivp(angle_rhs(cf_row, 0.0, True), (0.0, 1e-3), y0, method=method)
        return
    if group == "reference":  # scipy's path: imported only here
        from .reference import free_swing, solve_stroke

        solve_stroke(120.0, 81.5, rtol=1e-6, atol=1e-6)
        free_swing(120.0, 81.5, 0.05)
        return
    kind, method = group.split(":")
    settings = SolverSettings(method=method)
    if kind == "batch":
        strike_batch(np.array([90.0, 120.0]), 45.0, settings=settings, threads=1)
    else:
        cf_row = coefficients(resolve_params({}), 120.0, 81.5)[0]
        solve_contact(cf_row, np.array([1.0, 0.0, 10.0, 30.0, 0.0, 20.0]), 0.01, settings)


def load(group: str) -> None:
    """:func:`warm_up` in this process with numba's compiling refused: the entry points
    load from the cache, or :class:`~tennis_stroke.solver.compiled.CompileInPlace` says
    the cache lacks one (:func:`tennis_stroke.solver.compiled.ensure_compiled`)."""
    from .stroke import refusing_compiles

    with refusing_compiles():
        warm_up(group)


if __name__ == "__main__":
    warm_up(sys.argv[1])
