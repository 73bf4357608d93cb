"""A stroke over time as an ``xarray.Dataset``: the joint angles and rates, the elbow,
the racket's points and the ball in the lab frame, with the stroke's result fields, each
variable with its ``units`` and ``long_name`` from the one table
(:data:`tennis_stroke.io.units.VARIABLES`), so that plots label themselves.

The numbers are those of :meth:`tennis_stroke.solver.reference.ReferenceStroke.lab_frame`
(every quantity from :mod:`tennis_stroke.model.dynamics`); this module only names them.
It sits in the io layer because it reads both the solver's result and the units table,
which the solver may not import.

Example: the speeds of the ball and of the racket's hitting point through Fig. 4's
stroke a (``examples/stroke_speeds.py`` draws them):

>>> from tennis_stroke import solve_stroke, stroke_dataset
>>> ds = stroke_dataset(solve_stroke(120.0, 81.5, follow_through=0.05))
>>> print(ds["speed_hit"].attrs["units"], ds["speed_hit"].attrs["long_name"])
m/s hitting point speed (lab frame)
>>> print(f"{float(ds['v_out']):.2f} {ds['v_out'].attrs['units']}")
155.68 km/h
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..model.params import ParameterError, real_array
from ..solver.reference import ReferenceStroke
from ..solver.results import COUNT_FIELDS, RESULT_FIELDS
from .netcdf import result_dataset
from .units import cf_attrs

#: Sample times of :func:`stroke_dataset` when none are given: this many evenly over the
#: simulated span, and as many again over the contact (a few milliseconds).
DEFAULT_SAMPLES = 1001
#: The quantities of :meth:`ReferenceStroke.lab_frame` that are angles: radians there,
#: degrees in the dataset (the unit of the table, as in the result files).
ANGLES = ("theta", "phi")


def sample_times(stroke: ReferenceStroke, samples: int = DEFAULT_SAMPLES) -> np.ndarray:
    """``samples`` times (s) evenly over the simulated span of ``stroke`` and as many over
    its contact (from its start to separation, when both are known), sorted, no repeats."""
    if not stroke.segments:
        return np.zeros(0)
    times = [np.linspace(stroke.segments[0].t0, stroke.segments[-1].t1, samples)]
    t_c = stroke.result.get("t_contact_start", np.nan)
    t_sep = stroke.result.get("t_separation", np.nan)
    if np.isfinite(t_c) and np.isfinite(t_sep) and t_sep > t_c:
        times.append(np.linspace(t_c, t_sep, samples))
    return np.unique(np.concatenate(times))


def _checked_times(times: object) -> np.ndarray:
    """``times`` as a 1-D array of finite floats in increasing order, or
    :class:`tennis_stroke.model.params.ParameterError` saying what is wrong."""
    arr = real_array("the sample times", times)
    if arr.ndim > 1:
        raise ParameterError(f"the sample times must be one-dimensional, got shape {arr.shape}")
    arr = np.atleast_1d(arr)
    if np.any(np.diff(arr) <= 0.0):
        raise ParameterError("the sample times must increase strictly")
    return arr


def stroke_dataset(stroke: ReferenceStroke, times: object = None) -> xr.Dataset:
    """The stroke ``stroke`` (from :func:`tennis_stroke.solve_stroke`) over time, in the
    lab frame, as a dataset on the time axis ``t`` (s).

    Parameters
    ----------
    stroke : ReferenceStroke
        A solved stroke; give it a ``follow_through`` to see the swing after the ball
        has left.
    times : array_like, optional
        Sample times (s), one-dimensional and increasing; default :func:`sample_times`.

    Returns
    -------
    xarray.Dataset
        On ``t``: ``theta, phi`` (degree, from ``-y``, counter-clockwise),
        ``omega1, omega2`` (rad/s, clockwise), the elbow's, the wrist's, the racket end's and the
        hitting point's positions (``x_*, y_*``, m) and velocities (``vx_*, vy_*``, m/s),
        the hitting point's speed ``speed_hit`` (m/s), and the ball's ``x_ball`` (m) and
        ``vx_ball`` (m/s) along x, NaN outside the simulated stroke
        (:meth:`tennis_stroke.solver.reference.ReferenceStroke.lab_frame`).  Scalars:
        the result fields (``v_out`` in km/h, ``t_contact_start`` and ``t_separation``
        in s, ...; ``status`` with its ``flag_meanings``).  Global attributes: the
        parameters, the readings and the integrator (as in the result files).

    Raises
    ------
    ParameterError
        If ``stroke`` is not a :class:`tennis_stroke.solver.reference.ReferenceStroke`
        or ``times`` are not finite numbers in increasing order.
    """
    if not isinstance(stroke, ReferenceStroke):
        raise ParameterError(
            f"stroke must be a ReferenceStroke (from solve_stroke), got {type(stroke).__name__}"
        )
    times = sample_times(stroke) if times is None else _checked_times(times)
    lab = stroke.lab_frame(times)
    results = {}
    for name in RESULT_FIELDS:
        value = stroke.result.get(name, np.nan)
        results[name] = np.int64(value) if name in COUNT_FIELDS and np.isfinite(value) else value
    ds = result_dataset(results, {}, stroke.params, stroke.solver)
    ds = ds.assign_coords(t=("t", times, cf_attrs("t")))
    for name, values in lab.items():
        values = np.degrees(values) if name in ANGLES else values
        ds[name] = ("t", values, cf_attrs(name))
    return ds
