"""Measurements of the paper's claims: functions of result files returning a number for
each reading.

A claim of ``config/claims.yaml`` names one of :data:`MEASUREMENTS` (without the
``measure_`` prefix) and its arguments.  Qualitative claims are measurements returning 1
(true) or 0 (false).  The figures use some of them to mark what the claims read.  Each
measurement says the unit of its value (:func:`gives`), from the one table of units
(:mod:`tennis_stroke.io.units`) where it is a file's variable or coordinate, so a claim
states the unit its measure gives (:func:`measurement_unit`).

Each measurement reads one or more :class:`Stack` s: a result file under ``n`` readings,
each variable an array with a leading reading axis, and returns ``n`` values, one per
reading.  The robustness analysis measures a claim under every reading of a chunk in one
call; the claims job, the ladder and the validation measure one reading, the case
``n = 1``.  Called with datasets (``xr.Dataset``) instead, a measurement reads them as
one reading and returns a float (:func:`one_or_many`).
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Literal

import numpy as np

if TYPE_CHECKING:  # imported where a dataset is read: planning checks claims without it
    import xarray as xr

from ..io.units import unit_of
from ..solver.results import OK

#: The unit of a qualitative measurement's value: 1 (true) or 0 (false).
QUALITATIVE_UNIT = "1"


class Stack:
    """One result file under ``n`` readings: each variable (a data variable or a
    coordinate) an array whose first axis is the reading, stacked from the readings'
    datasets when first read (or given whole: :meth:`of_arrays`).  The datasets must
    have the same sizes (the readings whose searches gave a different number of rows go
    to different stacks)."""

    def __init__(self, datasets: Sequence[xr.Dataset]):
        if not datasets:
            raise ValueError("a stack needs at least one dataset")
        self.datasets = list(datasets)
        self.n = len(self.datasets)
        self._arrays: dict[str, np.ndarray] = {}
        self._dims: dict[str, tuple[str, ...]] = {}
        self._data_vars: list[str] = []

    @classmethod
    def of_arrays(
        cls,
        variables: Mapping[str, tuple[Sequence[str], np.ndarray]],
        coords: Sequence[str] = (),
    ) -> Stack:
        """A stack of arrays computed for every reading at once: ``variables`` maps each
        name to its dimensions (after the reading axis) and its values (reading first);
        the names in ``coords`` are coordinates, the others data variables."""
        arrays = {k: np.asarray(v) for k, (_, v) in variables.items()}
        sizes = {a.shape[0] for a in arrays.values()}
        if len(sizes) != 1:
            raise ValueError(f"the variables of a stack hold different readings: {sizes}")
        stack = cls.__new__(cls)
        stack.datasets, stack.n, stack._arrays = [], sizes.pop(), arrays
        stack._dims = {k: tuple(dims) for k, (dims, _) in variables.items()}
        stack._data_vars = [k for k in variables if k not in coords]
        return stack

    def take(self, index: Sequence[int]) -> Stack:
        """The stack of the readings ``index`` (in that order)."""
        if self.datasets:
            return Stack([self.datasets[i] for i in index])
        index = np.asarray(index, dtype=np.intp)
        return Stack.of_arrays(
            {k: (self._dims[k], v[index]) for k, v in self._arrays.items()},
            [k for k in self._arrays if k not in self._data_vars],
        )

    @property
    def data_vars(self) -> list[str]:
        """The data variables' names (the first reading's order)."""
        return list(self.datasets[0].data_vars) if self.datasets else list(self._data_vars)

    def __contains__(self, name: str) -> bool:
        return name in self.datasets[0].variables if self.datasets else name in self._arrays

    def __getitem__(self, name: str) -> np.ndarray:
        """Variable ``name`` of every reading, shape ``(n, *its shape)``."""
        if name not in self._arrays:
            if not self.datasets:
                raise KeyError(f"the stack has no variable {name!r}")
            self._arrays[name] = np.stack([ds.variables[name].values for ds in self.datasets])
        return self._arrays[name]

    def dims(self, name: str) -> tuple[str, ...]:
        """The dimensions of variable ``name`` (after the reading axis)."""
        if not self.datasets:
            return self._dims[name]
        return tuple(self.datasets[0].variables[name].dims)

    def axis(self, name: str, dim: str) -> int:
        """The axis of dimension ``dim`` in :meth:`__getitem__` ``(name)``."""
        dims = self.dims(name)
        if dim not in dims:
            raise ValueError(f"variable {name!r} has no dimension {dim!r} (it has {dims})")
        return 1 + dims.index(dim)


def pick(values: np.ndarray, axis: int, index) -> np.ndarray:
    """``values`` (reading first) at position ``index`` along ``axis``: one position for
    every reading, or one per reading (an array of ``n``); the axis is dropped."""
    index = np.broadcast_to(np.asarray(index, dtype=np.intp), values.shape[:1])
    shape = [1] * values.ndim
    shape[0] = values.shape[0]
    return np.take_along_axis(values, index.reshape(shape), axis).squeeze(axis)


def per_reading(values: np.ndarray) -> np.ndarray:
    """One number per reading from ``values`` (reading first) that hold one each."""
    return np.asarray(values).reshape(values.shape[0])


def gives(unit: str | Callable[..., str]) -> Callable:
    """Declare the unit of a measurement's value: a unit (:data:`QUALITATIVE_UNIT` for
    1 or 0), or a function of the measurement's arguments that returns one (the unit of
    the coordinate an argument names, say); read by :func:`measurement_unit`."""

    def mark(fn: Callable) -> Callable:
        fn.unit = unit if callable(unit) else lambda **_: unit
        return fn

    return mark


def measurement_unit(name: str, args: Mapping) -> str | None:
    """The unit of measurement ``name``'s value under the claim's ``args`` (checked
    against its signature by the claims' check); None if the arguments name no variable
    of the table (the measurement then refuses them itself)."""
    try:
        return MEASUREMENTS[name].unit(**args)
    except (KeyError, TypeError):
        return None


def one_or_many(fn: Callable[..., np.ndarray]) -> Callable:
    """A measurement of stacks (one value per reading) that also takes datasets: called
    with ``xr.Dataset`` s it reads them as one reading and returns that reading's float."""

    @functools.wraps(fn)
    def measurement(*args, **kwargs):
        import xarray as xr

        if any(isinstance(a, xr.Dataset) for a in args):
            stacks = (Stack([a]) if isinstance(a, xr.Dataset) else a for a in args)
            return float(fn(*stacks, **kwargs)[0])
        return fn(*args, **kwargs)

    return measurement


def valid_v_out(ds: xr.Dataset) -> xr.DataArray:
    """v_out (km/h) of a result dataset with failed strokes as NaN."""
    return ds["v_out"].where(ds["status"] == OK)


def valid_values(ds: xr.Dataset, var: str) -> xr.DataArray:
    """Variable ``var`` as a view or a difference shows it: v_out of a file with
    statuses with its failed strokes NaN (:func:`valid_v_out`), any other as it is."""
    return valid_v_out(ds) if var == "v_out" and "status" in ds else ds[var]


def _valid(files: Stack) -> np.ndarray:
    """:func:`valid_v_out` of every reading (v_out and status have the same dims)."""
    return np.where(files["status"] == OK, files["v_out"], np.nan)


def _half_tau_step(ds: Stack) -> np.ndarray:
    """Half the step of the ``tau`` grid of every reading, shape ``(n, 1)``."""
    tau = ds["tau"]
    return 0.5 * (tau[:, 1] - tau[:, 0])[:, None]


@gives(unit_of("C2"))
@one_or_many
def measure_delay_threshold(ds: Stack) -> np.ndarray:
    """Fig. 7: the torque C2 above which the best delay is no longer 0 (N m).

    The first C2 of the grid from which on the best tau stays above 0 (more than half a
    tau step), interpolated half-way to the previous C2; C2 = 0 is skipped (v_out does not
    depend on tau there).
    """
    c2 = ds["C2"]
    positive = (ds["best_tau"] > _half_tau_step(ds)) & (c2 > 0)
    # a row from which on every row is positive (and so C2 > 0)
    stays = np.logical_and.accumulate(positive[:, ::-1], axis=1)[:, ::-1]
    found = stays.any(axis=1)
    first = np.argmax(stays, axis=1)
    rows = np.arange(ds.n)
    value = np.where(
        first > 0, 0.5 * (c2[rows, first] + c2[rows, np.maximum(first - 1, 0)]), c2[rows, first]
    )
    return np.where(found, value, np.nan)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_below_threshold_tau_zero(ds: Stack) -> np.ndarray:
    """Fig. 7: 1 if the best tau is 0 for every C2 in (0, threshold)."""
    thr = measure_delay_threshold(ds)
    c2 = ds["C2"]
    with np.errstate(invalid="ignore"):
        sel = (c2 > 0) & (c2 < thr[:, None])
    return np.all(np.where(sel, ds["best_tau"], 0.0) <= _half_tau_step(ds), axis=1).astype(float)


def _extreme(ds: Stack, coord: str, sign: float) -> np.ndarray:
    """The coordinate ``coord`` of the largest (``sign`` 1) or smallest (-1) v_out."""
    v = _valid(ds)
    flat = np.where(np.isnan(v), -sign * np.inf, v).reshape(ds.n, -1)
    best = np.argmax(flat, axis=1) if sign > 0 else np.argmin(flat, axis=1)
    index = np.unravel_index(best, v.shape[1:])[ds.axis("v_out", coord) - 1]
    return pick(ds[coord], 1, index)


@gives(lambda coord: unit_of(coord))
@one_or_many
def measure_optimum(ds: Stack, coord: str) -> np.ndarray:
    """The coordinate ``coord`` of the largest v_out of a map (grid point)."""
    return _extreme(ds, coord, 1.0)


@gives(lambda coord: unit_of(coord))
@one_or_many
def measure_minimum(ds: Stack, coord: str) -> np.ndarray:
    """The coordinate ``coord`` of the smallest v_out of a map (grid point)."""
    return _extreme(ds, coord, -1.0)


def _fig9_unit(what: str) -> str:
    return {"tau_H": unit_of("best_tau"), "gain_percent": "%"}.get(what, unit_of("best_v_out"))


@gives(_fig9_unit)
@one_or_many
def measure_fig9(ds: Stack, what: Literal["v_L", "v_H", "tau_H", "gain_percent"]) -> np.ndarray:
    """Fig. 9: ``v_L`` (tau = 0), ``v_H`` (max), ``tau_H`` or the ``gain_percent``."""

    def first(name: str, values: np.ndarray) -> np.ndarray:
        return pick(values, ds.axis(name, "delta0"), 0)

    v_l = per_reading(first("v_out", _valid(ds))[:, 0])
    v_h = per_reading(first("best_v_out", ds["best_v_out"]))
    if what == "tau_H":
        return per_reading(first("best_tau", ds["best_tau"]))
    return {"v_L": v_l, "v_H": v_h, "gain_percent": 100 * (v_h / v_l - 1)}[what]


#: How far beyond its axis' ends a value may lie and still be on it, relative to the
#: axis' span (absolute on a one-point axis): what a decimal number in YAML can say of a
#: grid's end (``120.0`` against ``119.99999999999``).  A claim's ``sel`` value must lie
#: this close to a grid point (:func:`tennis_stroke.inference.claims.selection`).
AXIS_TOLERANCE = 1e-9


@dataclass(frozen=True)
class OnAxis:
    """The annotation of a measurement argument that is a value of the coordinate
    ``coord`` of its file (``theta0: Annotated[float, OnAxis("theta0")]``): the value
    must lie on the axis (between its ends, within :data:`AXIS_TOLERANCE`), checked when
    the file is read (:func:`nearest`) and, from the config's grid of the file, before
    any job (:func:`tennis_stroke.inference.claims.claim_axis_errors`)."""

    coord: str


class OffAxisError(ValueError):
    """A measurement's argument lies beyond the ends of its file's axis (one line)."""


def off_axis(low, high, value: float):
    """Whether ``value`` lies beyond the axis from ``low`` to ``high`` (arrays: one axis
    per reading), by more than :data:`AXIS_TOLERANCE`."""
    slack = AXIS_TOLERANCE * np.maximum(np.asarray(high) - np.asarray(low), 1.0)
    return (value < np.asarray(low) - slack) | (value > np.asarray(high) + slack)


def nearest(axis: np.ndarray, value: float, coord: str) -> np.ndarray:
    """The position of the value nearest ``value`` in each reading's ``axis`` of
    coordinate ``coord`` (reading first; a tie goes to the later position, as
    ``sel(method="nearest")`` on a rising axis).  A value between two grid points is
    read at the nearer; a value beyond the axis' ends raises :class:`OffAxisError`
    (its nearest row is another point's value, not this one's)."""
    low, high = np.min(axis, axis=1), np.max(axis, axis=1)
    beyond = off_axis(low, high, value)
    if np.any(beyond):
        r = int(np.argmax(beyond))
        raise OffAxisError(
            f"{coord} = {value:g} lies off the file's {coord} axis ({low[r]:g} to "
            f"{high[r]:g}): a measurement reads a value on its axis, never beyond"
        )
    gap = np.abs(axis - value)
    return axis.shape[1] - 1 - np.argmin(gap[:, ::-1], axis=1)


@gives(unit_of("best_delta0"))
@one_or_many
def measure_best_delta0(ds: Stack, theta0: Annotated[float, OnAxis("theta0")]) -> np.ndarray:
    """Figs. 2-3: the best delta0 at ``theta0`` (the red line)."""
    at = nearest(ds["theta0"], theta0, "theta0")
    return pick(ds["best_delta0"], ds.axis("best_delta0", "theta0"), at)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_best_delta0_decreases(
    ds: Stack,
    low: Annotated[float, OnAxis("theta0")],
    middle: Annotated[float, OnAxis("theta0")],
    high: Annotated[float, OnAxis("theta0")],
) -> np.ndarray:
    """Figs. 2-3: 1 if the best delta0 falls from theta0 = ``low`` to ``middle`` to
    ``high`` (degree; values of the file's axis, checked at planning as every
    :class:`OnAxis` argument is: they were fixed here, 60, 90 and 120, where no check
    saw them)."""
    b = [measure_best_delta0(ds, t) for t in (low, middle, high)]
    return ((b[0] > b[1]) & (b[1] > b[2])).astype(float)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_delta0_smaller_for_longer_arm(short: Stack, long: Stack) -> np.ndarray:
    """Fig. 3 vs 2: 1 if the best delta0 is smaller for L1 = 0.4 m at 90 % of theta0."""
    diff = long["best_delta0"] - short["best_delta0"]
    return (np.mean((diff < 0).reshape(diff.shape[0], -1), axis=1) >= 0.9).astype(float)


@gives(lambda var, **_: unit_of(var))
@one_or_many
def measure_stroke(ds: Stack, var: str, stroke: int, absolute: bool = False) -> np.ndarray:
    """``var`` of stroke ``stroke`` (its size if ``absolute``)."""
    value = per_reading(pick(ds[var], ds.axis(var, "stroke"), stroke)).astype(float)
    return np.abs(value) if absolute else value


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_greater(ds: Stack, var: str, first: int, second: int) -> np.ndarray:
    """1 if ``var`` of stroke ``first`` exceeds that of stroke ``second``."""
    return (measure_stroke(ds, var, first) > measure_stroke(ds, var, second)).astype(float)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_omega2_peak_greater(ds: Stack, first: int, second: int) -> np.ndarray:
    """Fig. 4: 1 if the whole-stroke maximum of omega2 of ``first`` exceeds ``second``'s."""
    peaks = np.fmax.reduce(ds["omega2"], axis=ds.axis("omega2", "t"))  # NaN skipped
    dims = [d for d in ds.dims("omega2") if d != "t"]
    at = 1 + dims.index("stroke")
    return (per_reading(pick(peaks, at, first)) > per_reading(pick(peaks, at, second))).astype(
        float
    )


def _of_stroke(ds: Stack, var: str, stroke: int) -> np.ndarray:
    """``var`` of stroke ``stroke`` (its other axes after the reading's)."""
    return pick(ds[var], ds.axis(var, "stroke"), stroke)


def _linear(t: np.ndarray, values: np.ndarray, at: float) -> float:
    """``values(t)`` at ``at`` by linear interpolation, NaN outside ``t`` (what
    ``DataArray.interp`` computes: scipy's ``interp1d`` with these options)."""
    from scipy.interpolate import interp1d  # here: the figure and report jobs load no scipy

    curve = interp1d(
        t,
        values,
        kind="linear",
        fill_value=(np.nan, np.nan),
        bounds_error=False,
        assume_sorted=True,
        copy=False,
    )
    return float(curve(at))


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_omega2_rises_after_contact(ds: Stack, stroke: int) -> np.ndarray:
    """Fig. 4: 1 if omega2 is larger 10 ms after separation than at the contact start."""
    omega2 = _of_stroke(ds, "omega2", stroke)  # (n, t)
    later = per_reading(_of_stroke(ds, "t_separation", stroke)) + 0.01
    t = ds["t"]
    value = np.array([_linear(t[r], omega2[r], later[r]) for r in range(ds.n)])
    return (value > per_reading(_of_stroke(ds, "omega2_contact", stroke))).astype(float)


def _at_omega2_peak(ds: Stack, var: str, stroke: int) -> np.ndarray:
    """``var`` (a curve, or the time ``t``) of stroke ``stroke`` when its omega2 is
    largest (NaN skipped)."""
    omega2 = _of_stroke(ds, "omega2", stroke)
    peak = np.argmax(np.where(np.isnan(omega2), -np.inf, omega2), axis=1)
    values = ds["t"] if var == "t" else _of_stroke(ds, var, stroke)
    return pick(values, 1, peak)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_peak_after_contact(ds: Stack, stroke: int) -> np.ndarray:
    """Fig. 10: 1 if omega2 peaks after the contact start (the ball is hit before)."""
    start = per_reading(_of_stroke(ds, "t_contact_start", stroke))
    return (_at_omega2_peak(ds, "t", stroke) > start).astype(float)


@gives(unit_of("omega1"))
@one_or_many
def measure_omega1_at_omega2_peak(ds: Stack, stroke: int) -> np.ndarray:
    """Fig. 10: |omega1| (rad/s) when omega2 has its maximum."""
    return np.abs(_at_omega2_peak(ds, "omega1", stroke))


@gives(unit_of("t_contact_start"))
@one_or_many
def measure_contact_time_difference(ds: Stack) -> np.ndarray:
    """Fig. 10: |t_c(tau_H) - t_c(tau_L)| (s)."""
    return np.abs(
        per_reading(_of_stroke(ds, "t_contact_start", 1) - _of_stroke(ds, "t_contact_start", 0))
    )


@gives("%")
@one_or_many
def measure_k_spread(ds: Stack) -> np.ndarray:
    """Sec. II: the largest change of v_out over the spring constants of a
    ``(stroke, k_contact)`` map, per stroke in % of its largest v_out (the largest of
    the strokes)."""
    v, k = _valid(ds), ds.axis("v_out", "k_contact")
    top = np.fmax.reduce(v, axis=k)  # NaN skipped
    spread = (top - np.fmin.reduce(v, axis=k)) / top * 100.0
    return np.fmax.reduce(spread.reshape(ds.n, -1), axis=1)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_mass_trend(
    ds: Stack, m2: Annotated[float, OnAxis("M2")], sign: Literal[-1, 1]
) -> np.ndarray:
    """Fig. 5: 1 if the fastest v_out at ``M2`` changes with L1 (largest vs smallest) in
    the direction ``sign``."""
    row = pick(ds["v_out_best"], ds.axis("v_out_best", "M2"), nearest(ds["M2"], m2, "M2"))
    return (np.sign(per_reading(row[:, -1] - row[:, 0])) == sign).astype(float)


def _theta_c_ends(ds: Stack) -> tuple[np.ndarray, np.ndarray]:
    """theta_c at the smallest and at the largest L1, each ``(n, M2)``."""
    at = ds.axis("theta_c", "L1")
    tc = ds["theta_c"]
    return pick(tc, at, 0).reshape(ds.n, -1), pick(tc, at, -1).reshape(ds.n, -1)


@gives(unit_of("theta_c"))
@one_or_many
def measure_theta_c(ds: Stack, end: Literal["small", "large"]) -> np.ndarray:
    """Fig. 6: mean over M2 of theta_c at the smallest or largest L1 (degree)."""
    values = _theta_c_ends(ds)[{"small": 0, "large": 1}[end]]
    with warnings.catch_warnings():  # as xarray's mean: NaN skipped, silent if all are
        warnings.filterwarnings("ignore", "Mean of empty slice", RuntimeWarning)
        return np.nanmean(np.ascontiguousarray(values), axis=1)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_theta_c_decreases(ds: Stack) -> np.ndarray:
    """Fig. 6: 1 if theta_c at the largest L1 is below that at the smallest, for every M2."""
    small, large = _theta_c_ends(ds)
    return np.all(large < small, axis=1).astype(float)


@gives(QUALITATIVE_UNIT)
@one_or_many
def measure_table1_minimum(ds: Stack) -> np.ndarray:
    """Table I: 1 if psi_F = 275 deg gives the slowest rebound of the four cases."""
    v, psi = ds["v_out"], ds["psi_F"]
    if not (psi == 275.0).any(axis=1).all():
        raise ValueError("Table I's strokes have no psi_F = 275 deg")
    return (np.nanargmin(v, axis=1) == np.argmax(psi == 275.0, axis=1)).astype(float)


#: Named measurements: function(stacks..., **args) -> one value per reading.  The
#: parameters annotated :class:`Stack` take the claim's files in order, the others its
#: arguments; the annotations (``float``, ``int``, ``str``, ``Literal[...]``, and
#: :class:`OnAxis` for a value of a file's coordinate) are checked before any job
#: (:func:`tennis_stroke.inference.claims.claim_errors`,
#: :func:`tennis_stroke.inference.claims.claim_axis_errors`).
MEASUREMENTS: dict[str, Callable[..., np.ndarray]] = {
    name.removeprefix("measure_"): fn
    for name, fn in globals().items()
    if name.startswith("measure_") and callable(fn)
}
