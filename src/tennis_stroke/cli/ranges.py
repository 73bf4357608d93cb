"""A sweep's axes as the command line gives them: ``START:STOP:NUM`` (a count of points)
or ``START:STOP/STEP`` (the config's form), checked before anything is allocated."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: The two forms of a range on the command line, as ``--help`` and the errors say them.
RANGE_FORMS = (
    "START:STOP:NUM (NUM points from START to STOP, both included: NUM 1 only where STOP "
    "is START) or START:STOP/STEP (from START to STOP in steps of STEP, which must land "
    "on STOP; the config's form)"
)


@dataclass(frozen=True)
class GridRange:
    """A sweep's axis as the command line gives it: ``step`` None for ``START:STOP:NUM``
    (``num`` points), else ``START:STOP/STEP`` (``num`` counts its points)."""

    start: float
    stop: float
    num: int
    step: float | None = None

    def values(self) -> np.ndarray:
        """The axis: :func:`numpy.linspace` for a count, the workflow's inclusive grid
        (:func:`tennis_stroke.experiments.grids.grid`) for a step."""
        if self.step is None:
            return np.linspace(self.start, self.stop, self.num)
        from ..experiments.grids import grid

        return grid(self.start, self.stop, self.step)


def parse_range(text: str, name: str) -> np.ndarray:
    """``START:STOP:NUM`` or ``START:STOP/STEP`` -> the axis (degrees)."""
    return range_spec(text, name).values()


def range_spec(text: str, name: str) -> GridRange:
    """``START:STOP:NUM`` or ``START:STOP/STEP`` -> :class:`GridRange`, checked, nothing
    allocated; a bad form or value raises ValueError (one line naming ``--name``)."""
    option = f"--{name}"
    ends, slash, step_text = text.partition("/")
    parts = ends.split(":")
    if len(parts) != (2 if slash else 3):
        raise ValueError(f"{option} expects {RANGE_FORMS}, got {text!r}")
    start = _range_number(option, "START", parts[0])
    stop = _range_number(option, "STOP", parts[1])
    if not math.isfinite(stop - start):
        raise ValueError(f"{option} STOP - START overflows, got {text!r}")
    if slash:
        return _step_range(option, start, stop, _range_number(option, "STEP", step_text))
    try:
        num = int(parts[2])
    except ValueError:
        raise ValueError(
            f"{option} NUM (of START:STOP:NUM) must be a whole number of points, got "
            f"{parts[2]!r} (a step is written START:STOP/STEP)"
        ) from None
    if num < 1:
        raise ValueError(f"{option} NUM must be >= 1, got {num}")
    if num == 1 and stop != start:  # linspace would give START alone
        raise ValueError(
            f"{option} NUM 1 gives START alone, never STOP {stop:g} (both ends are included): "
            f"give NUM >= 2, or {start:g}:{start:g}:1 for one point, got {text!r}"
        )
    if num > 1 and stop == start:  # linspace would give NUM equal coordinates
        raise ValueError(
            f"{option} START = STOP is one point, not {num}: give NUM 1, or a STOP above "
            f"START, got {text!r}"
        )
    return GridRange(start, stop, num)


def _range_number(option: str, part: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{option} {part} must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{option} {part} must be finite, got {text!r}")
    return value


def _step_range(option: str, start: float, stop: float, step: float) -> GridRange:
    """``START:STOP/STEP``, by the rules the workflow applies to a configured range."""
    from ..experiments.grids import grid_size, lands_on_stop

    if step <= 0:
        raise ValueError(f"{option} STEP must be > 0, got {step:g}")
    if stop < start:
        raise ValueError(f"{option} STOP {stop:g} is below START {start:g} (a step goes up)")
    if not lands_on_stop(start, stop, step):
        raise ValueError(
            f"{option} step {step:g} does not land on STOP {stop:g} from START {start:g} "
            "(a whole number of steps; START:STOP:NUM gives NUM points instead)"
        )
    return GridRange(start, stop, grid_size(start, stop, step), step)
