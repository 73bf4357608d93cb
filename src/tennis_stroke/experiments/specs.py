"""The one table of experiments: for each result file, what computes it from which keys
of the workflow config.

Each :class:`Experiment` row names its result file, the function that computes it (by
import path, so this table stays light: the Snakefile imports it without numba), the
config keys each argument of the function reads, how the map splits into chunks, how
many strokes it runs at once (the memory estimate before any job) and the variables of
its file.  Everything that wires an experiment reads this table: the workflow's rules
read a row by its file's stem (``workflow/rules/experiments.smk``), the generic script
runs the row (:func:`compute`), the config check estimates the memory of every row's largest job,
the robustness analysis reruns the paper's rows under each reading
(:func:`tennis_stroke.inference.multiverse.paper_results`), and the tests check every row
end to end.  Adding an experiment takes a function, a row, its config section (with its
schema) and its claims.

A config key is a dotted path into the workflow config (``angle_maps.theta0``); a number
in it indexes a list (``angle_maps.L1.0``, Fig. 2's length).  An argument is a key, or a
mapping of names to keys (the function gets a dict).  A row with ``model=True`` also gets
the model overrides (``params``) and the solver settings (``settings``); a row with
``chunks`` gets ``rows = (index, count)``, the chunk of its first axis (the argument
``rows``); a ``threaded`` row gets ``threads``.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from importlib import import_module

import numpy as np

from ..io.config_files import value_at
from ..solver.results import FILE_NAMES, RESULT_FIELDS
from .grids import axis, axis_size, bracket_size

#: Variables of every file of strokes (one per stroke result field).
STROKE_VARIABLES = tuple(FILE_NAMES.get(k, k) for k in RESULT_FIELDS)
#: The stick figure's points of a single stroke over time (the report animates them).
POINTS = ("x_wrist", "y_wrist", "x_racket", "y_racket", "x_hit", "y_hit")
#: Variables of the sampled curves of single strokes.
CURVE_VARIABLES = (
    "omega1",
    "omega2",
    "theta",
    "phi",
    "x_elbow",
    "y_elbow",
    *POINTS,
    "kinetic_energy",
)
#: The config keys of the Sec. V-VI base stroke (Fig. 9's curve, Figs. 10-14, Table I).
SEC5_STROKE = {
    "L1": "torque_delay.L1",
    "theta0": "torque_delay.theta0",
    "C2": "torque_delay.base_stroke.C2",
    "delta0": "torque_delay.base_stroke.delta0",
    "tau_L": "torque_delay.strokes.tau_L",
    "tau_H": "torque_delay.strokes.tau_H",
    "t_end": "torque_delay.strokes.t_end",
    "samples": "torque_delay.strokes.samples",
}


#: The model parameters of the Sec. V-VI base stroke's values (checked before any job).
SEC5_BOUNDS = {"stroke.L1": "L1", "stroke.C2": "C2", "stroke.tau_L": "tau", "stroke.tau_H": "tau"}
#: The model parameters the rows of the Sec. V-VI stroke set themselves, and whence.
SEC5_SETS = {"L1": "stroke.L1", "C2": "stroke.C2", "tau": "stroke.tau_L"}
#: The initial angles of the Sec. V-VI base stroke (checked before any job).
SEC5_ANGLES = ("stroke.theta0", "stroke.delta0")


def _points(value) -> int:
    """Points of an axis: a range's grid size, a list's length, a mapping's entries (a
    study's scenes), else 1."""
    if isinstance(value, Mapping) and "step" in value:
        return axis_size(value)
    if isinstance(value, list | tuple | Mapping):
        return len(value)
    return 1


@dataclass(frozen=True)
class Experiment:
    """One result file and what computes it.

    ``key``: the name claims and figures use; ``path``: the file, relative to the working
    directory; ``function``: ``module:function`` below ``tennis_stroke``; ``args``:
    argument -> config key (or a mapping of names to keys); ``family``: ``paper`` (the
    paper's experiments: rerun by the robustness analysis) or ``study``; ``chunks``: the
    config key of the chunk count (None: one job), or the key of the split axis itself
    for one job per entry (the work-precision study's scenes), ``rows`` the argument
    whose axis is split; ``strokes``: the strokes of the unchunked job's batches run at
    once, from its arguments (None: no estimate); ``gathered``: the gathered map holds
    one result per stroke of the first batch (its memory is estimated); ``samples``: the
    (stroke, time) points of its sampled curves, from its arguments (None: no curves);
    ``variables``: the file's data variables; ``label``: what a message calls it,
    ``section`` the config key it names; ``rule``: the row's name in the workflow's
    plans and tests (default: the key); ``bounds``: argument (``force.F0`` inside a
    mapping argument) -> the model parameter
    (:data:`tennis_stroke.model.params.PARAMETERS`) whose unit and bounds its values
    have, checked before any job; ``sets``: the model parameters the row's function sets
    itself at every stroke, each with the argument it takes it from (an axis or a value
    of its own), so a model override of them reaches nothing of it and is not passed to
    its job (:meth:`reads_instead` names the config key it reads); ``angles``: the
    arguments holding its strokes' initial angles, checked before any job by the rule of
    :data:`tennis_stroke.model.params.INITIAL_ANGLES`: ``(theta0, delta0)``, every
    theta0 with every delta0 (values, ranges or search ranges), or one argument of
    ``(theta0, delta0)`` pairs.
    """

    key: str
    path: str
    function: str
    args: Mapping[str, str | Mapping[str, str]]
    variables: tuple[str, ...]
    label: str
    family: str = "paper"
    model: bool = True
    threaded: bool = False
    chunks: str | None = None
    rows: str | None = None
    strokes: Callable[[Mapping], tuple[int, ...]] | None = None
    gathered: bool = False
    samples: Callable[[Mapping], int] | None = None
    section: str = ""
    rule: str = ""
    bounds: Mapping[str, str] = field(default_factory=dict)
    sets: Mapping[str, str] = field(default_factory=dict)
    angles: tuple[str, ...] = ()

    @property
    def stem(self) -> str:
        """The file's path without ``results/`` and ``.nc`` (a rule's wildcard value)."""
        return self.path.removeprefix("results/").removesuffix(".nc")

    def __post_init__(self) -> None:
        if not self.rule:
            object.__setattr__(self, "rule", self.key)

    def key_of(self, argument: str) -> str:
        """The config key of ``argument`` (``force.F0``: key ``F0`` of argument ``force``)."""
        name, _, inner = argument.partition(".")
        key = self.args[name]
        return key[inner] if inner else key

    def reads_instead(self, parameter: str) -> str | None:
        """The config key the row takes model ``parameter`` from (None: the model's)."""
        argument = self.sets.get(parameter)
        return None if argument is None else self.key_of(argument)

    def keys(self) -> list[str]:
        """Every config key the row reads (its arguments'), in order."""
        out = []
        for value in self.args.values():
            out.extend(value.values() if isinstance(value, Mapping) else [value])
        return out

    def arguments(self, config: Mapping) -> dict[str, object]:
        """Its arguments from the workflow ``config`` (plain values, mappings with sorted
        keys: a rule's params, which Snakemake compares by ``repr``)."""
        return {
            name: (
                {k: sorted_data(value_at(config, v)) for k, v in sorted(key.items())}
                if isinstance(key, Mapping)
                else sorted_data(value_at(config, key))
            )
            for name, key in self.args.items()
        }

    def axis_ends(self, config: Mapping, coord: str) -> tuple[float, float, str] | None:
        """The first and last value of the file's axis ``coord`` under ``config`` and the
        config key it comes from: the grid of a range (:func:`~.grids.axis`), a list's
        smallest and largest item, a single value twice; None where no argument of the
        row is that axis."""
        key = self.args.get(coord)
        if not isinstance(key, str):
            return None
        value = value_at(config, key)
        values = axis(value) if isinstance(value, Mapping) else np.atleast_1d(value)
        values = np.asarray(values, dtype=float)
        return float(values.min()), float(values.max()), key

    def row_count(self, arguments: Mapping) -> int:
        """Points of the axis it is chunked along (1 for an unchunked row)."""
        return _points(arguments[self.rows]) if self.rows else 1

    def requested_chunks(self, config: Mapping) -> int:
        """The chunk count ``config`` asks of a chunked row: the value at ``chunks``, or
        one per entry of the split axis where ``chunks`` is that axis' own key."""
        if self.chunks == self.key_of(self.rows):
            return self.row_count(self.arguments(config))
        return int(value_at(config, self.chunks))

    def callable(self) -> Callable:
        module, name = self.function.split(":")
        return getattr(import_module(f"tennis_stroke.{module}"), name)


def pruned(config: Mapping, keys) -> dict:
    """The part of ``config`` at the dotted ``keys`` (their parents as nested dicts; a
    list is taken whole): what a job that reads only those keys gets, so that a change of
    another key reruns nothing of it."""
    out: dict = {}
    for key in keys:
        node, source = out, config
        parts = key.split(".")
        for n, part in enumerate(parts):
            value = value_at(source, part)
            if n == len(parts) - 1 or isinstance(value, list):
                node[part] = sorted_data(value)
                break
            node, source = node.setdefault(part, {}), value
    return out


def merged(base: Mapping, overrides: Mapping) -> dict:
    """``base`` with ``overrides`` applied (neither is changed): mappings merge key by
    key, any other value (a number, a list, a range given whole) replaces the base's, as
    a nested ``--config`` value does."""
    out = copy.deepcopy(dict(base))
    for key, value in overrides.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = merged(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def shown(value) -> str:
    """A config value as a message or a page shows it: numbers in ``g`` format, lists and
    mappings in flow style."""
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k}: {shown(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(shown(v) for v in value) + "]"
    return str(value)


def sorted_data(value):
    """``value`` as plain data: mappings as dicts with sorted keys, sequences as lists."""
    if isinstance(value, Mapping):
        return {str(k): sorted_data(value[k]) for k in sorted(value)}
    if isinstance(value, list | tuple):
        return [sorted_data(v) for v in value]
    return value


def compute(
    experiment: Experiment,
    arguments: Mapping[str, object],
    model: Mapping[str, object] | None = None,
    settings=None,
    rows: tuple[int, int] | None = None,
    threads: int | None = None,
):
    """Run one row: its function on ``arguments`` (:meth:`Experiment.arguments`), with the
    model overrides and solver settings of a model row, the chunk ``rows = (index,
    count)`` of a chunked row and ``threads`` of a threaded one.  Returns its dataset."""
    kwargs = dict(arguments)
    if experiment.model:
        kwargs.update(params=dict(model or {}), settings=settings)
    if experiment.chunks:
        kwargs["rows"] = rows
    if experiment.threaded:
        kwargs["threads"] = threads
    return experiment.callable()(**kwargs)


def _grid(a, key) -> int:
    return _points(a[key])


def _mass_length_strokes(a) -> tuple[int, ...]:
    """The coarse bracket of every point at once (the largest batch of the search)."""
    points = _grid(a, "M2") * _grid(a, "L1")
    coarse = bracket_size(*a["theta0_range"], a["coarse_step"])
    coarse *= bracket_size(*a["delta0_range"], a["coarse_step"])
    return (points * coarse,)


def _delay_strokes(first: str) -> Callable[[Mapping], tuple[int, ...]]:
    return lambda a: (_grid(a, first) * _grid(a, "tau"),)


def _angle_map(fig: str, index: int) -> Experiment:
    return Experiment(
        fig,
        f"results/angle_maps/{fig}.nc",
        "experiments.maps:angle_map_section",
        {
            "theta0": "angle_maps.theta0",
            "delta0": "angle_maps.delta0",
            "L1": f"angle_maps.L1.{index}",
        },
        (*STROKE_VARIABLES, "best_delta0", "best_v_out"),
        "Figs. 2-3 map",
        section="angle_maps",
        bounds={"L1": "L1"},
        sets={"L1": "L1"},
        angles=("theta0", "delta0"),
        threaded=True,
        chunks="chunks.angle_map",
        rows="theta0",
        strokes=lambda a: (_grid(a, "theta0") * _grid(a, "delta0"),),
        gathered=True,
    )


def _delay_map(
    fig: str, first: str, other: str, *, first_from: str = "", other_from: str = ""
) -> Experiment:
    """A delay map of Figs. 7-9: ``first`` (its chunked axis) read from
    ``torque_delay.{first_from}`` and ``other`` from ``torque_delay.{other_from}`` (default:
    the figure's own section; ``base_stroke``: the Sec. V-VI stroke's value, which the
    figure does not write again), ``tau`` from the figure's."""
    return Experiment(
        fig,
        f"results/torque_delay/{fig}.nc",
        "experiments.maps:torque_delay_section",
        {
            "L1": "torque_delay.L1",
            "theta0": "torque_delay.theta0",
            first: f"torque_delay.{first_from or fig}.{first}",
            other: f"torque_delay.{other_from or fig}.{other}",
            "tau": f"torque_delay.{fig}.tau",
        },
        (*STROKE_VARIABLES, "best_tau", "best_v_out", "v_out_tau0"),
        f"Fig. {fig[3:]} map",
        section=f"torque_delay.{fig}",
        bounds={"L1": "L1", "C2": "C2", "tau": "tau"},
        sets={"L1": "L1", "C2": "C2", "tau": "tau"},
        angles=("theta0", "delta0"),
        threaded=True,
        chunks="chunks.delay_map",
        rows=first,
        strokes=_delay_strokes(first),
        gathered=True,
    )


#: The paper's angle maps in the order of the config's ``angle_maps.L1`` (the rod-1
#: length of each): Fig. 2 first, Fig. 3 second.
ANGLE_MAP_FIGURES = ("fig2", "fig3")

#: The table: every result file computed from the config alone, by key.
EXPERIMENTS: dict[str, Experiment] = {
    e.key: e
    for e in [
        *(_angle_map(fig, i) for i, fig in enumerate(ANGLE_MAP_FIGURES)),
        Experiment(
            "fig4",
            "results/strokes/fig4.nc",
            "experiments.strokes:fig4_strokes",
            {
                "strokes": "fig4.strokes",
                "t_end": "fig4.t_end",
                "samples": "fig4.samples",
                "curves": "figure_curves",
            },
            (*STROKE_VARIABLES, *CURVE_VARIABLES),
            "Fig. 4 strokes",
            section="fig4",
            angles=("strokes",),
            samples=lambda a: len(a["strokes"]) * int(a["samples"]),
        ),
        Experiment(
            "k_sensitivity",
            "results/strokes/k_sensitivity.nc",
            "experiments.maps:k_sensitivity_map",
            {
                "strokes": "fig4.strokes",
                "k_range": "k_sensitivity.k_contact",
                "points": "k_sensitivity.points",
            },
            STROKE_VARIABLES,
            "k sensitivity",
            section="k_sensitivity",
            bounds={"k_range": "k_contact"},
            sets={"k_contact": "k_range"},
            angles=("strokes",),
            threaded=True,
            strokes=lambda a: (len(a["strokes"]) * int(a["points"]),),
        ),
        Experiment(
            "ml",
            "results/mass_length/map.nc",
            "experiments.optima:mass_length_section",
            {
                "M2": "mass_length.M2",
                "L1": "mass_length.L1",
                "theta0_range": "mass_length.theta0_range",
                "delta0_range": "mass_length.delta0_range",
                "coarse_step": "mass_length.coarse_step",
                "tolerance": "mass_length.tolerance",
            },
            (
                "v_out_best",
                "theta0_best",
                "delta0_best",
                "theta_c",
                "failed_strokes",
                "evaluated_strokes",
            ),
            "Figs. 5-6 map",
            section="mass_length",
            bounds={"M2": "M2", "L1": "L1"},
            sets={"M2": "M2", "L1": "L1"},
            angles=("theta0_range", "delta0_range"),
            rule="mass_length",
            threaded=True,
            chunks="chunks.mass_length",
            rows="M2",
            strokes=_mass_length_strokes,
        ),
        _delay_map("fig7", "C2", "delta0"),
        _delay_map("fig8", "delta0", "C2", other_from="base_stroke"),
        _delay_map("fig9", "delta0", "C2", first_from="base_stroke", other_from="base_stroke"),
        Experiment(
            "delay",
            "results/strokes/delay.nc",
            "experiments.strokes:delay_strokes",
            {"stroke": SEC5_STROKE, "curves": "figure_curves"},
            (*STROKE_VARIABLES, *CURVE_VARIABLES, "tau"),
            "Figs. 10-12 strokes",
            section="torque_delay.strokes",
            bounds=SEC5_BOUNDS,
            sets=SEC5_SETS,
            angles=SEC5_ANGLES,
            rule="delay_strokes",
            samples=lambda a: 2 * int(a["stroke"]["samples"]),  # tau_L and tau_H
        ),
        Experiment(
            "elbow_map",
            "results/elbow_force/map.nc",
            "experiments.maps:elbow_force_section_map",
            {
                "force": {"F0": "elbow_force.F0", "t_d": "elbow_force.t_d"},
                "psi_f": "elbow_force.psi_F",
                "tau_f": "elbow_force.tau_F",
                "stroke": SEC5_STROKE,
            },
            STROKE_VARIABLES,
            "Fig. 13 map",
            section="elbow_force",
            bounds={**SEC5_BOUNDS, "force.F0": "F0", "force.t_d": "t_d"},
            sets={
                **SEC5_SETS,
                "tau": "stroke.tau_H",
                "F0": "force.F0",
                "t_d": "force.t_d",
                "psi_F_deg": "psi_f",
                "t_F": "tau_f",
            },
            angles=SEC5_ANGLES,
            rule="elbow_force_map",
            threaded=True,
            chunks="chunks.elbow_force_map",
            rows="psi_f",
            strokes=lambda a: (_grid(a, "psi_f") * _grid(a, "tau_f"),),
            gathered=True,
        ),
        Experiment(
            "elbow",
            "results/strokes/elbow_force.nc",
            "experiments.strokes:elbow_force_strokes",
            {
                "force": {
                    "F0": "elbow_force.F0",
                    "t_d": "elbow_force.t_d",
                    "table1_psi": "elbow_force.table1_psi",
                    "table1_tau_F": "elbow_force.table1_tau_F",
                },
                "stroke": SEC5_STROKE,
                "curves": "figure_curves",
            },
            (*STROKE_VARIABLES, *CURVE_VARIABLES, "F0", "psi_F"),
            "Table I and Fig. 14 strokes",
            section="elbow_force",
            bounds={**SEC5_BOUNDS, "force.F0": "F0", "force.t_d": "t_d"},
            sets={
                **SEC5_SETS,
                "tau": "stroke.tau_H",
                "F0": "force.F0",
                "t_d": "force.t_d",
                "psi_F_deg": "force.table1_psi",
                "t_F": "force.table1_tau_F",
            },
            angles=SEC5_ANGLES,
            rule="elbow_force_strokes",
            # each direction of Table I and the stroke without the force
            samples=lambda a: (len(a["force"]["table1_psi"]) + 1) * int(a["stroke"]["samples"]),
        ),
        Experiment(
            "work_precision",
            "results/solver_study/work_precision.nc",
            "studies.work_precision:work_precision_study",
            {
                k: f"solver_study.{k}"
                for k in (
                    "scenes",
                    "scene_strokes",
                    "seed",
                    "compiled_tolerances",
                    "scipy_tolerances",
                    "rk4_steps",
                    "scipy_methods",
                    "state_times",
                    "requirement",
                    "repeats",
                )
            },
            (
                "v_out_error",
                "event_time_error",
                "state_error",
                "rhs_evals",
                "us_per_stroke",
                "us_per_stroke_low",
                "us_per_stroke_high",
                "failed",
                "reference_failed",
                "theta0",
                "delta0",
                "scene_params",
                "rule",
            ),
            "work-precision study",
            section="solver_study",
            family="study",
            model=False,
            chunks="solver_study.scenes",  # one job per scene
            rows="scenes",
        ),
        Experiment(
            "convergence",
            "results/solver_study/convergence.nc",
            "studies.convergence:convergence_study",
            {k: f"solver_study.convergence.{k}" for k in ("theta0", "delta0", "t_end", "counts")},
            ("step", "omega_error", "slope", "order"),
            "convergence study",
            section="solver_study.convergence",
            family="study",
            model=False,
            angles=("theta0", "delta0"),
        ),
        Experiment(
            "stability",
            "results/solver_study/stability.nc",
            "studies.stability:stability_study",
            {
                "k_contact": "solver_study.stability.k_contact",
                "cases": "solver_study.stability.cases",
                "paper_k": "k_sensitivity.k_contact",
            },
            ("outcome", "v_exit", "duration", "energy_change", "expected_duration", "setting"),
            "stability study",
            section="solver_study.stability",
            family="study",
            model=False,
        ),
        Experiment(
            "ladder",
            "results/solver_study/ladder.nc",
            "studies.ladder:ladder_study",
            {"strokes": "solver_study.strokes", "seed": "solver_study.seed"},
            ("v_out_spring", "v_out_impact"),
            "model ladder",
            section="solver_study",
            family="study",
            model=False,
        ),
        Experiment(
            "optimum_cost",
            "results/solver_study/optimum_cost.nc",
            "studies.optimum_cost:optimum_cost_study",
            {
                "M2": "solver_study.optimum.M2",
                "L1": "solver_study.optimum.L1",
                "steps": "solver_study.optimum.steps",
                "searches": "solver_study.optimum.searches",
                "reference_step": "solver_study.optimum.reference_step",
            },
            ("v_err", "theta0_err", "delta0_err", "seconds"),
            "optimum-search study",
            section="solver_study.optimum",
            family="study",
            model=False,
        ),
    ]
}


def fit_set_arguments(config: Mapping) -> dict[str, object]:
    """What the fit sets of ``config/readings.yaml`` simulate, from the rows that compute
    it: Fig. 4's strokes (``fig4_strokes``), and Table I's force (``force``) on the Sec.
    V-VI stroke (``stroke``).  The identification and the robustness screen get only these
    keys (the workflow and ``tennis-stroke identify`` alike)."""
    elbow = EXPERIMENTS["elbow"].arguments(config)
    return {
        "fig4_strokes": EXPERIMENTS["fig4"].arguments(config)["strokes"],
        "force": elbow["force"],
        "stroke": elbow["stroke"],
    }


#: The config keys whose values rows of the table put into the model, and the model
#: parameter each is (``Experiment.bounds``: ``torque_delay.L1`` is an ``L1``, in m): what
#: the config check bounds and a scenario's note gives a unit.
#: The config keys of the initial angles the table's rows read (:attr:`Experiment.angles`):
#: ``(theta0 key, delta0 key)``, or ``(key,)`` of ``(theta0, delta0)`` pairs.
ANGLE_KEYS: tuple[tuple[str, ...], ...] = tuple(
    dict.fromkeys(tuple(e.key_of(a) for a in e.angles) for e in EXPERIMENTS.values() if e.angles)
)
BOUND_KEYS: dict[str, str] = {
    e.key_of(argument): parameter
    for e in EXPERIMENTS.values()
    for argument, parameter in e.bounds.items()
}
#: The paper's result files (the claims read these), by key.  A file is named by the
#: paper's figure, never by a parameter value the config can change (the value is in the
#: file's attributes and the figure's title).
PAPER_RESULTS = {k: e.path for k, e in EXPERIMENTS.items() if e.family == "paper"}
#: The speed-against-accuracy studies' result files, by key.
STUDY_RESULTS = {k: e.path for k, e in EXPERIMENTS.items() if e.family == "study"}
#: The identification's files (config/readings.yaml), by ``{fit set}_{kind}``.
IDENTIFICATION_FILES = {
    f"{fit}_{kind}": f"results/identification/{fit}_{kind}.nc"
    for fit in ("model", "elbow_force")
    for kind in ("fits", "profiles", "loo")
}


#: The robustness analysis' files: the screen of the candidate readings, the kept
#: consistent readings, every claim under each of them (claims x readings), and the
#: targeted evaluation checked against the full maps on some of them.
ROBUSTNESS_FILES = {
    "robustness_screen": "results/robustness/screen.nc",
    "robustness_readings": "results/robustness/readings.nc",
    "robustness": "results/robustness/claims.nc",
}
#: The check of the claims' searches against the maps (tennis_stroke.inference.validation):
#: one job and file per group of the files the claims find by a search (a claim reads
#: the files of one group), by ``validation_{group}``, so a change of one figure's
#: config reruns one of them.
VALIDATION_GROUPS = {
    "angle_maps": ("fig2", "fig3"),
    "mass_length": ("ml",),
    "fig7": ("fig7",),
    "fig8": ("fig8",),
    "fig9": ("fig9",),
    "elbow_map": ("elbow_map",),
}
ROBUSTNESS_FILES |= {
    f"validation_{g}": f"results/robustness/validation/{g}.nc" for g in VALIDATION_GROUPS
}


#: The model ladder claim by claim (tennis_stroke.inference.ladder): every claim under
#: each rung of the config's ``model_ladder``.
LADDER_FILES = {"model_ladder": "results/ladder/claims_by_rung.nc"}


#: The inference's files (identification, robustness, the model ladder), by key.
INFERENCE_RESULTS = {**IDENTIFICATION_FILES, **ROBUSTNESS_FILES, **LADDER_FILES}


RESULT_FILES = {**PAPER_RESULTS, **STUDY_RESULTS, **INFERENCE_RESULTS}
