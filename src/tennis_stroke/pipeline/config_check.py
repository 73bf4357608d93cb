"""Checks of the workflow configuration, each failure one line naming the key and the rule.

:func:`config_errors` applies the JSON schema (``workflow/schemas/config.schema.yaml``),
then what a schema cannot say (a range's ``stop`` below its ``start``, an empty grid, a
search range the wrong way round), then the package's own checks: the model overrides
through :func:`tennis_stroke.model.params.resolve_params` (every parameter's unit and
bounds), the solver section and the work-precision tolerances through
:class:`~tennis_stroke.solver.settings.SolverSettings` (the accuracy bound), the
stability cases and RK4 steps through :func:`tennis_stroke.studies.methods.check_case`
(the methods that exist, the smallest RK4 step), and last the points of every job
(:func:`job_points`) against the declared bound ``max_points_per_job``
(:mod:`tennis_stroke.pipeline.resources`, which also says what each job asks of the
scheduler).  The Snakefile prints the first message and exits before any job starts.
"""

from __future__ import annotations

import copy
import functools
import json
from collections.abc import Iterator, Mapping
from decimal import Decimal
from pathlib import Path

import numpy as np

from ..experiments.grids import bracket_size, chunk_count, grid_size, lands_on_stop
from ..experiments.specs import ANGLE_KEYS, BOUND_KEYS, EXPERIMENTS, Experiment
from ..inference.ladder_plan import LadderError, check_ladder, rung_model, rung_settings
from ..inference.search_plan import BRACKET_KEYS, SEARCHED, search_strokes
from ..io.config_files import (
    ConfigKeyError,
    dotted_key,
    load_yaml,
    non_finite_numbers,
    schema_errors,
    value_at,
    walk,
)
from ..model.params import (
    CHOICES,
    PARAMETERS,
    ParameterError,
    initial_angle,
    initial_angles,
    resolve_params,
)
from ..solver.settings import METHOD_IDS, SolverSettingError, SolverSettings
from ..studies.methods import OPTIMUM_DELTA0_RANGE, OPTIMUM_THETA0_RANGE, check_case
from .resources import DEFAULT_MAX_POINTS


def _semantic_errors(config: Mapping) -> Iterator[str]:
    for parts, node in non_finite_numbers(config):
        yield f"config key {dotted_key(parts)!r}: {node} is not a finite number (rule: finite)"
    for parts, node in walk(config):
        if isinstance(node, Mapping) and {"start", "stop"} <= set(node):
            start, stop = node["start"], node["stop"]
            if isinstance(start, int | float) and isinstance(stop, int | float) and stop < start:
                yield (
                    f"config key {dotted_key(parts)!r}: stop {stop} is below start {start} "
                    "(rule: stop >= start)"
                )
            step = node.get("step")
            numbers = all(isinstance(v, int | float) for v in (start, stop, step))
            if numbers and step > 0 and stop >= start and not lands_on_stop(start, stop, step):
                yield (
                    f"config key {dotted_key(parts)!r}: step {step} does not land on stop {stop} "
                    f"from start {start} (rule: a whole number of steps)"
                )
        if (
            parts
            and str(parts[-1]).endswith("_range")
            and isinstance(node, list)
            and len(node) == 2
            and all(isinstance(v, int | float) for v in node)
            and node[1] <= node[0]
        ):
            yield (
                f"config key {dotted_key(parts)!r}: {node} is empty or reversed "
                "(rule: lower < upper)"
            )
    model = config.get("model") or {}
    for name, value in model.items() if isinstance(model, Mapping) else ():
        if not isinstance(value, int | float | str) or isinstance(value, bool):
            yield (
                f"config key 'model.{name}': a model parameter or reading takes one value, "
                f"got {value!r} (rule: one value)"
            )
            return
    try:
        resolve_params(model)
    except ParameterError as exc:
        yield f"config key 'model': {exc}"
    yield from _bound_errors(config)
    yield from _angle_errors(config)
    yield from _solver_errors(config)
    yield from _ladder_errors(config, model)


def _values(value) -> list:
    """The values of a config value a bound applies to: a range's ends, a list's items."""
    if isinstance(value, Mapping):
        return [value.get("start"), value.get("stop")]
    return list(value) if isinstance(value, list) else [value]


def _bound_errors(config: Mapping) -> Iterator[str]:
    """The values the table's rows put into the model (``Experiment.bounds``) against the
    unit and bounds of their parameter, naming the config key: a value the solver would
    refuse never reaches a job."""
    for key, name in BOUND_KEYS.items():
        try:
            value = value_at(config, key)
        except ConfigKeyError:  # a key the schema gives a default
            continue
        try:
            resolve_params({name: np.asarray(_values(value), dtype=float)})
        except (ParameterError, TypeError, ValueError) as exc:
            yield f"config key {key!r}: {exc} (rule: bounds of {name})"


def _angle_errors(config: Mapping) -> Iterator[str]:
    """The initial angles the table's rows read (``Experiment.angles``) by the rule of
    :data:`~tennis_stroke.model.params.INITIAL_ANGLES`, naming the config keys: each
    angle (a value, a range's ends, a search range, a list's pairs) within its bounds,
    and every theta0 with every delta0 of the row less than a turn before the hit."""
    for keys in ANGLE_KEYS:
        try:
            values = [value_at(config, key) for key in keys]
            if len(keys) == 1:  # (theta0, delta0) pairs
                pairs = np.asarray(values[0], dtype=float).reshape(-1, 2)
                theta0, delta0 = pairs[:, 0], pairs[:, 1]
            else:  # every theta0 with every delta0
                theta0 = np.asarray(_values(values[0]), dtype=float)[:, None]
                delta0 = np.asarray(_values(values[1]), dtype=float)[None, :]
        except (ConfigKeyError, TypeError, ValueError):
            continue  # a key the schema gives a default, or not numbers: the schema's
        named = dict(zip(("theta0", "delta0"), keys, strict=True)) if len(keys) == 2 else {}
        try:
            for name, key in named.items():
                label = f"config key {key!r}"
                initial_angle(name, theta0 if name == "theta0" else delta0)
            label = " and ".join(map(repr, keys))
            label = f"config key{'s' if len(keys) > 1 else ''} {label}"
            initial_angles(theta0, delta0)
        except ParameterError as exc:
            yield f"{label}: {exc} (rule: initial angles)"


def _solver_errors(config: Mapping) -> Iterator[str]:
    """The solver section and the studies' methods and tolerances, checked by the code
    that will run them."""
    try:
        SolverSettings(**(config.get("solver") or {}))
    except SolverSettingError as exc:
        yield f"config key 'solver.{exc.setting}': {exc} (rule: solver settings)"
    study = config.get("solver_study") or {}
    for i, tol in enumerate(study.get("compiled_tolerances") or []):
        try:  # the work-precision study runs SolverSettings(rtol=tol, atol=tol)
            SolverSettings(rtol=tol, atol=tol)
        except SolverSettingError as exc:
            yield (
                f"config key 'solver_study.compiled_tolerances.{i}': {exc} (rule: solver settings)"
            )
    for name, scene in (study.get("scenes") or {}).items():
        yield from _scene_errors(name, scene)
    for i, step in enumerate(study.get("rk4_steps") or []):
        try:
            check_case("fixed.RK4", step)
        except ValueError as exc:
            yield f"config key 'solver_study.rk4_steps.{i}': {exc} (rule: methods)"
    for i, case in enumerate((study.get("stability") or {}).get("cases") or []):
        try:
            check_case(*case)
        except ValueError as exc:
            yield f"config key 'solver_study.stability.cases.{i}': {exc} (rule: methods)"


def _scene_errors(name: str, scene: Mapping) -> Iterator[str]:
    """A work-precision scene's parameters, each value (both ends of a range) checked by
    the model's own bounds; a range's low end at most its high end."""
    key = f"solver_study.scenes.{name}"
    for end in (0, 1):
        values = {}
        for k, v in scene.items():
            if isinstance(v, list):
                if v[0] > v[1]:
                    yield f"config key '{key}.{k}': range {v} has its low end above its high end"
                    return
                v = v[end]
            values[k] = v
        try:
            resolve_params(values)
        except (ParameterError, TypeError, ValueError) as exc:
            yield f"config key {key!r}: {exc} (rule: model parameters)"
            return


def _n(count: int) -> str:
    """A count for a message: exact up to 1e12, else three digits."""
    return str(count) if count < 10**12 else f"{Decimal(count):.3g}"


def rows_per_job(rows: int, requested: int) -> int:
    """Rows of the largest chunk when ``rows`` are split into ``requested`` chunks (the
    readings of the largest robustness job, searched in lockstep)."""
    return -(-rows // chunk_count(requested, rows))


def _requested_chunks(config: Mapping, key: str) -> int:
    """The chunk count at config ``key``; 1 where not given (the schema's default)."""
    try:
        return int(value_at(config, key))
    except ConfigKeyError:
        return 1


def map_jobs(config: Mapping, readings: int = 1) -> Iterator[tuple[str, str, int]]:
    """``(config key, what, points)`` of the workflow's largest jobs, from the sizes alone
    (nothing is allocated): the largest chunk job of every row of the table of
    experiments that runs a batch of strokes, the gathering of each chunked map, the
    sampled curves of the rows that draw them, the first batch of every claim's search
    (``readings`` of them searched in lockstep, the largest robustness job's), and the
    solver studies' searches."""
    yield from _experiment_jobs(config)
    yield from search_jobs(config, readings)
    yield from _study_jobs(config)


def job_points(e: Experiment, config: Mapping) -> tuple[int, str]:
    """The points of the largest job of row ``e`` under ``config`` (the strokes of its
    batches in one chunk, or its curves' samples) and what they are, for a message."""
    args = e.arguments(config)
    if e.samples is not None:
        points = e.samples(args)
        return points, f"the curves of the {e.label} ({_n(points)} stroke-samples)"
    if e.strokes is None:
        return 0, e.label
    batches = e.strokes(args)
    rows = e.row_count(args)
    per_job = rows_per_job(rows, _requested_chunks(config, e.chunks)) if e.chunks else rows
    sizes = [b // rows * per_job for b in batches]
    if len(sizes) == 1:
        return sizes[0], f"a {e.label} job ({_n(per_job)} x {_n(sizes[0] // per_job)} strokes)"
    shown = " + ".join(_n(s) for s in sizes)
    return sum(sizes), f"a {e.label} job ({_n(per_job)} rows, {shown} strokes)"


def _experiment_jobs(config: Mapping) -> Iterator[tuple[str, str, int]]:
    """The jobs of :func:`map_jobs` that the rows of the table of experiments run: the
    sampled curves, the largest chunk job of a batch of strokes, a chunked map's gathering."""
    for e in EXPERIMENTS.values():
        if e.samples is None and e.strokes is None:
            continue
        try:
            points, what = job_points(e, config)
        except ConfigKeyError:  # a key the schema gives a default: checked once it has it
            continue
        if e.samples is not None:
            yield e.key_of("samples" if "samples" in e.args else "stroke.samples"), what, points
            continue
        yield e.section, what, points
        if e.gathered:
            n = e.strokes(e.arguments(config))[0]
            yield e.section, f"gathering the {e.label} ({_n(n)} strokes)", n


def search_jobs(config: Mapping, readings: int) -> Iterator[tuple[str, str, int]]:
    """The first batch of every claim's search of :func:`map_jobs`, ``readings`` of them
    in lockstep."""
    together = max(1, int(readings))
    for key in SEARCHED if "search" in config else ():  # else: checked once defaulted
        e, steps = EXPERIMENTS[key], BRACKET_KEYS[key]
        try:
            n = search_strokes(key, e.arguments(config), config["search"])
        except ConfigKeyError:
            continue
        shown = ", ".join(f"{k} = {value_at(config, k):g}" for k in steps)
        yield (
            steps[0] if len(steps) == 1 else steps[0].partition(".")[0],
            f"the search of the {e.label}'s claims ({shown}: {_n(n)} strokes at once"
            + (f" for each of {together} readings)" if together > 1 else ")"),
            n * together,
        )


def _study_jobs(config: Mapping) -> Iterator[tuple[str, str, int]]:
    """The solver studies' jobs of :func:`map_jobs`: the optimum searches and the
    stability map."""
    study = config["solver_study"]
    opt = study["optimum"]
    th_range, de_range = OPTIMUM_THETA0_RANGE, OPTIMUM_DELTA0_RANGE
    points = len(opt["M2"]) * len(opt["L1"])
    for coarse_step, fine_step in [(1.0, opt["reference_step"]), *opt["steps"]]:
        coarse = grid_size(*th_range, coarse_step) * grid_size(*de_range, coarse_step)
        fine = grid_size(-coarse_step, coarse_step, fine_step) ** 2
        yield (
            "solver_study.optimum",
            f"the optimum search with steps {coarse_step:g}/{fine_step:g} deg "
            f"({_n(points)} points, {_n(coarse)} + {_n(fine)} strokes each)",
            points * max(coarse, fine),
        )
    for bracket, _ in opt.get("searches", []):
        coarse = bracket_size(*th_range, bracket) * bracket_size(*de_range, bracket)
        yield (
            "solver_study.optimum",
            f"the optimum search with a {bracket:g} deg bracket ({_n(points)} points, "
            f"{_n(coarse)} strokes each at once)",
            points * coarse,
        )
    k = study["stability"]["k_contact"]
    cases = len(study["stability"]["cases"])
    yield (
        "solver_study.stability.k_contact",
        f"the stability map ({cases} cases x {_n(k['num'])} spring constants)",
        int(k["num"]) * cases,
    )


def points_errors(config: Mapping, readings: int = 1) -> Iterator[str]:
    """The first job of :func:`map_jobs` with more points than ``max_points_per_job``, as
    a one-line message naming its config key (``readings``: searched in lockstep by the
    largest robustness job)."""
    bound = config.get("max_points_per_job") or DEFAULT_MAX_POINTS
    for key, what, points in map_jobs(config, readings):
        if points > bound:
            yield (
                f"config key {key!r}: {what} holds {_n(points)} points, above "
                f"max_points_per_job = {_n(bound)} (a coarser step, more chunks, or a "
                "larger bound) (rule: points per job)"
            )
            return


def _number(text: str):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def numbers_from_strings(node):
    """``node`` with every string that spells a number turned into that number.

    Snakemake's ``--config key={a: 2}`` reads nested values with YAML's BaseLoader, as
    strings (``'2'``); this restores the numbers the YAML file would have given.  No
    string option of the config spells a number.
    """
    if isinstance(node, Mapping):
        return {key: numbers_from_strings(value) for key, value in node.items()}
    if isinstance(node, list):
        return [numbers_from_strings(value) for value in node]
    return _number(node) if isinstance(node, str) else node


def _ladder_errors(config: Mapping, model: Mapping) -> Iterator[str]:
    """The model ladder's rungs, checked by the code that will run them: names, the
    reference, each rung's model over the config's and its solver settings."""
    ladder = config.get("model_ladder")
    if not ladder:
        return
    try:
        check_ladder(ladder)
    except LadderError as exc:
        yield f"{exc} (rule: unique rungs)"
    for i, rung in enumerate(ladder["rungs"]):
        try:
            rung_settings(config.get("solver") or {}, rung)
            resolve_params(rung_model(model, rung))
        except SolverSettingError as exc:  # a kind of ParameterError: first
            yield (
                f"config key 'model_ladder.rungs.{i}.solver.{exc.setting}': {exc} "
                "(rule: solver settings)"
            )
        except ParameterError as exc:
            yield f"config key 'model_ladder.rungs.{i}': {exc} (rule: a model the solver runs)"


def _resolved(schema: Mapping, root: Mapping) -> Mapping:
    """``schema`` with its local ``$ref`` and ``allOf`` parts merged in (one level each)."""
    out = dict(schema)
    ref = out.pop("$ref", None)
    if ref is not None:
        target = root
        for part in ref.removeprefix("#/").split("/"):
            target = target[part]
        out = {**_resolved(target, root), **out}
    for part in out.pop("allOf", ()):
        out = {**_resolved(part, root), **out}
    return out


def _is_number(schema: Mapping) -> bool:
    kinds = schema.get("type")
    kinds = [kinds] if isinstance(kinds, str) else list(kinds or ())
    return "number" in kinds and "integer" not in kinds


#: Config sections whose keys the schema does not name and whose numbers are all real:
#: the model overrides (every model parameter is a real number; a reading is a string).
REAL_SECTIONS = {("model",)}


def _is_default(name: str, value) -> bool:
    """Whether model ``name`` set to ``value`` is its default: a parameter that is not
    derived (a derived one's default depends on the others), a reading or an option."""
    if name in PARAMETERS and not PARAMETERS[name].derived:
        default = PARAMETERS[name].default
        return isinstance(value, float) and default is not None and value == float(default)
    return name in CHOICES and value == CHOICES[name].default


def canonical(node, schema: Mapping, root: Mapping | None = None, path: tuple = ()):
    """``node`` (a checked config) in one spelling per value, so that equal settings give
    equal job params (Snakemake reruns a job whose params' text changed):

    - an integer where the schema says ``number`` becomes a float (``5`` is ``5.0``;
      YAML's ``1e3`` is already ``1000.0``); booleans stay booleans;
    - a mapping's keys follow the schema's ``properties`` order, then the keys it does not
      name in sorted order;
    - every number of a :data:`REAL_SECTIONS` section is a float;
    - a model parameter, reading or option set to its default is left out (``model: {M2:
      0.3}`` is the model of ``model: {}``: nothing reruns).
    """
    root = schema if root is None else root
    schema = _resolved(schema, root)
    if isinstance(node, Mapping):
        properties = schema.get("properties", {})
        order = [key for key in properties if key in node]
        order += sorted((key for key in node if key not in properties), key=str)
        out = {
            key: canonical(node[key], properties.get(key, {}), root, (*path, key)) for key in order
        }
        if path == ("model",):
            out = {key: value for key, value in out.items() if not _is_default(key, value)}
        return out
    if isinstance(node, list):
        prefix = schema.get("prefixItems", [])
        return [
            canonical(v, prefix[i] if i < len(prefix) else schema.get("items", {}), root, path)
            for i, v in enumerate(node)
        ]
    real = _is_number(schema) or any(path[: len(s)] == s for s in REAL_SECTIONS)
    if real and isinstance(node, int) and not isinstance(node, bool):
        return float(node)
    return node


def with_defaults(node, schema: Mapping, root: Mapping | None = None):
    """``node`` with every key the schema gives a ``default`` filled in where missing, at
    every level (what the workflow's ``validate(..., set_default=True)`` does): a config
    file may leave them out."""
    root = schema if root is None else root
    schema = _resolved(schema, root)
    if not isinstance(node, Mapping):
        return node
    out = dict(node)
    for key, spec in schema.get("properties", {}).items():
        spec = _resolved(spec, root)
        if key not in out and "default" in spec:
            out[key] = copy.deepcopy(spec["default"])
        if key in out:
            out[key] = with_defaults(out[key], spec, root)
    return out


def load_schema(schema_path: str | Path) -> dict:
    """The config schema (``workflow/schemas/config.schema.yaml``) as data (read once per
    process while the file is unchanged: the live explorer checks every setting)."""
    path = Path(schema_path).resolve()
    stat = path.stat()
    return copy.deepcopy(_parsed_schema(path, stat.st_mtime_ns, stat.st_size))


@functools.lru_cache(maxsize=4)
def _parsed_schema(path: Path, mtime_ns: int, size: int) -> dict:
    return with_package_values(load_yaml(path))


def with_package_values(schema: dict) -> dict:
    """``schema`` with what the package owns, which the file does not write again: the
    solver's defaults (``method``, ``rtol``, ``atol``) from
    :class:`~tennis_stroke.solver.settings.SolverSettings` and the methods that exist
    (:data:`~tennis_stroke.solver.settings.METHOD_IDS`), for the solver section and a
    model ladder rung's."""
    default = SolverSettings()
    solver = schema["properties"]["solver"]["properties"]
    for key in ("method", "rtol", "atol"):
        solver[key]["default"] = getattr(default, key)
    rung = schema["properties"]["model_ladder"]["properties"]["rungs"]["items"]
    for spec in (solver["method"], rung["properties"]["solver"]["properties"]["method"]):
        spec["enum"] = list(METHOD_IDS)
    return schema


def config_errors(config: Mapping, schema_path: str | Path, readings: int = 1) -> list[str]:
    """Every problem of ``config`` as one-line messages (empty: the config is good);
    ``readings``: how many readings the largest job searches in lockstep (the bound on
    a job's points, :func:`points_errors`)."""
    schema = load_schema(schema_path)
    errors = schema_errors(config, schema, "config")
    return errors or list(_semantic_errors(config)) or list(points_errors(config, readings))


def _kind(spec: Mapping) -> str:
    """A schema entry's type and bounds in words (``number > 0, <= 60``)."""
    ref = spec.get("$ref") or next((p["$ref"] for p in spec.get("allOf", ()) if "$ref" in p), "")
    kinds = spec.get("type", ref.rpartition("/")[2] or "any")
    words = "|".join(kinds) if isinstance(kinds, list) else kinds
    if "enum" in spec:
        words = " or ".join(map(str, spec["enum"]))
    marks = {"exclusiveMinimum": ">", "minimum": ">=", "exclusiveMaximum": "<", "maximum": "<="}
    bounds = [f"{mark} {spec[key]:g}" for key, mark in marks.items() if key in spec]
    return ", ".join([words, *bounds])


def key_table(schema: Mapping, config: Mapping) -> str:
    """Every key of the config ``schema`` (:func:`load_schema`) as a Markdown table: its
    dotted name, type and bounds, its value in ``config`` (the config file as written)
    or else its default, and its description (``config/README.md``, written by
    ``tennis-stroke config keys``)."""
    rows = [
        KEYS_HEAD,
        "| key | type | value | description |",
        "|---|---|---|---|",
    ]

    def walk_schema(spec: Mapping, path: tuple[str, ...], given) -> None:
        properties = spec.get("properties")
        text = spec.get("description") or _resolved(spec, schema).get("description", "")
        text = " ".join(str(text).split()).replace("|", "\\|")
        if properties and spec.get("type") == "object" and "$ref" not in spec:
            if path:
                rows.append(f"| `{'.'.join(path)}` | section | | {text} |")
            for key, child in properties.items():
                inner = given.get(key, _MISSING) if isinstance(given, Mapping) else _MISSING
                walk_schema(child, (*path, key), inner)
            return
        if given is not _MISSING:
            value = json.dumps(given)
            value = f"`{value}`" if len(value) <= 80 else "(a list: see config.yaml)"
        else:
            value = f"default `{json.dumps(spec['default'])}`" if "default" in spec else ""
        rows.append(f"| `{'.'.join(path)}` | {_kind(spec)} | {value} | {text} |")

    walk_schema(schema, (), config)
    return "\n".join(rows)


_MISSING = object()
#: What config/README.md says before the table.
KEYS_HEAD = """\
# The configuration

This folder is the workflow's configuration, copied whole by `snakedeploy
deploy-workflow` into a workflow that imports this one:

* `config.yaml`: the workflow's keys (below), the paper's values;
* `claims.yaml`: the paper's numbers, each a claim with its tolerance and source;
* `readings.yaml`: the readings of the paper's unstated assumptions, their fit sets and
  the robustness analysis;
* `scenarios.yaml`: declared what-if scenarios (docs/scenarios.md).

Every key of `config.yaml`, from the schema `workflow/schemas/config.schema.yaml`
(`tennis-stroke config keys` writes this page; a test keeps it current; what each key
drives: docs/config_keys.md). A value the schema or the package refuses stops the run
before any job, in one line naming the key.
"""
