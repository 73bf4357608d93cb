"""What the live explorer computes (``tennis-stroke explore``), without the server: each
view at a configuration (:func:`~tennis_stroke.live.controls.configuration`: the
paper's with a setting's overrides), by the workflow's own functions:

* the map of Fig. 2 or 3 (:func:`map_level`: the figure's experiment, row block by row
  block, at the explorer's :data:`LEVELS`, coarse then full; each stroke by
  :func:`~tennis_stroke.solver.stroke.strike_batch`, so a cell's value is that of the
  stroke at its coordinates);
* Fig. 9's delay curve (:func:`fig9_curve`, its experiment at the configured grid);
* the stroke at a picked point (:func:`stroke_at`, the curves of Fig. 4);
* the claims these views test (:func:`view_claims`, :func:`claims_table`): the targeted
  evaluation of the claims job (:func:`~tennis_stroke.inference.targeted.searched_files`)
  and its verdicts (:func:`~tennis_stroke.replication.claims.evaluate`), not a copy.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from ..experiments.grids import axis, axis_size, chunk_count
from ..experiments.specs import EXPERIMENTS, compute
from ..experiments.strokes import trajectories
from ..inference.claims import claim_files
from ..inference.measures import OffAxisError
from ..inference.targeted import searched_files
from ..io.config_files import value_at
from ..replication.claims import evaluate
from ..solver.settings import SolverSettings

#: The maps the explorer draws, by the figure a reader asks for (the values of
#: :data:`~tennis_stroke.replication.registry.LIVE`): the experiment of the map and the
#: index of its rod-1 length in ``angle_maps.L1``.  ``fig9`` shows Fig. 3's map
#: (L1 = 0.4 m, the arm of Sec. V) beside its curve.
FIGURES = {"fig2": ("fig2", 0), "fig3": ("fig3", 1), "fig9": ("fig3", 1)}
#: The result files of the explorer's views: the claims reading only these are shown.
VIEW_FILES = ("fig2", "fig3", "fig9")
#: The map's resolutions, (theta0 step, delta0 step) in degree, over the figure's ranges
#: (the paper's 60-120 x 0-100 deg: 121 x 101 coarse, 241 x 201 full).
LEVELS = {"coarse": (0.5, 1.0), "full": (0.25, 0.5)}
#: Row blocks of a map level: between two blocks a stale setting is dropped.
BLOCKS = {"coarse": 1, "full": 4}


def model_and_settings(config: Mapping) -> tuple[dict, SolverSettings]:
    """The model overrides and solver settings of a configuration, as the jobs read them."""
    return dict(config.get("model") or {}), SolverSettings(**config["solver"])


def _map_arguments(config: Mapping, figure: str, level: str) -> dict:
    fig, _ = FIGURES[figure]
    args = EXPERIMENTS[fig].arguments(config)
    for name, step in zip(("theta0", "delta0"), LEVELS[level], strict=True):
        args[name] = {**args[name], "step": step}
    return args


def map_axes(config: Mapping, figure: str, level: str) -> tuple[np.ndarray, np.ndarray]:
    """The theta0 and delta0 of a map level (degree)."""
    args = _map_arguments(config, figure, level)
    return axis(args["theta0"]), axis(args["delta0"])


def map_shape(config: Mapping, figure: str, level: str) -> tuple[int, int]:
    """The (theta0, delta0) size of a map level."""
    args = _map_arguments(config, figure, level)
    return axis_size(args["theta0"]), axis_size(args["delta0"])


def map_level(
    config: Mapping,
    figure: str,
    level: str,
    stale: Callable[[], bool] = lambda: False,
    threads: int | None = None,
) -> xr.Dataset | None:
    """The map of ``figure`` at ``level``, computed by the figure's experiment in
    :data:`BLOCKS` row blocks; None when ``stale()`` turns true between two blocks."""
    fig, _ = FIGURES[figure]
    args = _map_arguments(config, figure, level)
    model, settings = model_and_settings(config)
    count = chunk_count(BLOCKS[level], axis_size(args["theta0"]))
    blocks = []
    for index in range(count):
        if stale():
            return None
        blocks.append(compute(EXPERIMENTS[fig], args, model, settings, (index, count), threads))
    return blocks[0] if count == 1 else xr.concat(blocks, "theta0", data_vars="minimal")


def fig9_curve(config: Mapping, threads: int | None = None) -> xr.Dataset:
    """Fig. 9's delay curve at the configuration (its experiment, its grid)."""
    model, settings = model_and_settings(config)
    experiment = EXPERIMENTS["fig9"]
    ds = compute(experiment, experiment.arguments(config), model, settings, None, threads)
    return ds.isel(delta0=0)


def stroke_at(config: Mapping, figure: str, theta0: float, delta0: float) -> xr.Dataset:
    """The stroke at ``(theta0, delta0)`` of the map of ``figure``: its curves as Fig. 4
    draws them (its times and curves setting), one stroke."""
    fig, index = FIGURES[figure]
    model, settings = model_and_settings(config)
    spec = config["fig4"]
    times = np.linspace(0.0, float(spec["t_end"]), int(spec["samples"]))
    params = {**model, "L1": float(value_at(config, f"angle_maps.L1.{index}"))}
    label = f"theta0 {theta0:g}, delta0 {delta0:g} deg"
    return trajectories(
        [(float(theta0), float(delta0), {})],
        [label],
        times,
        params,
        settings,
        str(config.get("figure_curves", "free_swing")),
    )


def view_claims(claims: Sequence[Mapping]) -> list[Mapping]:
    """The claims whose every file is one of the explorer's views (:data:`VIEW_FILES`)."""
    return [c for c in claims if set(claim_files(c)) <= set(VIEW_FILES)]


def claims_table(
    config: Mapping,
    claims: Sequence[Mapping],
    fit_of_claim: Mapping[str, str],
    threads: int | None = None,
) -> pd.DataFrame:
    """The verdicts of ``claims`` (:func:`view_claims`) at the configuration: the claims
    job's targeted evaluation and :func:`~tennis_stroke.replication.claims.evaluate`; a
    claim whose measurement would read off the configuration's axes has status
    :data:`OFF_AXIS` and no value."""
    model, settings = model_and_settings(config)
    keys = sorted({f for c in claims for f in claim_files(c)}, key=VIEW_FILES.index)
    found = searched_files(config, model, settings, None, threads, keys)
    rows = []
    for claim in claims:  # one at a time: a claim off the axes leaves the others
        try:
            rows.append(evaluate([claim], found, fit_of_claim))
        except OffAxisError:
            rows.append(pd.DataFrame([{**_OFF_AXIS_ROW, **_declared(claim)}]))
    return pd.concat(rows, ignore_index=True)


#: The status of a claim whose measurement reads a value off the configuration's axes (a
#: map narrower than the paper's: the workflow refuses it before any job; the explorer
#: shows the claim's row without a value).
OFF_AXIS = "off_axis"
_OFF_AXIS_ROW = {"reproduced_value": np.nan, "status": OFF_AXIS}


def _declared(claim: Mapping) -> dict:
    return {k: claim[k] for k in ("id", "quantity", "unit", "paper_value", "tolerance")}
