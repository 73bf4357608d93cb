"""What the targeted evaluation of the claims (:mod:`tennis_stroke.inference.targeted`)
searches and reads of a configuration, without its searches: the jobs' params and the
workflow's plan read these without loading the solver.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping

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
