"""What-if scenarios: named sets of overrides of the paper's configuration, run beside it.

The paper's configuration (``config/config.yaml``) is what the replication is graded on.
A scenario is a name and overrides in the shape of that file
(``heavy_racket: {model: {M2: 0.35}}``), declared in ``config/scenarios.yaml`` or given on
the command line (``--config 'scenarios={NAME: {...}}'``, or ``tennis-stroke whatif``).
Its files mirror the paper's under ``results/scenarios/<name>/`` and its page is
``report/scenarios/<name>/index.html``; the same rules make them.  A scenario reads the
paper's file wherever its overrides change nothing the file's job reads
(:func:`resolved_results`), so it computes what it changes and nothing else, and it never
writes a paper file.

Checked before any job, each failure one line naming the scenario: the name, the shape,
every override against the config's schema and bounds (the config with the overrides is
checked as the paper's is), and no override of a section only the paper's configuration
runs (:data:`PAPER_ONLY`).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
from collections.abc import Collection, Iterator, Mapping
from pathlib import Path

import yaml

from ..experiments.specs import BOUND_KEYS, EXPERIMENTS, PAPER_RESULTS, merged, shown, sorted_data
from ..io.config_files import ConfigFileError, did_you_mean, load_yaml
from ..io.netcdf import read_only, temporary_beside
from ..model.listing import origin
from ..model.params import CHOICES, PARAMETERS
from .config_check import (
    canonical,
    config_errors,
    load_schema,
    numbers_from_strings,
    with_defaults,
)
from .params import changed_results, reads

#: A scenario's name: a folder name on every system, and a Snakemake wildcard value.
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,63}")
#: Snakemake refuses a wildcard value that ends in one substring repeated 20 times or more
#: (its PeriodicWildcardError, taken for an infinite recursion): such a name is refused.
PERIODIC = re.compile(r"(.+?)\1{19,}$")
#: The folder of the scenarios' result files and pages, below ``results/`` and ``report/``.
FOLDER = "scenarios"
#: Config sections a scenario may not override: what runs only in the paper's
#: configuration (the speed-against-accuracy studies, the model ladder).
PAPER_ONLY = {
    "solver_study": "the speed-against-accuracy studies run in the paper's configuration only",
    "model_ladder": "the model ladder runs in the paper's configuration only",
}


class ScenarioError(ValueError):
    """A scenario that cannot run as declared (one line)."""


def changes(base: Mapping, other: Mapping, prefix: str = "") -> list[tuple[str, object, object]]:
    """Every dotted config key whose value differs between ``base`` and ``other``, with
    both values (a list or a value missing on one side compares whole), in key order."""
    out = []
    for key in sorted(set(base) | set(other), key=str):
        a, b = base.get(key), other.get(key)
        path = f"{prefix}{key}"
        if isinstance(a, Mapping) and isinstance(b, Mapping):
            out.extend(changes(a, b, f"{path}."))
        elif sorted_data(a) != sorted_data(b):
            out.append((path, sorted_data(a), sorted_data(b)))
    return out


def _shape_errors(name: object, overrides: object) -> list[str]:
    if not isinstance(name, str) or not NAME.fullmatch(name):
        return [
            f"scenario name {name!r}: a letter, then letters, digits, '_' or '-' "
            "(at most 64; it names a folder)"
        ]
    periodic = PERIODIC.search(name)
    if periodic:
        repeated = len(periodic.group(0)) // len(periodic.group(1))
        return [
            f"scenario name {name!r}: it ends in {periodic.group(1)!r} repeated {repeated} "
            "times, which Snakemake refuses in a file name (it takes it for an endless "
            "recursion); at most 19 repeats"
        ]
    if overrides is None:
        return []
    if not isinstance(overrides, Mapping):
        return [
            f"scenario {name!r}: overrides must be a mapping in the shape of "
            f"config/config.yaml, got {overrides!r}"
        ]
    for section in overrides:
        if section in PAPER_ONLY:
            return [f"scenario {name!r}: may not override {section!r} ({PAPER_ONLY[section]})"]
        if section == "scenarios":
            return [f"scenario {name!r}: a scenario may not declare scenarios"]
    return []


def scenario_config(
    base: Mapping, name: str, overrides: Mapping | None, schema: str | Path
) -> dict:
    """The configuration of scenario ``name``: ``base`` (the paper's, validated) with its
    ``overrides``, checked as the paper's is.  Raises :class:`ScenarioError`."""
    errors = _shape_errors(name, overrides)
    if errors:
        raise ScenarioError(errors[0])
    config = merged(base, numbers_from_strings(dict(overrides or {})))
    errors = config_errors(config, schema)
    if errors:
        raise ScenarioError(f"scenario {name!r}: {errors[0]}")
    return canonical(config, load_schema(schema))


def changing_config(
    base: Mapping, name: str, overrides: Mapping | None, schema: str | Path
) -> dict:
    """:func:`scenario_config`, refusing a scenario that changes nothing of ``base``
    (every override the value ``base`` has, a model value's default, or none: ``NAME:
    {}``): its page would be the paper's under another name.  The one check of a
    declared scenario at planning (:class:`~tennis_stroke.pipeline.runs.Runs`), of the
    explorer's Save (:func:`save_scenario`) and of ``tennis-stroke whatif``
    (:func:`scenario_reach`).  Raises :class:`ScenarioError`."""
    config = scenario_config(base, name, overrides, schema)
    loaded = load_schema(schema)
    if not changes(_complete(base, loaded), _complete(config, loaded)):
        raise ScenarioError(
            f"scenario {name!r} changes nothing of the paper's configuration (each "
            "override is the value it has, or a model value's default)"
        )
    return config


def _complete(config: Mapping, schema: Mapping) -> dict:
    """``config`` with the schema's defaults, in one spelling per value: two configs
    that run the same jobs compare equal."""
    return canonical(with_defaults(config, schema), schema)


def load_scenarios(
    path: str | Path, extra: Mapping | None = None, errors: dict | None = None
) -> dict[str, dict]:
    """The declared scenarios of ``path`` (``config/scenarios.yaml``; an empty or missing
    file: none), and ``extra`` ones (given on the command line) replacing any of the same
    name, by name.  Only their shape is checked here (:func:`scenario_config` checks the
    values).  A scenario of a bad name or shape raises :class:`ScenarioError`, or, given
    ``errors``, is left out with its one-line error there by name: one bad scenario
    then stops only itself.  A file that is not a mapping always raises."""
    raw = None
    if Path(path).is_file():
        try:
            raw = load_yaml(path)
        except ConfigFileError as exc:
            raise ScenarioError(str(exc)) from None
    if raw is None:
        raw = {}
    if not isinstance(raw, Mapping):
        raise ScenarioError(
            f"{path}: must map each scenario's name to its overrides, got {type(raw).__name__}"
        )
    if extra is not None and not isinstance(extra, Mapping):
        raise ScenarioError(
            f"--config scenarios: must map each scenario's name to its overrides, got {extra!r}"
        )
    out = {}
    for name, overrides in {**raw, **(extra or {})}.items():
        problems = _shape_errors(name, overrides)
        if problems and errors is None:
            raise ScenarioError(problems[0])
        if problems:
            errors[name] = problems[0]
        else:
            out[name] = sorted_data(overrides or {})
    return out


def override_from(items, top_level: Collection[str] | None = None) -> dict:
    """Overrides from ``KEY=VALUE`` items (the command line): a model parameter, reading
    or model option by its name (``M2=0.35``: ``model.M2``), any other config key dotted
    (``torque_delay.base_stroke.C2=8``); a value is read as YAML (a number, a list).
    With ``top_level`` (the config's top-level keys), a bare name that is none of them
    is refused with the closest names."""
    out: dict = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key or not text:
            raise ScenarioError(f"--set {item!r}: expected KEY=VALUE")
        named = key in PARAMETERS or key in CHOICES
        unknown = _unknown_name(key, top_level) if top_level is not None else ""
        if unknown:
            raise ScenarioError(f"--set {item!r}: {unknown}")
        try:
            value = yaml.safe_load(text)
        except yaml.YAMLError:
            raise ScenarioError(f"--set {item!r}: {text!r} is not a value") from None
        parts = ["model", key] if named else key.split(".")
        node = out
        for part in parts[:-1]:
            node = node.setdefault(part, {})
            if not isinstance(node, dict):
                raise ScenarioError(f"--set {item!r}: {part!r} is already set to a value")
        node[parts[-1]] = value
    return out


def _unknown_name(key: str, top_level: Collection[str]) -> str:
    """Why the ``--set`` key ``key`` names nothing (``""``: it may name something): a
    bare name must be a model parameter, reading or option or a top-level config key,
    ``model.NAME`` one of the first; a deeper key is the schema's to check."""
    models = [*PARAMETERS, *CHOICES]
    section, _, name = key.partition(".")
    if not name and key not in models and key not in top_level:
        hint = did_you_mean(key, [*models, *top_level])
        return f"{key!r} is no model parameter, reading or option, nor a top-level config key{hint}"
    if section == "model" and name and name not in models:
        return f"{name!r} is no model parameter, reading or option{did_you_mean(name, models)}"
    return ""


def folder(name: str, top: str = "results") -> str:
    """The folder of scenario ``name``'s files below ``top`` (``results`` or ``report``)."""
    return f"{top}/{FOLDER}/{name}"


def scenario_path(path: str, name: str) -> str:
    """The scenario's counterpart of a paper file ``path`` (``results/...`` or
    ``report/...``): the same relative path below the scenario's folder."""
    top, _, rest = path.partition("/")
    return f"{folder(name, top)}/{rest}"


def resolved_results(base: Mapping, config: Mapping, name: str) -> dict[str, str]:
    """The paper's result files as scenario ``name`` (configuration ``config``) reads
    them, by key: its own file where its overrides change what the file's job reads, the
    paper's file elsewhere (the same values: the same job)."""
    changed = set(changed_results(base, config))
    return {
        key: scenario_path(path, name) if key in changed else path
        for key, path in PAPER_RESULTS.items()
    }


def changes_read(files, base: Mapping, config: Mapping) -> list[tuple[str, object, object]]:
    """The changes from ``base`` to ``config`` (:func:`changes`) that the jobs of the
    paper's result files ``files`` (keys of :data:`PAPER_RESULTS`) read."""
    return [c for c in changes(base, config) if any(reads(EXPERIMENTS[key], c[0]) for key in files)]


def unreached(base: Mapping, config: Mapping, files=None) -> list[str]:
    """One line per model override of ``config`` against ``base`` that rows of the paper
    (of ``files``, keys of the paper's results; default all) set themselves
    (``Experiment.sets``): what it does not reach and the key each reads instead
    (``model.C2 does not reach the Fig. 9 map (it reads torque_delay.base_stroke.C2)``)."""
    files = PAPER_RESULTS if files is None else files
    out = []
    for key, _, _ in changes(base, config):
        section, _, name = key.partition(".")
        if section != "model":
            continue
        rows = [e for k, e in EXPERIMENTS.items() if k in files and name in e.sets]
        if rows:
            shown = ", ".join(f"the {e.label} (it reads {e.reads_instead(name)})" for e in rows)
            out.append(f"{key} does not reach {shown}")
    return out


#: The workflow config and its schema, relative to a project's folder.
CONFIG_FILE, SCHEMA_FILE = "config/config.yaml", "workflow/schemas/config.schema.yaml"
#: The declared scenarios, relative to a project's folder.
SCENARIOS_FILE = "config/scenarios.yaml"


def scenario_reach(
    name: str, overrides: Mapping | None, figures=(), root: str | Path = "."
) -> list[str]:
    """Check scenario ``name`` (``overrides`` of the project at ``root``) as the workflow
    will, and what it reaches: raises :class:`ScenarioError` (one line) for a value the
    workflow refuses, or for a figure of ``figures`` (registry names) that nothing of
    them reaches; returns what of it does not reach them, the lines the workflow says
    at planning (:func:`unreached`; of ``figures``' files where given)."""
    from ..replication.registry import FIGURES

    base, config = _configurations(name, overrides, Path(root))
    moved = set(changed_results(base, config))
    for figure in figures:
        if not moved & set(FIGURES[figure].files):
            why = "; ".join(unreached(base, config, FIGURES[figure].files))
            why = why or "no job of its files reads what it changes"
            raise ScenarioError(f"scenario {name!r} does not change {figure}: {why}")
    if figures:  # what matters to the figures asked for
        return unreached(base, config, {k for f in figures for k in FIGURES[f].files})
    return unreached(base, config)


def scenario_results(
    name: str, overrides: Mapping | None, root: str | Path = "."
) -> dict[str, str]:
    """The result files scenario ``name`` (``overrides`` of the project at ``root``) reads,
    by key, as its jobs read them (:func:`resolved_results`); raises
    :class:`ScenarioError` (one line) where the workflow would refuse it."""
    return resolved_results(*_configurations(name, overrides, Path(root)), name)


def _configurations(name: str, overrides: Mapping | None, root: Path) -> tuple[dict, dict]:
    """The paper's configuration of the project at ``root`` as the workflow reads it (with
    the schema's defaults) and scenario ``name``'s (:func:`changing_config`)."""
    schema = root / SCHEMA_FILE
    try:
        loaded = load_schema(schema)
        base = canonical(with_defaults(load_yaml(root / CONFIG_FILE), loaded), loaded)
    except ConfigFileError as exc:
        raise ScenarioError(str(exc)) from None
    return base, changing_config(base, name, overrides, schema)


def describe(key: str, old, new, fitted: Collection[str], stated: Collection[str]) -> str:
    """One override for a title or a banner: ``key = new (paper: old)``, the word before
    the old value saying where it comes from.  A model parameter, reading or model
    option the paper's configuration leaves at its default is shown with that default,
    its unit (:data:`~tennis_stroke.model.params.PARAMETERS`) and its origin
    (:func:`~tennis_stroke.model.listing.origin`: ``paper``, ``fitted``, ``derived`` or
    ``ours``; ``fitted``: the names whose default a fit set chose,
    :meth:`~tennis_stroke.inference.reading_space.ReadingSpace.fitted`), the words of
    ``tennis-stroke params``, the report and the explorer.  Any other key is ``paper``
    where it is (or lies in) one of the paper's stated inputs ``stated``
    (``config/claims.yaml``, :func:`~tennis_stroke.inference.paper_config.load_paper_inputs`),
    else ``config``: a value of config.yaml the paper does not state (a grid, a step)."""
    unit = ""
    section, _, name = key.partition(".")
    word = "paper" if any(key == k or key.startswith(f"{k}.") for k in stated) else "config"
    if section == "model" and name in PARAMETERS:
        spec = PARAMETERS[name]
        if old is None or old == spec.default:
            old, word = spec.default, origin(name, fitted)
        new = spec.default if new is None else new  # set back to its default
        unit = "" if spec.unit == "1" else f" {spec.unit}"
    elif section == "model" and name in CHOICES:
        if old in (None, CHOICES[name].default):
            old, word = CHOICES[name].default, origin(name, fitted)
        new = CHOICES[name].default if new is None else new
    elif key in BOUND_KEYS:  # a value a row puts into the model: its parameter's unit
        spec = PARAMETERS[BOUND_KEYS[key]]
        unit = "" if spec.unit == "1" else f" {spec.unit}"
    return f"{key} = {_shown(new)}{unit} ({word}: {_shown(old)}{unit})"


def _shown(value) -> str:
    return "default" if value is None else shown(value)


def save_scenario(
    path: str | Path, name: str, overrides: Mapping, base: Mapping, schema: str | Path
) -> Path:
    """Declare scenario ``name`` with ``overrides`` at the end of ``path``
    (``config/scenarios.yaml``; its comments kept), after checking it as a declared one
    is (:func:`changing_config`: one that changes nothing is refused); a name already
    declared is refused.  Returns the path.

    Safe against what a saver meets: the file is read again under a lock (two savers of
    one name: the second is refused), the new text is read back before it replaces the
    old (a layout that an appended block would break, a flow-style mapping or a document
    end ``...``, is refused and the file kept), a read-only file or one that is not a
    regular file is refused, a symbolic link stays a link to the file it names, and the
    file keeps its mode; a file or folder the system will not write (immutable,
    append-only, a full disk) is refused.  Every refusal is one line
    (:class:`ScenarioError`)."""
    path = Path(path)
    changing_config(base, name, overrides, schema)
    target = path.resolve() if path.is_symlink() else path
    if target.exists() and not target.is_file():
        raise ScenarioError(f"{path}: not a regular file: not saved")
    if target.exists() and read_only(target):
        raise ScenarioError(f"{path}: read-only: not saved (make it writable to save)")
    block = yaml.safe_dump(
        {name: sorted_data(dict(overrides))}, default_flow_style=None, sort_keys=True
    )
    try:
        with _locked(target):  # one saver at a time; the next reads its result
            declared = load_scenarios(target)
            if name in declared:
                raise ScenarioError(
                    f"scenario {name!r} is already declared in {path}: pick another name"
                )
            text = target.read_text() if target.is_file() else ""
            separator = "" if not text or text.endswith("\n") else "\n"
            temporary = temporary_beside(target)  # its mode (_locked made it if new)
            try:
                temporary.write_text(f"{text}{separator}{block}")
                try:
                    again = load_scenarios(temporary)
                except ScenarioError:
                    again = None
                if again != {**declared, name: sorted_data(dict(overrides))}:
                    raise ScenarioError(
                        f"{path}: a scenario appended to it would not read back (a flow-style "
                        "mapping, a document end '...'?): not saved; add it by hand"
                    )
                os.replace(temporary, target)  # whole or not at all
            finally:
                temporary.unlink(missing_ok=True)
    except OSError as exc:  # a folder or file the system keeps: immutable, append-only, full
        raise ScenarioError(
            f"{path}: cannot be written ({exc.strerror or exc}): not saved"
        ) from None
    return path


@contextlib.contextmanager
def _locked(path: Path) -> Iterator[None]:
    """Hold an exclusive lock on the file ``path`` (made empty if missing) as it is now:
    a saver that waited on a file another saver has since replaced locks the new one."""
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)  # the umask applies
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            if os.fstat(fd).st_ino == os.stat(path).st_ino:
                yield
                return
        finally:
            os.close(fd)
