"""What the live explorer computes (``tennis-stroke explore``), without the server: the
controls with their units, bounds and the paper's values, and each view at a setting.

A setting is a scenario's overrides (:mod:`tennis_stroke.pipeline.scenarios`): the
paper's configuration (``config/config.yaml``) with ``model``, ``solver``,
``angle_maps`` and ``torque_delay`` values changed, so what a reader finds can be saved
as a scenario and computed whole by the workflow.  Every view is computed by the
workflow's own functions on the configuration with those overrides:

* the map of Fig. 2 or 3 (:func:`map_block`: the figure's experiment, row block by row
  block, at the explorer's :data:`LEVELS`, coarse then full; each stroke by
  :func:`~tennis_stroke.solver.stroke.strike_batch`, so a cell's value is that of the
  stroke at its coordinates);
* Fig. 9's delay curve (:func:`fig9_curve`, its experiment at the configured grid);
* the stroke at a picked point (:func:`stroke_at`, the curves of Fig. 4);
* the claims these views test (:func:`view_claims`): the targeted evaluation of the
  claims job (:func:`~tennis_stroke.inference.targeted.searched_files`) and its verdicts
  (:func:`~tennis_stroke.replication.claims.evaluate`), not a copy.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd
import xarray as xr

from ..experiments.grids import axis, axis_size, chunk_count
from ..experiments.specs import EXPERIMENTS, compute, merged
from ..experiments.strokes import trajectories
from ..inference.claims import claim_files
from ..inference.targeted import searched_files
from ..io.config_files import value_at
from ..model.listing import origin
from ..model.params import CHOICES, PARAMETERS
from ..solver.settings import METHOD_IDS, SolverSettings
from .claims import evaluate

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
#: The solver tolerances offered (rtol = atol), loosest first; the paper's 5e-8 among them.
TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7, 5e-8, 1e-8, 1e-9, 1e-10)


class ExplorerError(ValueError):
    """A setting the explorer cannot compute (one line)."""


@dataclass(frozen=True)
class Control:
    """One control: the dotted config ``key`` it sets, its label and unit, its value in
    the paper's configuration (``paper``) and where that value comes from (``origin``,
    :data:`tennis_stroke.model.listing.ORIGINS`: the paper, fitted, derived, ours), its
    bounds (None: unbounded; a number control refuses what is outside) and step, or its
    ``choices``."""

    key: str
    label: str
    unit: str
    paper: float | str
    low: float | None = None
    high: float | None = None
    step: float | None = None
    choices: tuple[str, ...] = ()
    note: str = ""
    origin: str = "paper"


def _control_step(value: float) -> float:
    """A control's step: about a hundredth of the paper's value, a power of ten."""
    return 10.0 ** np.floor(np.log10(abs(value)) - 2) if value else 0.01


def _bounds(spec) -> tuple[float | None, float | None]:
    """A parameter's bounds for an input that refuses what is outside them: an exclusive
    lower bound becomes the smallest step above it."""
    low = spec.lower
    if low is not None and spec.strict:
        low = low + _control_step(spec.default or 1.0)
    return low, spec.upper


#: Parameters a view sets itself (their controls are the figures' values below), and
#: those derived from others (shown, not set: their reading is the control).
_SET_BY_VIEWS = ("L1",)


def controls(config: Mapping, figure: str, fitted: Collection[str] = ()) -> list[Control]:
    """Every control, in the order the page shows them: the model's parameters (less
    the derived ones and ``L1``, which each figure sets), the readings and model
    options, the solver, then the figures' own values (the map's ``L1``; Fig. 9's arm,
    initial angles and wrist torque).  ``fitted``: the names whose default is fitted
    (their ``origin``)."""
    out = []
    for name, spec in PARAMETERS.items():
        if spec.derived or name in _SET_BY_VIEWS:
            continue
        low, high = _bounds(spec)
        note = "Figs. 2-3; Fig. 9 sets its own" if name in ("C2", "tau") else ""
        out.append(
            Control(
                f"model.{name}",
                name,
                spec.unit,
                spec.default,
                low,
                high,
                _control_step(spec.default),
                note=note or spec.description,
                origin=origin(name, fitted),
            )
        )
    for name, reading in CHOICES.items():
        out.append(
            Control(
                f"model.{name}",
                name,
                "",
                reading.default,
                choices=reading.choices,
                note=f"{reading.description} (the paper's words: {reading.literal})",
                origin=origin(name, fitted),
            )
        )
    solver = SolverSettings(**config["solver"])
    out.append(
        Control(
            "solver.method", "method", "", solver.method, choices=tuple(METHOD_IDS), origin="ours"
        )
    )
    out.append(
        Control(
            "solver.rtol",
            "rtol = atol",
            "1",
            f"{solver.rtol:g}",
            choices=tuple(f"{t:g}" for t in TOLERANCES),
            origin="ours",
        )
    )
    fig, index = FIGURES[figure]
    l1 = PARAMETERS["L1"]
    out.append(
        Control(
            f"angle_maps.L1.{index}",
            f"L1 of the {fig} map",
            l1.unit,
            value_at(config, f"angle_maps.L1.{index}"),
            *_bounds(l1),
            0.01,
            note=l1.description,
        )
    )
    for key, label, unit, low, high, step in (  # values the paper states (Sec. V)
        ("torque_delay.L1", "L1 of Fig. 9", "m", *_bounds(l1), 0.01),
        ("torque_delay.theta0", "theta0 of Fig. 9", "degree", 0.0, 180.0, 0.5),
        ("torque_delay.base_stroke.delta0", "delta0 of Fig. 9", "degree", -90.0, 180.0, 0.5),
        ("torque_delay.base_stroke.C2", "C2 of Fig. 9", "N m", None, None, 0.1),
    ):
        out.append(Control(key, label, unit, value_at(config, key), low, high, step))
    return out


def overrides(config: Mapping, values: Mapping[str, object]) -> dict:
    """A scenario's overrides (nested, in the shape of the config) from control values
    by dotted key, keeping only those that differ from ``config``'s; ``solver.rtol``
    sets ``atol`` too."""
    out: dict = {}
    for key, value in values.items():
        if key == "solver.rtol":
            value = float(value)
        paper = config_value(config, key)
        if _same(paper, value):
            if key != "solver.rtol" or _same(config_value(config, "solver.atol"), value):
                continue
        parts = key.split(".")
        if parts[0] == "angle_maps" and parts[1] == "L1":  # a list: set whole
            current = list(value_at(config, "angle_maps.L1"))
            base = out.setdefault("angle_maps", {}).get("L1", current)
            base[int(parts[2])] = float(value)
            out["angle_maps"]["L1"] = base
            continue
        node = out
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = value
        if key == "solver.rtol":
            node["atol"] = value
    return out


def config_value(config: Mapping, key: str):
    """The value a configuration gives the control ``key`` (a model parameter's or
    reading's default where the config leaves it out)."""
    section, _, name = key.partition(".")
    if section == "model":
        model = config.get("model") or {}
        if name in model:
            return model[name]
        return PARAMETERS[name].default if name in PARAMETERS else CHOICES[name].default
    return value_at(config, key)


def _same(a, b) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return str(a) == str(b)
    return bool(np.isclose(float(a), float(b), rtol=1e-12, atol=0.0))


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
    job's targeted evaluation and :func:`~tennis_stroke.replication.claims.evaluate`."""
    model, settings = model_and_settings(config)
    keys = sorted({f for c in claims for f in claim_files(c)}, key=VIEW_FILES.index)
    found = searched_files(config, model, settings, None, threads, keys)
    return evaluate(list(claims), found, fit_of_claim)


def configuration(paper: Mapping, values: Mapping[str, object]) -> dict:
    """The configuration at control values: the paper's with :func:`overrides`."""
    return merged(paper, overrides(paper, values))
