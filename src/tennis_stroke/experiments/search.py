"""Optima and thresholds located by a search instead of a dense grid.

The paper's claims read optima (the best delta0 of a row of Figs. 2-3, the best initial
angles of Figs. 5-6, the best delay of Figs. 7-9, the best and worst direction of Fig. 13)
and one threshold (the C2 of Fig. 7).  A dense map answers them at the resolution of its
grid; the searches here answer the same question between grid points, with far fewer
strokes, for a whole batch of independent problems at once: every iteration evaluates
one batch of strokes (one call of the solver) for all problems still running.

:func:`maximize` brackets each maximum on a coarse grid over the whole box, then refines
it by a compass search (a pattern search: the neighbours at +-h along each axis; move to
the best one if it improves, else halve h) until h is below the tolerance of every axis.
The compass search converges to a local maximum of a smooth function (Kolda, Lewis and
Torczon, SIAM Review 45 (2003) 385); the coarse grid decides which local maximum, so its
step must resolve the separation of the objective's peaks (the validation of the
targeted claims measures it).  scipy.optimize has no vectorised bounded search in more
than one dimension: its ``minimize`` runs one problem at a time, and one call of the
solver costs about 0.5 ms of overhead whatever its size.

:func:`first_crossing` locates where a predicate that is false below and true above a
value switches, by multisection of a bracket (several points per iteration, all problems
in one batch).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..solver.results import OK
from ..solver.stroke import strike_batch
from .grids import bracket_size

#: A batch objective: points of shape ``(n, k, dims)`` of the problems ``index`` (``(n,)``,
#: positions in the batch) -> values ``(n, k)`` (NaN: the stroke failed; the worst value).
Objective = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Optimum:
    """The result of :func:`maximize` for a batch of problems."""

    x: np.ndarray  #: ``(problems, dims)``: the location of each maximum
    value: np.ndarray  #: ``(problems,)``: the objective there (NaN: no stroke succeeded)
    evaluations: int  #: objective evaluations per problem, coarse grid included (the most)


def coarse_axis(lower: float, upper: float, step: float) -> np.ndarray:
    """Equally spaced points from ``lower`` to ``upper`` inclusive, no further apart than
    ``step`` (both ends included whatever the step)."""
    return np.linspace(lower, upper, bracket_size(lower, upper, step))


def _worst(values: np.ndarray) -> np.ndarray:
    return np.where(np.isfinite(values), values, -np.inf)


def step_bound(extent: np.ndarray, first: np.ndarray, tolerances: np.ndarray) -> int:
    """The most steps a compass search can take: at each step size ``h`` (``first``,
    halved until every axis is at most its tolerance) it moves to a strictly better
    point of the lattice of spacing ``h`` over the box (``extent`` per axis: its width,
    or a periodic axis's period) or halves, so it visits each lattice point at most once.
    A search with a deterministic objective ends before it; one still moving after it
    is a fault, stopped with an error."""
    h, total = np.asarray(first, float).copy(), 0
    while np.any(h > tolerances):
        # ceil: an extent of 12 steps may divide to 11.999999999999998
        points = np.where(h > 0, np.ceil(extent / np.where(h > 0, h, 1.0)) + 1, 1)
        total += math.prod(int(n) for n in points)  # Python ints: no overflow
        h *= 0.5
    return total + 1


def maximize(
    objective: Objective,
    problems: int,
    lower: Sequence[float],
    upper: Sequence[float],
    steps: Sequence[float],
    tolerances: Sequence[float],
    sign: float = 1.0,
    max_iterations: int | None = None,
    periods: Sequence[float | None] | None = None,
) -> Optimum:
    """The maximum of ``sign * objective`` of each of ``problems`` problems over the box
    ``[lower, upper]`` (one bound per axis, the same for every problem).

    A coarse grid of at most ``steps`` apart along each axis brackets each maximum; a
    compass search from the best grid point, starting at half the coarse step and
    clipped to the box, refines it until its step is at most ``tolerances`` along every
    axis.  Along one axis, a maximum bracketed inside the grid is refined by
    Chandrupatla's method instead (:func:`scipy.optimize.elementwise.find_minimum`: about
    half the evaluations), one on the edge by the compass search.  ``sign = -1`` finds
    minima (``value`` is then the objective, not its negative).  A maximum on the edge of
    the box stays there.  ``periods``: per axis, None or the period of a periodic axis
    (an angle over a full turn, ``upper - lower`` equal to it): its grid leaves out
    ``upper`` (the same point as ``lower``) and the compass search wraps around,
    returning values in ``[lower, upper)``.  ``max_iterations``: the steps after which a
    search still moving is an error; None, the most it can take (:func:`step_bound`).
    """
    lo, hi, steps, tol, wrap, period = _box(lower, upper, steps, tolerances, periods)
    dims = lo.size
    axes = [coarse_axis(lo[k], hi[k], steps[k]) for k in range(dims)]
    axes = [a[:-1] if wrap[k] and a.size > 2 else a for k, a in enumerate(axes)]
    mesh = np.stack([m.ravel() for m in np.meshgrid(*axes, indexing="ij")], axis=-1)
    everyone = np.arange(problems)
    values = sign * np.asarray(objective(np.broadcast_to(mesh, (problems, *mesh.shape)), everyone))
    values = _worst(values.reshape(problems, -1))
    best = np.argmax(values, axis=1)
    x = mesh[best].copy()
    v = values[np.arange(problems), best]
    evaluations = mesh.shape[0]
    spacing = np.array([a[1] - a[0] if a.size > 1 else 0.0 for a in axes])
    h = np.broadcast_to(0.5 * spacing, (problems, dims)).copy()
    if dims == 1 and not wrap[0]:
        done, count = _bracketed(objective, axes[0], values, best, sign, float(tol[0]))
        x[done, 0], v[done] = count[0], count[1]
        h[done] = 0.0  # the compass search takes the maxima on the edges only
        evaluations += count[2]
    if max_iterations is None:  # the search's own bound: only a fault reaches it
        max_iterations = step_bound(np.where(wrap, period, hi - lo), 0.5 * spacing, tol)
    box = (lo, hi, wrap, period)
    evaluations += _compass(objective, x, v, h, box, tol, sign, max_iterations)
    value = np.where(np.isfinite(v), sign * v, np.nan)
    return Optimum(x, value, evaluations)


def _box(lower, upper, steps, tolerances, periods):
    """The search box of :func:`maximize` as arrays, checked: ``(lower, upper, steps,
    tolerances, wrap, period)``, ``wrap`` whether an axis is periodic, ``period`` its
    period (inf for the others)."""
    lo, hi = np.asarray(lower, float), np.asarray(upper, float)
    steps, tol = np.asarray(steps, float), np.asarray(tolerances, float)
    dims = lo.size
    if not (hi.size == steps.size == tol.size == dims):
        raise ValueError("lower, upper, steps and tolerances need one value per axis")
    if np.any(tol <= 0):
        raise ValueError(f"search tolerances must be > 0, got {tol.tolist()}")
    periods = list(periods) if periods is not None else [None] * dims
    if len(periods) != dims:
        raise ValueError("periods needs one value (None or a period) per axis")
    wrap = np.array([p is not None for p in periods])
    period = np.array([p if p is not None else np.inf for p in periods], float)
    if np.any(wrap & ~np.isclose(hi - lo, np.where(wrap, period, 0.0))):
        raise ValueError("a periodic axis must span exactly one period")
    return lo, hi, steps, tol, wrap, period


def _compass(objective, x, v, h, box, tol, sign, max_iterations) -> int:
    """The compass search of :func:`maximize` from ``x`` (values ``v``, steps ``h``, one
    row per problem, updated in place) in ``box`` (``lower, upper, wrap, period``) until
    every step is at most ``tol``; the evaluations per problem it took (the most)."""
    lo, hi, wrap, period = box
    dims = x.shape[1]
    offsets = np.concatenate([np.eye(dims), -np.eye(dims)])  # (2 dims, dims)
    evaluations = 0
    for _ in range(max_iterations):
        active = np.flatnonzero(np.any(h > tol, axis=1) & np.isfinite(v))
        if active.size == 0:
            break
        trial = x[active, None, :] + offsets[None] * h[active, None, :]
        trial = np.where(wrap, lo + np.mod(trial - lo, period), np.clip(trial, lo, hi))
        tv = _worst(sign * np.asarray(objective(trial, active)))
        evaluations += trial.shape[1]
        j = np.argmax(tv, axis=1)
        gain = tv[np.arange(active.size), j] > v[active]
        moved = active[gain]
        x[moved] = trial[gain, j[gain]]
        v[moved] = tv[gain, j[gain]]
        h[active[~gain]] *= 0.5
    else:
        moving = int(np.sum(np.any(h > tol, axis=1) & np.isfinite(v)))
        raise RuntimeError(
            f"the compass search did not converge in {max_iterations} steps "
            f"({moving} of {x.shape[0]} searches still moving)"
        )
    return evaluations


def _bracketed(objective, grid, values, best, sign, tolerance):
    """The 1-D maxima whose best grid point has a neighbour on each side that is not
    better (one strictly worse), refined by Chandrupatla's bracketing minimisation
    (:func:`scipy.optimize.elementwise.find_minimum`, vectorised over the problems).
    Returns the problems it refined and, for them, ``(x, sign * value, evaluations)``."""
    from scipy.optimize import elementwise

    rows = np.arange(values.shape[0])
    inner = (best > 0) & (best < grid.size - 1)
    left = np.where(inner, values[rows, np.maximum(best - 1, 0)], -np.inf)
    right = np.where(inner, values[rows, np.minimum(best + 1, grid.size - 1)], -np.inf)
    mid = values[rows, best]
    done = np.flatnonzero(
        inner
        & np.isfinite(mid)
        & np.isfinite(left)
        & np.isfinite(right)
        & ((mid > left) | (mid > right))
    )
    if done.size == 0:
        return done, (np.empty(0), np.empty(0), 0)

    def f(x, index):
        got = objective(x.reshape(-1, 1, 1), index.astype(int).reshape(-1))[:, 0]
        return np.where(np.isfinite(got), -sign * got, np.inf).reshape(x.shape)

    b = best[done]
    res = elementwise.find_minimum(
        f,
        (grid[b - 1], grid[b], grid[b + 1]),
        args=(done.astype(float),),
        tolerances={"xatol": tolerance, "xrtol": 0.0, "fatol": 0.0, "frtol": 0.0},
    )
    return done, (res.x, -res.f_x, int(np.max(res.nfev)))


def first_crossing(
    predicate: Callable[[np.ndarray, np.ndarray], np.ndarray],
    below: np.ndarray,
    above: np.ndarray,
    tolerance: float,
    points: int = 7,
) -> tuple[np.ndarray, np.ndarray]:
    """Narrow brackets ``[below, above]`` (one per problem, the predicate false at
    ``below`` and true at ``above``) around the switch of a boolean ``predicate`` to at
    most ``tolerance`` wide, evaluating ``points`` interior points per problem and
    iteration (``predicate`` takes ``(n, points)`` values of the problems ``index``
    (``(n,)``, those whose bracket is still wider than ``tolerance``) and returns
    booleans of that shape).  Returns the narrowed ``(below, above)``; where the
    predicate switches more than once inside a bracket, the first switch of each
    iteration's points is followed.  A problem's brackets do not depend on the other
    problems: a bracket narrow enough is left as it is."""
    lo, hi = np.array(below, float), np.array(above, float)
    if tolerance <= 0:
        raise ValueError(f"the bracket tolerance must be > 0, got {tolerance}")
    fractions = np.arange(1, points + 1) / (points + 1)
    while True:
        active = np.flatnonzero(hi - lo > tolerance)
        if active.size == 0:
            return lo, hi
        a, b = lo[active], hi[active]
        x = a[:, None] + (b - a)[:, None] * fractions[None, :]
        true = np.asarray(predicate(x, active), bool)
        # the first true point: the bracket becomes (previous point, that point)
        first = np.where(true.any(axis=1), np.argmax(true, axis=1), points)
        edges = np.concatenate([a[:, None], x, b[:, None]], axis=1)
        rows = np.arange(active.size)
        lo[active], hi[active] = edges[rows, first], edges[rows, first + 1]


#: The axes a stroke search may vary: initial angles (degrees) and model parameters.
ANGLES = ("theta0", "delta0")


def _per_problem(value, problems: int) -> np.ndarray:
    """One value per problem: numbers as floats, a reading's choices as strings."""
    arr = np.asarray(value)
    return np.broadcast_to(arr if arr.dtype.kind in "UO" else arr.astype(float), (problems,))


def stacked(
    models: Sequence[Mapping[str, object]], counts: Sequence[int]
) -> tuple[dict[str, object], dict[str, np.ndarray]]:
    """The model overrides of several parameter sets (``models``, each of plain scalars
    and choices) as one batch of problems, set ``r`` owning the next ``counts[r]``
    problems: ``(shared, per_problem)``, the values every set gives alike and, for the
    others, one value per problem (:class:`StrokeObjective`'s ``params`` and
    ``fixed``).  Every set must name the same parameters; one set is shared whole."""
    if len(models) == 1:
        return dict(models[0]), {}
    keys = list(dict.fromkeys(k for m in models for k in m))
    shared: dict[str, object] = {}
    per_problem: dict[str, np.ndarray] = {}
    for key in keys:
        if any(key not in m for m in models):
            raise ValueError(f"the parameter sets do not all set {key!r}")
        values = [m[key] for m in models]
        if any(np.ndim(v) != 0 for v in values):
            raise ValueError(f"{key!r}: a parameter set searched in lockstep holds scalars")
        if all(type(v) is type(values[0]) and v == values[0] for v in values):
            shared[key] = values[0]
        else:
            kind = object if isinstance(values[0], str) else float
            per_problem[key] = np.repeat(np.asarray(values, dtype=kind), counts)
    return shared, per_problem


def lockstep_objective(
    axes, problems: int, fixed, models, counts, settings, threads=None, *, memo: bool = False
) -> StrokeObjective:
    """The :class:`StrokeObjective` of a search of several parameter sets in lockstep:
    set ``r`` of ``models`` owns the next ``counts[r]`` problems (:func:`stacked`); the
    search's per-problem values ``fixed`` replace the sets' own, as they replace one
    set's overrides.  ``memo``: as :class:`StrokeObjective`'s."""
    shared, per_problem = stacked(models, counts)
    return StrokeObjective(
        axes, problems, {**per_problem, **fixed}, shared, settings, threads, memo=memo
    )


class StrokeObjective:
    """The rebound speed v_out (km/h; NaN where the stroke fails) as a batch objective
    (:data:`Objective`) over ``axes`` (``theta0``, ``delta0`` in degrees, or model
    parameters such as ``tau`` or ``psi_F_deg``), with per-problem values ``fixed``
    (arrays of one value per problem: angles, parameters or a reading's choices) over
    the model overrides ``params`` (which may hold ``theta0`` and ``delta0`` too).
    ``failed`` and ``evaluated`` count the strokes that failed and that were asked for,
    per problem.

    ``memo``: a point a problem asked for before is not run again, its speed and status
    kept from the first time (the same stroke: the problem's values and the point are
    the same, bit for bit).  A search revisits points (the compass search the point it
    came from, a maximum on the box's edge the clipped trial; Chandrupatla's method its
    bracket): about a third of a robustness chunk's strokes.  ``failed`` and
    ``evaluated`` count as without it; :func:`~tennis_stroke.solver.stroke.rhs_evaluations`
    counts the strokes run, so a study that reports it leaves the memo off."""

    def __init__(self, axes, problems: int, fixed, params, settings, threads=None, *, memo=False):
        self.axes, self.settings, self.threads = tuple(axes), settings, threads
        self.fixed = {k: _per_problem(v, problems) for k, v in fixed.items()}
        self.params = dict(params)
        self.failed = np.zeros(problems, dtype=np.int64)
        self.evaluated = np.zeros(problems, dtype=np.int64)
        self._memo: dict[bytes, tuple[float, int]] | None = {} if memo else None

    def _run(self, points: np.ndarray, index: np.ndarray) -> dict[str, np.ndarray]:
        """Every result field of the strokes at ``points`` (``(n, k, dims)``) of the
        problems ``index``, shape ``(n, k)``."""
        values = {name: points[..., k] for k, name in enumerate(self.axes)}
        values.update({k: v[index, None] for k, v in self.fixed.items()})
        model = {**self.params, **values}
        theta0, delta0 = (model.pop(a, None) for a in ANGLES)
        res = strike_batch(theta0, delta0, model, self.settings, self.threads)
        return {k: np.broadcast_to(v, points.shape[:-1]) for k, v in res.items()}

    def _count(self, status: np.ndarray, index: np.ndarray) -> None:
        np.add.at(self.failed, index, np.count_nonzero(status, axis=1))
        np.add.at(self.evaluated, index, status.shape[1])

    def strike(self, points: np.ndarray, index: np.ndarray) -> dict[str, np.ndarray]:
        """Every result field of the strokes at ``points`` (``(n, k, dims)``) of the
        problems ``index`` (run, memo or not)."""
        out = self._run(points, index)
        self._count(out["status"], index)
        return out

    def _remembered(self, points: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """v_out (km/h) and status of the strokes at ``points`` of the problems
        ``index``, each point a problem asked for before from the memo, the others run
        (each once)."""
        n, k, dims = points.shape
        rows = np.empty((n, k, 1 + dims))
        rows[..., 0] = index[:, None]
        rows[..., 1:] = points
        keys = rows.reshape(n * k, -1).view(np.dtype((np.void, 8 * (1 + dims)))).ravel().tolist()
        memo = self._memo
        new = list(itertools.filterfalse(memo.__contains__, dict.fromkeys(keys)))
        if new:
            at = np.frombuffer(b"".join(new), dtype=float).reshape(len(new), 1 + dims)
            res = self._run(at[:, None, 1:], at[:, 0].astype(np.intp))
            got = zip(res["v_out_kmh"][:, 0].tolist(), res["status"][:, 0].tolist(), strict=True)
            memo.update(zip(new, got, strict=True))
        got = np.array(list(map(memo.__getitem__, keys)), dtype=float).reshape(n, k, 2)
        return got[..., 0], got[..., 1].astype(np.int64)  # a status is a small integer

    def __call__(self, points: np.ndarray, index: np.ndarray) -> np.ndarray:
        if self._memo is None:
            res = self.strike(points, index)
            return np.where(res["status"] == OK, res["v_out_kmh"], np.nan)
        points = np.asarray(points, dtype=float)
        index = np.asarray(index, dtype=np.intp)
        v_out, status = self._remembered(points, index)
        self._count(status, index)
        return np.where(status == OK, v_out, np.nan)
