"""Grids of the experiments and the refinement of optima found on them.

Optima found on a grid are refined by a parabola through the best grid point and its two
neighbours along each axis (:func:`refine_peak`), so their accuracy is much finer than
the grid; the grid spacing is recorded with every optimum.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from fractions import Fraction

import numpy as np

from ..solver.results import OK

#: Relative slack of a step count: a range whose span is within it of a whole number of
#: steps lands on its stop (floating-point spans such as 0.3 / 0.0025).
LANDING = 1e-9


def _steps(start: float, stop: float, step: float):
    count = (float(stop) - float(start)) / float(step)
    if not math.isfinite(count):  # a step far below the span: count exactly
        count = (Fraction(stop) - Fraction(start)) / Fraction(step)
    return count


def lands_on_stop(start: float, stop: float, step: float) -> bool:
    """Whether ``start + n step`` reaches ``stop`` for a whole ``n`` (within
    :data:`LANDING`)."""
    count = _steps(start, stop, step)
    return abs(count - round(count)) <= LANDING * max(1.0, abs(float(count)))


def grid_size(start: float, stop: float, step: float) -> int:
    """Number of points of :func:`grid` ``(start, stop, step)``, computed without making it
    (to check a grid's memory before allocating it)."""
    count = _steps(start, stop, step)
    nearest = round(count)
    if abs(count - nearest) <= LANDING * max(1.0, abs(float(count))):
        return int(nearest) + 1
    return int(math.floor(count)) + 1


def grid(start: float, stop: float, step: float) -> np.ndarray:
    """Inclusive grid ``start, start + step, ...`` up to ``stop`` (rounded to the step's
    decimals): it ends on ``stop`` when the step lands there (:func:`lands_on_stop`),
    else at the last point before it, never beyond.  The workflow refuses a configured
    range whose step does not land on its stop."""
    return np.round(start + step * np.arange(grid_size(start, stop, step)), 10)


def bracket_size(lower: float, upper: float, step: float) -> int:
    """Points of a search's bracket grid: equally spaced from ``lower`` to ``upper``
    inclusive, no further apart than ``step``
    (:func:`tennis_stroke.experiments.search.coarse_axis`)."""
    if not step > 0:
        raise ValueError(f"a search step must be > 0, got {step}")
    if upper < lower:
        raise ValueError(f"a search range must have lower <= upper, got [{lower}, {upper}]")
    return max(2, math.ceil((upper - lower) / step - 1e-9) + 1) if upper > lower else 1


def axis_size(spec) -> int:
    """Number of points of :func:`axis` ``(spec)``, computed without making it."""
    if isinstance(spec, Mapping):
        spec = [spec["start"], spec["stop"], spec["step"]]
    return grid_size(*map(float, spec))


def axis(spec) -> np.ndarray:
    """A range ``[start, stop, step]`` or ``{start, stop, step}`` (the config's form) as an
    inclusive :func:`grid`."""
    if isinstance(spec, Mapping):
        spec = [spec["start"], spec["stop"], spec["step"]]
    return grid(*map(float, spec))


def refine_peak(x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
    """Location and value of the maximum of samples ``v(x)`` (NaN = failed stroke).

    A parabola through the best sample and its neighbours refines both; at the edge of
    the grid the best sample itself is returned.
    """
    if not np.any(np.isfinite(v)):
        return np.nan, np.nan
    i = int(np.nanargmax(v))
    if 0 < i < len(x) - 1 and np.all(np.isfinite(v[i - 1 : i + 2])):
        y0, y1, y2 = v[i - 1 : i + 2]
        denom = y0 - 2.0 * y1 + y2
        if denom < 0.0:
            shift = 0.5 * (y0 - y2) / denom
            h = x[i + 1] - x[i]
            return float(x[i] + shift * h), float(y1 - 0.25 * (y0 - y2) * shift)
    return float(x[i]), float(v[i])


def ok_speeds(res: Mapping[str, np.ndarray]) -> np.ndarray:
    """v_out with failed strokes as NaN."""
    return np.where(res["status"] == OK, res["v_out_kmh"], np.nan)


def chunk_count(requested: int, rows: int) -> int:
    """Number of chunks actually used: ``requested``, at most one per row (>= 1)."""
    if requested < 1:
        raise ValueError(f"chunk count must be >= 1, got {requested}")
    return max(1, min(int(requested), int(rows)))


def chunk_rows(values: np.ndarray, index: int, count: int) -> np.ndarray:
    """Rows ``index`` (0-based) of ``count`` contiguous, nearly equal blocks of ``values``."""
    if not 0 <= index < count:
        raise ValueError(f"chunk index {index} is outside 0..{count - 1}")
    return np.array_split(np.asarray(values), count)[index]


def select_rows(values: np.ndarray, rows: tuple[int, int] | None) -> np.ndarray:
    """All of ``values``, or only chunk ``rows = (index, count)`` of them (:func:`chunk_rows`)."""
    return np.asarray(values) if rows is None else chunk_rows(values, *rows)
