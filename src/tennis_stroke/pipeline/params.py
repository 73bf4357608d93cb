"""What each workflow job reads of a configuration: its rule's params, as plain data.

A job's params are the config values it reads, and nothing else: Snakemake reruns a job
when they change (it compares their ``repr``), so a change of another key reruns nothing
of it.  The same functions give the params of the paper's jobs (the workflow config) and
of a scenario's (the config with the scenario's overrides,
:mod:`tennis_stroke.pipeline.scenarios`), and tell which files a scenario changes: those
whose job reads a value it overrides (:func:`changed_results`).
"""

from __future__ import annotations

from collections.abc import Mapping

from ..experiments.specs import (
    EXPERIMENTS,
    PAPER_RESULTS,
    VALIDATION_GROUPS,
    Experiment,
    pruned,
    sorted_data,
)
from ..inference.reading_space import MULTIVERSE_SETS
from ..inference.search_plan import targeted_config


def model(config: Mapping) -> dict:
    """Model overrides as a plain dict in a fixed order (params compare by repr)."""
    return dict(sorted((config.get("model") or {}).items()))


def solver(config: Mapping) -> dict:
    """Solver settings as a plain dict."""
    return dict(sorted(config["solver"].items()))


def common_params(config: Mapping) -> dict:
    """Params every model simulation needs."""
    return {"model": model(config), "solver": solver(config)}


def simulation_params(experiment: Experiment, config: Mapping) -> dict:
    """A row's params: what the job runs (its row: function and flags), the config values
    it reads and, for a model row, the model overrides and solver settings."""
    out = {
        "experiment": {
            "key": experiment.key,
            "function": experiment.function,
            "model": experiment.model,
            "chunks": bool(experiment.chunks),
            "threaded": experiment.threaded,
        },
        "args": experiment.arguments(config),
    }
    if experiment.model:
        common = common_params(config)
        # the parameters the row sets itself: an override of them reaches nothing of it
        common["model"] = {k: v for k, v in common["model"].items() if k not in experiment.sets}
        out["common"] = common
    return out


#: The config sections the paper's experiments read and the claims' search settings
#: (section ``search``), less those the multiverse sets itself.
PAPER_SECTIONS = tuple(
    sorted(
        {key.split(".")[0] for e in EXPERIMENTS.values() if e.family == "paper" for key in e.keys()}
        - set(MULTIVERSE_SETS)
        | {"search"}
    )
)


def paper_sections(config: Mapping) -> dict:
    """The :data:`PAPER_SECTIONS` of ``config``."""
    # plain: keys sorted, as a --config merge reorders them (params compare by repr)
    return sorted_data({k: config[k] for k in PAPER_SECTIONS})


def paper_experiments(config: Mapping) -> dict:
    """What the targeted evaluation of the claims reads (the claims job and the
    robustness analysis rerun it): :func:`paper_sections` less the steps of the maps it
    searches instead (:func:`tennis_stroke.inference.search_plan.targeted_config`)."""
    return sorted_data(targeted_config(paper_sections(config)))


def claims_params(config: Mapping) -> dict:
    """What the claims job reads besides its files: the targeted evaluation's sections and
    the model and solver."""
    return {"experiments": paper_experiments(config), "common": common_params(config)}


def group_config(config: Mapping, group: str) -> dict:
    """What a validation job of ``group`` reads of the workflow ``config``: the keys of
    its files' rows and the ``search`` section (its params)."""
    keys = [k for key in VALIDATION_GROUPS[group] for k in EXPERIMENTS[key].keys()]
    return sorted_data({**pruned(config, keys), "search": config["search"]})


def changed_results(base: Mapping, other: Mapping) -> list[str]:
    """The paper's result files (keys of :data:`PAPER_RESULTS`) whose job reads a value
    that differs between configs ``base`` and ``other``, in the table's order."""
    return [
        key
        for key in PAPER_RESULTS
        if simulation_params(EXPERIMENTS[key], base) != simulation_params(EXPERIMENTS[key], other)
    ]


def read_keys(experiment: Experiment) -> list[str]:
    """The dotted config keys a row's job reads: its arguments' and, for a model row,
    the sections ``model`` and ``solver``."""
    return [*experiment.keys(), *(["model", "solver"] if experiment.model else [])]


def unread(experiment: Experiment, key: str) -> bool:
    """Whether config ``key`` is a model parameter the row sets itself (``sets``)."""
    section, _, name = key.partition(".")
    return section == "model" and name in experiment.sets


def reads(experiment: Experiment, key: str) -> bool:
    """Whether a change of config ``key`` changes what the row's job gets."""
    if unread(experiment, key):
        return False
    return any(related(key, r) for r in read_keys(experiment))


def related(key: str, read: str) -> bool:
    """Whether a change of config ``key`` changes what a job reading ``read`` gets: the
    same key, one inside it, or one holding it (``torque_delay`` holds
    ``torque_delay.L1``; a list is read whole: ``angle_maps.L1`` holds
    ``angle_maps.L1.0``)."""
    return key == read or key.startswith(f"{read}.") or read.startswith(f"{key}.")
