"""What the targeted evaluation of the claims (:mod:`tennis_stroke.inference.targeted`)
searches and reads of a configuration, without its searches: the jobs' params and the
workflow's plan read these without loading the solver.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping

from ..experiments.grids import axis_size, bracket_size
from ..io.config_files import ConfigKeyError, value_at

#: The keys of the search section of the config (and their units).
SEARCH_KEYS = {
    "angle_step": "degree",
    "tau_step": "s",
    "psi_F_step": "degree",
    "tau_F_step": "s",
    "angle_tolerance": "degree",
    "time_tolerance": "s",
    "C2_step": "N m",
    "C2_tolerance": "N m",
}
#: The result files the targeted evaluation finds by a search (the others it computes
#: as the workflow does, less what no claim reads: :data:`NUMBERS_ONLY`).
SEARCHED = ("fig2", "fig3", "ml", "fig7", "fig8", "fig9", "elbow_map")
#: Files of single strokes whose claims read only the strokes' numbers (not the curves):
#: computed without the curves.
NUMBERS_ONLY = ("elbow",)
#: The config ranges the targeted evaluation reads without their step (a map's step,
#: which it does not use: changing it reruns no targeted job).
UNREAD_STEPS = (
    "angle_maps.delta0",
    "torque_delay.fig7.C2",
    "torque_delay.fig8.delta0",
    "torque_delay.fig8.tau",
    "torque_delay.fig9.tau",
    "elbow_force.psi_F",
    "elbow_force.tau_F",
)


#: The config keys of the steps of each searched file's coarse bracket (a memory
#: message names them).
BRACKET_KEYS = {
    "fig2": ("search.angle_step",),
    "fig3": ("search.angle_step",),
    "ml": ("mass_length.coarse_step",),
    "fig7": ("search.C2_step", "search.tau_step"),
    "fig8": ("search.angle_step", "search.tau_step"),
    "fig9": ("search.tau_step",),
    "elbow_map": ("search.psi_F_step", "search.tau_F_step"),
}


def _bracket(spec, step: float) -> int:
    """Points of a search's bracket over a range (a ``{start, stop}`` mapping or a
    ``[lower, upper]`` pair) ``step`` apart."""
    lower, upper = (spec["start"], spec["stop"]) if isinstance(spec, Mapping) else spec
    return bracket_size(float(lower), float(upper), float(step))


def search_strokes(key: str, args: Mapping, search: Mapping) -> int:
    """Strokes of the largest batch of one reading's search of the searched file ``key``
    (:data:`SEARCHED`; ``args``: the file's arguments, ``search``: the config's ``search``
    section), from the sizes alone: the coarse bracket of every problem at once, the first
    batch of :func:`tennis_stroke.experiments.search.maximize` and the largest (the compass
    steps that follow evaluate a few points per problem).  Readings searched in lockstep
    multiply it (:func:`tennis_stroke.inference.targeted.searched_files_of`)."""
    if key in ("fig2", "fig3"):  # every theta0 row along delta0
        return axis_size(args["theta0"]) * _bracket(args["delta0"], search["angle_step"])
    if key == "ml":  # every M2 at the two ends of L1, over (theta0, delta0)
        step = args["coarse_step"]
        grid = _bracket(args["theta0_range"], step) * _bracket(args["delta0_range"], step)
        return axis_size(args["M2"]) * 2 * grid
    if key == "fig7":  # the C2 rows along tau
        return _bracket(args["C2"], search["C2_step"]) * _bracket(args["tau"], search["tau_step"])
    if key == "fig8":  # (delta0, tau)
        return _bracket(args["delta0"], search["angle_step"]) * _bracket(
            args["tau"], search["tau_step"]
        )
    if key == "fig9":  # tau
        return _bracket(args["tau"], search["tau_step"])
    if key == "elbow_map":  # (psi_F, tau_F), the largest then the smallest
        return _bracket(args["psi_f"], search["psi_F_step"]) * _bracket(
            args["tau_f"], search["tau_F_step"]
        )
    raise KeyError(f"{key!r} is not a searched file ({', '.join(SEARCHED)})")


def targeted_config(config: Mapping) -> dict:
    """``config`` less what the targeted evaluation does not read: the steps of
    :data:`UNREAD_STEPS` (the params of the jobs that run it)."""
    out = copy.deepcopy(dict(config))
    for key in UNREAD_STEPS:
        try:
            node = value_at(out, key)
        except ConfigKeyError:
            continue
        if isinstance(node, dict):
            node.pop("step", None)
    return out
