"""Measured orders: each integrator at fixed steps on a smooth stretch of the swing, its
error against the step and the fitted slope beside the theoretical order.

The stretch is the free swing of one stroke of the default model from rest over
``(0, t_end)``, a span without a torque switch (checked), so the solution is smooth and
a method of order ``p`` has a global error close to ``C h**p``.  The compiled
integrators take their steps with the compiled kernel
(:func:`tennis_stroke.solver.integrate.rk_step`: the step fixed, the error estimate
unused), fixed-step RK4 with :func:`tennis_stroke.solver.rk4.rk4_step`; the reference is
scipy's DOP853 at rtol = atol = 1e-13, independent of both.  The error is the largest of
the ``omega1`` and ``omega2`` errors at ``t_end`` (rad/s); the slope is the least-squares
slope of log error against log step.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from scipy.integrate import solve_ivp

from ..io.netcdf import provenance
from ..io.units import cf_attrs
from ..model.dynamics import (
    A_OMEGA1,
    A_OMEGA2,
    CF_PHI0,
    CF_THETA0,
    OMEGA1,
    OMEGA2,
    angle_rhs,
    coefficients,
    next_switch,
    rhs_trig,
    to_trig,
    wrist_torque,
)
from ..model.params import resolve_params
from ..solver._kernels import coefficient_tuple
from ..solver.integrate import rk_step, specialised
from ..solver.rk4 import rk4_step
from ..solver.settings import METHOD_IDS, ORDERS
from .sampling import REFERENCE

#: The theoretical order of each method of the convergence plot.
THEORETICAL_ORDERS = {**ORDERS, "RK4": 4}
#: Each method's name in the other studies (``family.NAME``).
STUDY_NAMES = {"DP54": "tennis_stroke.DP54", "DOP853": "tennis_stroke.DOP853", "RK4": "fixed.RK4"}
#: The reference's rtol = atol (scipy DOP853).
REFERENCE_TOL = 1e-13


def _reference(cf: np.ndarray, c2: float, t_end: float) -> np.ndarray:
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    sol = solve_ivp(
        angle_rhs(cf, c2, False),
        (0.0, t_end),
        y0,
        method="DOP853",
        rtol=REFERENCE_TOL,
        atol=REFERENCE_TOL,
    )
    return sol.y[[A_OMEGA1, A_OMEGA2], -1]


def _fixed(method: str, count: int, cf: np.ndarray, c2: float, t_end: float) -> np.ndarray:
    """``omega1, omega2`` at ``t_end`` after ``count`` equal steps of ``method``."""
    h = t_end / count
    y0 = np.array([cf[CF_THETA0], cf[CF_PHI0], 0.0, 0.0])
    if method == "RK4":
        fun, y = angle_rhs(cf, c2, False), y0
        for i in range(count):
            y = rk4_step(fun, i * h, y, h)
        return y[[A_OMEGA1, A_OMEGA2]]
    cft, y = coefficient_tuple(cf), to_trig(y0)
    f = rhs_trig(0.0, y, cft, c2, False)
    step = specialised(rk_step, METHOD_IDS[method], False, 0.0, y, f, h, cft, c2, 1.0, 1.0)
    for i in range(count):
        y, f, _ = step(False, i * h, y, f, h, cft, c2, 1.0, 1.0)
    return np.array([y[OMEGA1], y[OMEGA2]])


def convergence(
    theta0: float, delta0: float, t_end: float, counts: Mapping[str, Sequence[int]]
) -> xr.Dataset:
    """Error at ``t_end`` (s) of the swing from ``(theta0, delta0)`` (degree) for each
    method of ``counts`` (``DP54``, ``DOP853``, ``RK4``) after each number of equal
    steps; dims ``method`` x ``point``, with the fitted ``slope`` and the ``order``."""
    cf = coefficients(resolve_params({}), theta0, delta0)[0]
    if next_switch(0.0, cf, t_end) < t_end:
        raise ValueError(f"the wrist torque switches inside (0, {t_end:g} s): not smooth")
    c2 = wrist_torque(0.0, t_end, cf)
    ref = _reference(cf, c2, t_end)
    methods = list(counts)
    width = max(len(c) for c in counts.values())
    step, error = np.full((len(methods), width), np.nan), np.full((len(methods), width), np.nan)
    slope = np.full(len(methods), np.nan)
    for mi, method in enumerate(methods):
        for pi, count in enumerate(counts[method]):
            step[mi, pi] = t_end / count
            error[mi, pi] = float(np.max(np.abs(_fixed(method, count, cf, c2, t_end) - ref)))
        keep = np.isfinite(error[mi])
        slope[mi] = np.polyfit(np.log(step[mi, keep]), np.log(error[mi, keep]), 1)[0]
    dims = ("method", "point")
    ds = xr.Dataset(
        {
            "step": (dims, step, cf_attrs("step")),
            "omega_error": (dims, error, cf_attrs("omega_error")),
            "slope": ("method", slope, cf_attrs("slope")),
            "order": ("method", [THEORETICAL_ORDERS[m] for m in methods], cf_attrs("order")),
        },
        coords={
            "method": ("method", [STUDY_NAMES[m] for m in methods], cf_attrs("method")),
            "point": ("point", np.arange(width), cf_attrs("point")),
        },
    )
    ds.attrs.update(provenance(resolve_params(), REFERENCE))
    ds.attrs.update(
        theta0_deg=float(theta0),
        delta0_deg=float(delta0),
        t_end_s=float(t_end),
        reference=f"scipy DOP853, rtol = atol = {REFERENCE_TOL:g}",
        solver_settings_of="none: every method takes fixed steps",
    )
    return ds


def convergence_study(
    theta0: float, delta0: float, t_end: float, counts: Mapping[str, Sequence[int]]
) -> xr.Dataset:
    """The convergence plot's data from the config (``solver_study.convergence``)."""
    return convergence(theta0, delta0, t_end, counts)
