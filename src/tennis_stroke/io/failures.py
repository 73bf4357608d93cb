"""Failed strokes in a map: counted by status, and a limit on their share.

A stroke that fails (no ``phi = 0`` before ``t_max``, no release, a step-size failure,
...) is a status in the map (:data:`tennis_stroke.solver.results.STATUS_NAMES`), never a crashed
job.  A map whose failures exceed a configured share is not a result: the workflow's
gather step raises :class:`FailureShareError` with one line naming the map, the share and
the statuses, and the report lists the counts of every map.

Maps of stroke results carry a ``status`` variable; the optimum map of Figs. 5-6 carries
``failed_strokes`` and ``evaluated_strokes`` (the strokes of each point's search that
failed and that ran; the grid search of the studies, the attribute ``strokes_per_point``
instead).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..solver.results import STATUS_NAMES


class FailureShareError(RuntimeError):
    """More strokes of a map failed than the configured share (message is one line)."""


def failure_counts(ds: xr.Dataset) -> dict[str, int]:
    """Strokes of a map: ``total``, ``failed`` and the count of every failing status.

    Returns an empty dict for a dataset that records no stroke statuses.
    """
    if "status" in ds:
        status = np.asarray(ds["status"].values).ravel()
        counts = {"total": int(status.size), "failed": int(np.count_nonzero(status))}
        for code, name in sorted(STATUS_NAMES.items()):
            if code != 0:
                counts[name] = int(np.count_nonzero(status == code))
        return counts
    if "failed_strokes" in ds and "evaluated_strokes" in ds:
        failed = np.asarray(ds["failed_strokes"].values)
        return {"total": int(ds["evaluated_strokes"].sum()), "failed": int(failed.sum())}
    if "failed_strokes" in ds:
        failed = np.asarray(ds["failed_strokes"].values)
        per_point = int(ds.attrs["strokes_per_point"])
        return {"total": int(failed.size * per_point), "failed": int(failed.sum())}
    return {}


def check_failure_share(ds: xr.Dataset, max_share: float, name: str) -> dict[str, int]:
    """Counts of :func:`failure_counts`; raise if ``failed / total > max_share``.

    Parameters
    ----------
    ds : xarray.Dataset
        A map.
    max_share : float
        Largest acceptable share of failed strokes, in [0, 1].
    name : str
        The map's name for the message (e.g. its file).
    """
    if not 0.0 <= max_share <= 1.0:
        raise ValueError(f"max_share must be in [0, 1], got {max_share}")
    counts = failure_counts(ds)
    if not counts or counts["total"] == 0:
        return counts
    share = counts["failed"] / counts["total"]
    if share > max_share:
        statuses = ", ".join(
            f"{k} {v}" for k, v in counts.items() if k not in ("total", "failed") and v
        )
        detail = f" ({statuses})" if statuses else ""
        raise FailureShareError(
            f"{name}: {counts['failed']} of {counts['total']} strokes failed "
            f"({100 * share:.2f} %){detail}, above max_failure_share {100 * max_share:g} %"
        )
    return counts
