"""The Figs. 5-6 optimum by a search (:mod:`tennis_stroke.experiments.search`): the
workflow's ``mass_length`` row.  Apart from the grid maps (:mod:`tennis_stroke.experiments.maps`),
so an edit of the search reruns this row and the claims' searches, not the maps."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..solver.settings import SolverSettings
from .grids import axis, select_rows
from .maps import optimum_dataset
from .search import lockstep_objective, maximize


def mass_length_optimum(
    m2: np.ndarray,
    l1: np.ndarray,
    coarse_step: float,
    tolerance: float,
    theta0_range: tuple[float, float],
    delta0_range: tuple[float, float],
    params: Mapping[str, object],
    settings: SolverSettings,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 5-6: the fastest rebound over the initial angles at every ``(M2, L1)``, by a
    search (:func:`tennis_stroke.experiments.search.maximize`).

    What is optimised: ``v_out`` over ``(theta0, delta0)`` in the given ranges, the other
    parameters fixed, as in :func:`~tennis_stroke.experiments.maps.mass_length_map`.
    How: a coarse grid (at most ``coarse_step`` degrees apart) over the whole range
    brackets the optimum, a compass search refines it to ``tolerance`` degrees; an
    optimum on the edge of the range stays there.  ``theta_c`` is ``|theta|`` at
    ``phi = 0`` of the optimal stroke; ``failed_strokes`` and ``evaluated_strokes`` count
    the strokes of each point's search that failed and that ran.
    """
    return mass_length_optima(
        m2, [l1], coarse_step, tolerance, theta0_range, delta0_range, [params], settings, threads
    )[0]


def mass_length_optima(
    m2: np.ndarray,
    l1: Sequence[np.ndarray],
    coarse_step: float,
    tolerance: float,
    theta0_range: tuple[float, float],
    delta0_range: tuple[float, float],
    models: Sequence[Mapping[str, object]],
    settings: SolverSettings,
    threads: int | None = None,
    memo: bool = False,
) -> list[xr.Dataset]:
    """:func:`mass_length_optimum` of every parameter set of ``models`` (model
    overrides), set ``r`` on the ``L1`` values ``l1[r]``: one search for all of them,
    every iteration one batch of strokes (the sets in lockstep).  Each set's file is the
    one :func:`mass_length_optimum` gives it alone.  ``memo``: no stroke run twice
    (:class:`~tennis_stroke.experiments.search.StrokeObjective`)."""
    m2 = np.asarray(m2, float)
    meshes = [np.meshgrid(m2, np.asarray(x, float), indexing="ij") for x in l1]
    counts = [mm.size for mm, _ in meshes]
    n = sum(counts)
    fixed = {
        "M2": np.concatenate([mm.ravel() for mm, _ in meshes]),
        "L1": np.concatenate([ll.ravel() for _, ll in meshes]),
    }
    objective = lockstep_objective(
        ("theta0", "delta0"), n, fixed, models, counts, settings, threads, memo=memo
    )
    lower, upper = (theta0_range[0], delta0_range[0]), (theta0_range[1], delta0_range[1])
    best = maximize(objective, n, lower, upper, (coarse_step, coarse_step), (tolerance, tolerance))
    at = objective.strike(best.x[:, None, :], np.arange(n))
    ok = at["status"][:, 0] == 0
    variables = {
        "v_out_best": best.value,
        "theta0_best": np.where(ok, best.x[:, 0], np.nan),
        "delta0_best": np.where(ok, best.x[:, 1], np.nan),
        "theta_c": np.where(ok, np.abs(at["theta_deg_at_phi0"][:, 0]), np.nan),
        "failed_strokes": objective.failed,
        "evaluated_strokes": objective.evaluated,
    }
    attrs = {
        "search": "coarse grid, then compass search",
        "coarse_step_deg": coarse_step,
        "tolerance_deg": tolerance,
    }
    out, offsets = [], np.cumsum([0, *counts])
    for r, (mm, _) in enumerate(meshes):
        part = slice(offsets[r], offsets[r + 1])
        values = {k: v[part].reshape(mm.shape) for k, v in variables.items()}
        out.append(
            optimum_dataset(m2, np.asarray(l1[r], float), values, models[r], settings, attrs)
        )
    return out


def mass_length_section(
    M2,
    L1,
    theta0_range,
    delta0_range,
    coarse_step: float,
    tolerance: float,
    params: Mapping[str, object],
    settings: SolverSettings,
    rows: tuple[int, int] | None = None,
    threads: int | None = None,
) -> xr.Dataset:
    """Figs. 5-6 from their config: the ranges ``M2`` (kg) and ``L1`` (m), the search
    ranges, the bracket step and the tolerance (degrees) of :func:`mass_length_optimum`;
    ``rows``: only that chunk of the ``M2`` rows."""
    return mass_length_optimum(
        select_rows(axis(M2), rows),
        axis(L1),
        coarse_step,
        tolerance,
        tuple(theta0_range),
        tuple(delta0_range),
        params,
        settings,
        threads,
    )
