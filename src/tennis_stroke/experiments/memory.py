"""Memory of a batch of strokes, estimated before anything is allocated, and the limit.

A grid of strokes costs memory in proportion to its size, so a mistyped grid (a step of
1e-6 degrees, 31623 x 31623 points) would grow until the machine stops it with a
traceback.  ``tennis-stroke sweep`` runs on the user's machine, with no scheduler to
enforce a job's memory (the workflow's jobs ask for theirs and are bounded by
``max_points_per_job``, :mod:`tennis_stroke.pipeline.resources`), so it estimates first
(:func:`batch_bytes`, :func:`result_bytes`) and refuses with one line
(:func:`check_memory`) beyond :func:`memory_limit`.

The limit, first found wins: an explicit value (``tennis-stroke sweep --max-memory``),
the environment variable
:data:`MEMORY_ENV` (``TENNIS_STROKE_MAX_MEMORY``), else :data:`MEMORY_SHARE` of the
memory this process may use (the physical memory, or less under a cgroup limit or an
address-space ``ulimit``).  Sizes are bytes or a number with ``K``, ``M``, ``G``, ``T``
(powers of 1024: ``8G``, ``512MiB``, ``1.5 GB``).

The estimate lives with the experiments, not in the solver whose arrays it
counts: a change here must not invalidate the compiled solver's cache
(:mod:`tennis_stroke._cache`).
"""

from __future__ import annotations

import math
import os
import re
import resource
from decimal import Decimal
from pathlib import Path

import numpy as np

from ..model.dynamics import N_CF
from ..solver.integrate import HISTORY_COLS
from ..solver.results import COUNT_FIELDS, DEGREE_FIELDS, N_OUT, RESULT_FIELDS

#: Bytes of one float64 or int64 value.
WORD = np.dtype(np.float64).itemsize
#: Result fields that :func:`tennis_stroke.solver.results.results_from_output` copies
#: out of the compiled output: the counts (to int64) and the angles (to degrees); the
#: others are views of it.
_COPIED_FIELDS = len(COUNT_FIELDS) + len(DEGREE_FIELDS)
#: Peak bytes per stroke of one :func:`tennis_stroke.solver.stroke.strike_batch` call,
#: from the arrays it holds at once: the initial angles broadcast to every stroke
#: (theta0, delta0), the coefficient rows (``N_CF`` float64), the order the rows are
#: solved in (one int64, :func:`tennis_stroke.solver.stroke.swing_order`), the compiled
#: output (``N_OUT`` float64) and the result fields copied out of it: 456 bytes.
#: Measured (peak resident memory over the call, 2e6 strokes, before the order): 415
#: bytes per stroke for a grid given as broadcast axes, 440 for flat angle arrays (which
#: the caller holds as well).
BATCH_BYTES_PER_STROKE = WORD * (2 + 1 + N_CF + N_OUT + _COPIED_FIELDS)
#: Bytes per stroke of the result fields (every field one int64 or float64).
RESULT_BYTES_PER_STROKE = WORD * len(RESULT_FIELDS)
#: Share of the usable memory a computation may take by default: the rest is left to
#: the interpreter, the compiled code and everything else running on the machine.
MEMORY_SHARE = 0.5
#: Environment variable overriding the default limit (a size, :func:`parse_size`).
MEMORY_ENV = "TENNIS_STROKE_MAX_MEMORY"

_UNITS = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}
_SIZE = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][+-]?[0-9]+)?)\s*([KMGT]?)(?:I?B)?\s*$", re.I)


class MemoryLimitError(ValueError):
    """A computation would need more memory than the limit (message is one line)."""


def batch_bytes(n_strokes: int, threads: int = 1, history: int = 512) -> int:
    """Peak bytes of one ``strike_batch`` call over ``n_strokes`` strokes on ``threads``
    threads (each keeps a swing history of ``history`` rows)."""
    per_thread = (int(history) + 1) * HISTORY_COLS * WORD
    return int(n_strokes) * BATCH_BYTES_PER_STROKE + max(1, int(threads)) * per_thread


def result_bytes(n_strokes: int) -> int:
    """Bytes of the result fields of ``n_strokes`` strokes (one array per field)."""
    return int(n_strokes) * RESULT_BYTES_PER_STROKE


def parse_size(text: str | int | float) -> int:
    """``"8G"``, ``"512MiB"``, ``"1.5 GB"`` or a number of bytes -> bytes (> 0).

    ``K``, ``M``, ``G``, ``T`` are powers of 1024 (with or without ``iB``/``B``).
    """
    if isinstance(text, bool):
        raise ValueError(f"memory size must be a number of bytes or like 8G, got {text!r}")
    if isinstance(text, int | float):
        value, unit = float(text), ""
    else:
        match = _SIZE.match(str(text))
        if not match:
            raise ValueError(
                f"memory size must be a number of bytes or like 8G, 512M (K, M, G, T = "
                f"powers of 1024), got {text!r}"
            )
        value, unit = float(match.group(1)), match.group(2).upper()
    size = value * _UNITS[unit]
    if math.isnan(size):
        raise ValueError(f"memory size must be a number of bytes or like 8G, got {text!r}")
    if math.isinf(size):  # 1e400G, inf: more than any machine has
        raise ValueError(f"memory size must be a finite number of bytes, got {text!r}")
    if size < 1:
        raise ValueError(f"memory size must be at least 1 byte, got {text!r}")
    return int(size)


def format_size(n_bytes: int | float) -> str:
    """``1.5 GiB``-style size (powers of 1024); exact for any integer, however large."""
    value = Decimal(n_bytes) if isinstance(n_bytes, int) else Decimal(repr(float(n_bytes)))
    for unit in ("B", "KiB", "MiB", "GiB"):
        if value < 1024:
            return f"{value:.0f} {unit}" if unit == "B" else f"{value:.3g} {unit}"
        value /= 1024
    return f"{value:.3g} TiB"


def _cgroup_limit() -> float:
    """The memory limit of this process's cgroup (bytes), or infinity."""
    for path in ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"):
        try:
            text = Path(path).read_text().strip()
        except OSError:
            continue
        if text.isdigit() and int(text) < 2**60:
            return float(text)
    return math.inf


def _address_space_left() -> float:
    """Bytes this process may still map under ``ulimit -v`` / ``-d``, or infinity."""
    left = math.inf
    for which in (resource.RLIMIT_AS, resource.RLIMIT_DATA):
        soft, _ = resource.getrlimit(which)
        if soft != resource.RLIM_INFINITY:
            left = min(left, float(soft))
    if math.isinf(left):
        return left
    try:
        pages = int(Path("/proc/self/statm").read_text().split()[0])
        used = pages * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        used = 0
    return max(0.0, left - used)


def usable_memory() -> float:
    """Bytes this process may use: the physical memory, less under a cgroup limit."""
    physical = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    return min(float(physical), _cgroup_limit())


def memory_limit(
    explicit: str | int | float | None = None, source: str = "the given limit"
) -> tuple[int, str]:
    """The memory limit (bytes) and where it comes from, for messages.

    ``explicit`` (from ``source``, e.g. ``"--max-memory"``) wins, then the environment
    variable :data:`MEMORY_ENV`, then :data:`MEMORY_SHARE` of :func:`usable_memory`; the
    default never exceeds the address space left under a ``ulimit``.  The default's
    description names ``source`` and :data:`MEMORY_ENV` as the ways to change it.

    Raises
    ------
    ValueError
        ``explicit`` or the environment variable is not a size (:func:`parse_size`); the
        message starts with ``source`` or the variable's name.
    """
    if explicit is not None:
        try:
            return parse_size(explicit), source
        except ValueError as exc:
            raise ValueError(f"{source}: {exc}") from None
    env = os.environ.get(MEMORY_ENV, "").strip()
    if env:
        try:
            return parse_size(env), MEMORY_ENV
        except ValueError as exc:
            raise ValueError(f"{MEMORY_ENV}: {exc}") from None
    change = f"change it with {source} or {MEMORY_ENV}"
    share = MEMORY_SHARE * usable_memory()
    left = _address_space_left()
    if left < share:
        return int(left), f"the address space left under ulimit; {change}"
    return int(share), f"{MEMORY_SHARE:.0%} of the machine's memory; {change}"


def check_memory(needed: int, what: str, limit: tuple[int, str] | None = None) -> None:
    """Raise :class:`MemoryLimitError` (one line naming ``what``, the estimate and the
    limit) if ``needed`` bytes exceed ``limit`` (default: :func:`memory_limit`)."""
    limit_bytes, source = limit if limit is not None else memory_limit()
    if needed > limit_bytes:
        raise MemoryLimitError(
            f"{what} needs about {format_size(needed)} of memory, above the limit of "
            f"{format_size(limit_bytes)} ({source})"
        )
