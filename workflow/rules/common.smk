# Config validation and helpers shared by all rules.
from pathlib import Path

import os
import re
import sys
from collections import namedtuple
from dataclasses import asdict
from functools import cache
from operator import itemgetter

from snakemake.utils import validate

from tennis_stroke._imports import PACKAGE as INSTALLED
from tennis_stroke._imports import closure
from tennis_stroke.experiments.grids import chunk_count
from tennis_stroke.experiments.specs import (
    IDENTIFICATION_FILES,
    INFERENCE_RESULTS,
    PAPER_RESULTS,
    RESULT_FILES,
    STUDY_RESULTS,
    EXPERIMENTS,
    VALIDATION_GROUPS,
    fit_set_arguments,
    sorted_data,
    value_at,
)
from tennis_stroke.inference.claims import claim_errors, load_claims
from tennis_stroke.inference.reading_space import ReadingSpaceError, load_reading_space
from tennis_stroke.inference.paper_config import PaperConfigError, load_paper_inputs
from tennis_stroke.pipeline.config_check import (
    canonical,
    config_errors,
    load_schema,
    numbers_from_strings,
    rows_per_job,
)
from tennis_stroke.io.interrupts import PARENT_ENV, process_identity
from tennis_stroke.pipeline import params as job_params
from tennis_stroke.pipeline.checkout import (
    installed_difference,
    runs_no_code,
    shell_safe,
)
from tennis_stroke.pipeline.scenarios import (
    FOLDER as SCENARIO_FOLDER,
    ScenarioError,
    changes,
    changes_read,
    describe,
    folder as scenario_folder,
    load_scenarios,
    resolved_results,
    scenario_config,
    unreached,
)
from tennis_stroke.pipeline.targets import damaged_results, targets
from tennis_stroke.replication.marks import mark_values
from tennis_stroke.replication.registry import FIGURES

# Nested --config values arrive as strings: numbers again, as from the YAML file.
config.update(numbers_from_strings(config))
# Scenarios given on the command line (--config 'scenarios={NAME: {...}}') are not part
# of the paper's configuration: taken out before it is checked.
_ADHOC_SCENARIOS = config.pop("scenarios", None)
# The claims (config/claims.yaml), checked before any job: ids, result files,
# measurements and their arguments, tolerances (else they fail after every simulation).
_errors = claim_errors("config/claims.yaml")
if _errors:
    sys.stderr.write(f"tennis-stroke claims error: {_errors[0]}\n")
    sys.exit(1)
# The reading space (config/readings.yaml), checked before any job, with the claims its
# fit sets name: the robustness analysis' chunks are planned from it.
try:
    READING_SPACE = load_reading_space(
        "config/readings.yaml", [c["id"] for c in load_claims("config/claims.yaml")]
    )
except ReadingSpaceError as _exc:
    sys.stderr.write(f"tennis-stroke readings error: {_exc}\n")
    sys.exit(1)
# One line naming the key and the rule it breaks, before any job starts (no traceback);
# the memory a job needs counts the readings the largest robustness job searches in
# lockstep.
SCHEMA = Path(workflow.basedir) / "workflow/schemas/config.schema.yaml"
_multiverse = READING_SPACE.raw["multiverse"]
_errors = config_errors(
    config, SCHEMA, rows_per_job(_multiverse["readings"], _multiverse["chunks"])
)
if _errors:
    sys.stderr.write(f"tennis-stroke config error: {_errors[0]}\n")
    sys.exit(1)
validate(config, "../schemas/config.schema.yaml", set_default=True)
# One spelling per value (C2: 5 is 5.0, keys in the schema's order): equal settings, equal
# job params, no rerun.
_canonical = canonical(config, load_schema(SCHEMA))
config.clear()
config.update(_canonical)
# The model parameters and readings whose default a fit set chose: a scenario's overrides
# call their default "fitted", as `tennis-stroke params` does.
FITTED = READING_SPACE.fitted()
# The config keys the paper states (config/claims.yaml's inputs): a scenario's change of
# any other key names its old value config.yaml's, not the paper's.
try:
    STATED = [item["key"] for item in load_paper_inputs("config/claims.yaml")]
except PaperConfigError as _exc:
    sys.stderr.write(f"tennis-stroke claims error: {_exc}\n")
    sys.exit(1)
# The what-if scenarios (config/scenarios.yaml and --config scenarios=...), each checked
# as the paper's configuration is, before any job: their configurations by name.  A bad
# scenario never stops the paper's run: it is named in one warning line, and asking for
# any of its files is refused in one line (rule unknown_scenario).
SCENARIO_ERRORS = {}
try:
    SCENARIOS = load_scenarios(
        "config/scenarios.yaml", _ADHOC_SCENARIOS, SCENARIO_ERRORS
    )
except ScenarioError as _exc:
    SCENARIOS, SCENARIO_ERRORS[None] = {}, str(_exc)
SCENARIO_CONFIGS = {}
for _name, _overrides in SCENARIOS.items():
    try:
        SCENARIO_CONFIGS[_name] = scenario_config(config, _name, _overrides, SCHEMA)
    except ScenarioError as _exc:
        SCENARIO_ERRORS[_name] = str(_exc)
for _error in SCENARIO_ERRORS.values():
    sys.stderr.write(
        f"tennis-stroke scenario warning: {_error} (the paper's runs go on)\n"
    )

# A damaged result file (truncated, garbage) is named before any job: Snakemake would take
# it for up to date, and every job reading it would fail.
_damaged = damaged_results()
for _path, _problem in _damaged:
    if _path.startswith(f"results/{SCENARIO_FOLDER}/"):
        # a scenario's file never stops the paper's run
        sys.stderr.write(
            f"tennis-stroke results warning: {_path} is damaged ({_problem}): remove it; "
            "asking for its scenario's files again rebuilds it\n"
        )
_damaged = [d for d in _damaged if not d[0].startswith(f"results/{SCENARIO_FOLDER}/")]
if _damaged:
    _path, _problem = _damaged[0]
    sys.stderr.write(
        f"tennis-stroke results error: {_path} is damaged ({_problem}): remove it and make "
        f"it with: snakemake -j2 {_path}\n"
    )
    sys.exit(1)

#: The workflow's scripts: each rule's code inputs are the package modules its job
#: imports (tennis_stroke._imports), so an edit reruns exactly the jobs that run it
#: (Snakemake does not see code changes in an imported package).
SCRIPTS = Path(workflow.basedir) / "workflow" / "scripts"
PACKAGE_DIR = Path(workflow.basedir) / "src" / "tennis_stroke"
# The jobs must run the checkout's code: an installed copy that differs would run stale
# code while the reruns follow the checkout's edits.  Refused when jobs would run; a dry
# run (or --touch) runs no code and only warns.
_differs = installed_difference(INSTALLED, PACKAGE_DIR)
if _differs is not None:
    _line = (
        f"the jobs would import the tennis_stroke installed at {str(INSTALLED)!r}, whose "
        f"{_differs} differs from this checkout's: install the checkout editable (make "
        "install, or pip install -e .)"
    )
    if not runs_no_code(sys.argv[1:]):
        sys.stderr.write(f"tennis-stroke error: {_line}\n")
        sys.exit(1)
    sys.stderr.write(f"tennis-stroke warning: {_line}\n")
# Snakemake runs a script job as `{sys.executable} {script}` without quoting the
# interpreter's path: quoted here, a checkout under a folder with a space runs
# (tennis_stroke.pipeline.checkout; docs/workflow.md).
sys.executable = shell_safe(sys.executable)
# Each job stops when this Snakemake process ends (killed, say) instead of computing on
# and writing after it (tennis_stroke.io.interrupts.stop_with_snakemake).
os.environ[PARENT_ENV] = process_identity(os.getpid())
#: The table of experiments: a simulation job gets its row as params (function, flags,
#: config values), so editing another row reruns nothing of it.
TABLE = PACKAGE_DIR / "experiments" / "specs.py"
#: The one table of units and long names: a code input only of the jobs that write its
#: labels into their files, the table's unchunked rows and gather_map (the chunks of a
#: map leave the labels to it: tennis_stroke.io.netcdf.relabelled), so editing a long
#: name reruns no chunk of a map and no inference job (their files carry none of its
#: labels: tests/inference/test_labels.py).
UNITS = PACKAGE_DIR / "io" / "units.py"
#: The modules of the paper experiments' functions (the robustness analysis runs them).
PAPER_MODULES = sorted(
    {e.function.split(":")[0] for e in EXPERIMENTS.values() if e.family == "paper"}
)


def checkout_path(path):
    """A file of the checkout (the Snakefile's folder) as an input path relative to the
    working directory.  Snakemake records input paths: relative ones stay the same when
    the checkout and its working directory move together, so a moved or copied checkout
    reruns nothing (``workflow.source_path`` records the absolute path)."""
    return os.path.relpath(path, os.getcwd())


def code_inputs(script, *modules, labels=False, leave_out=()):
    """The package modules a job of ``script`` (in workflow/scripts) runs: those the
    script imports and ``modules`` (dotted, below the package) import, directly or
    through others, as sorted paths relative to the working directory; less
    ``leave_out`` (paths), and less the units table unless the job writes its
    ``labels``."""
    paths = closure(files=[SCRIPTS / script], modules=modules)
    # the same modules in this checkout (a moved or copied checkout reruns nothing)
    paths = {PACKAGE_DIR / p.relative_to(INSTALLED) for p in paths}
    paths -= {*leave_out, *([] if labels else [UNITS])}
    return sorted(checkout_path(p) for p in paths)


def simulation_code(experiment):
    """The code inputs of an experiment's jobs: the generic script and the module of the
    row's function, less the table (the row is in the params) and, for a chunk of a map,
    the units table (gather_map labels the map)."""
    name = experiment.function.split(":")[0]
    return code_inputs(
        "simulate.py", name, labels=not experiment.chunks, leave_out=[TABLE]
    )


def scenario_value(function):
    """A params function: ``function`` of the job's scenario's configuration."""

    def value(wildcards):
        return function(SCENARIO_CONFIGS[wildcards.scenario])

    return value


def row_code(wildcards):
    """The code inputs of a row's job (:func:`simulation_code`)."""
    return simulation_code(ROWS[wildcards.stem])


def row_param(key):
    """A params function: ``key`` of the row's params in its run's configuration
    (tennis_stroke.pipeline.params.simulation_params; None where the row has no such
    key: a row without the model has no ``common``)."""

    def value(wildcards):
        return job_params.simulation_params(ROWS[wildcards.stem], configuration(wildcards)).get(
            key
        )

    return value


wildcard_constraints:
    chunk=r"\d+",
    chunks=r"\d+",


#: Maps computed in chunks (paths under results/, without .nc) and gathered by rule
#: gather_map: the table's chunked rows and the robustness analysis.
CHUNKED = {e.stem: e for e in EXPERIMENTS.values() if e.chunks}
CHUNKED_MAPS = "|".join(re.escape(stem) for stem in [*CHUNKED, "robustness/claims"])


def scenario_name(wildcards):
    """The scenario of a job: its ``scenario`` wildcard, or the name in its ``run``
    wildcard (``scenarios/NAME/``); None for the paper's configuration."""
    if "scenario" in wildcards.keys():
        return wildcards.scenario
    run = wildcards.get("run") or ""
    return run.split("/")[1] if run else None


def configuration(wildcards):
    """The configuration of a job: its scenario's, else the paper's."""
    name = scenario_name(wildcards)
    return config if name is None else SCENARIO_CONFIGS[name]


def results_folder(wildcards):
    """The folder of a job's result files: ``results``, or its scenario's."""
    name = scenario_name(wildcards)
    return "results" if name is None else scenario_folder(name)


def map_rows(name, configuration=config):
    """Requested chunks and number of rows of the first axis of map ``name``
    (CHUNKED_MAPS) in a ``configuration``; the robustness analysis' from
    config/readings.yaml (its rows: at most the declared number of readings)."""
    if name == "robustness/claims":
        spec = READING_SPACE.raw["multiverse"]
        return spec["chunks"], spec["readings"]
    experiment = CHUNKED[name]
    requested = value_at(configuration, experiment.chunks)
    return requested, experiment.row_count(experiment.arguments(configuration))


def chunk_files(wildcards):
    """The chunk files of a map: the requested chunk count, at most one per row."""
    n = chunk_count(*map_rows(wildcards.map, configuration(wildcards)))
    folder = results_folder(wildcards)
    return [f"{folder}/chunks/{wildcards.map}/{i}-of-{n}.nc" for i in range(n)]


def common_params():
    """Params every model simulation needs (the paper's configuration)."""
    return job_params.common_params(config)


def paper_experiments():
    """What the targeted evaluation of the claims reads (the paper's configuration)."""
    return job_params.paper_experiments(config)


#: The table's rows by the stem of their file (the ``stem`` wildcard).
ROWS = {e.stem: e for e in EXPERIMENTS.values()}


def stems(chunked, family=None):
    """A regex of the stems of the rows computed in chunks or not, of one family or all."""
    return "|".join(
        re.escape(e.stem)
        for e in EXPERIMENTS.values()
        if bool(e.chunks) == chunked and family in (None, e.family)
    )


#: The paper experiments' maps gathered from chunks in a scenario.
SCENARIO_MAPS = "|".join(
    re.escape(stem) for stem, e in CHUNKED.items() if e.family == "paper"
)


#: A declared scenario's name (none: nothing).
DECLARED_SCENARIO = "|".join(re.escape(name) for name in SCENARIO_CONFIGS) or "(?!x)x"
#: A name no scenario declares (the rule unknown_scenario refuses it in one line).
UNKNOWN_SCENARIO = f"(?!(?:{DECLARED_SCENARIO})/)[^/]+"


def refuse_unknown_scenario(wildcards):
    """The input function of rule unknown_scenario: one line, then exit status 1."""
    error = SCENARIO_ERRORS.get(wildcards.unknown, SCENARIO_ERRORS.get(None))
    if error:
        sys.stderr.write(f"tennis-stroke scenario error: {error}\n")
        sys.exit(1)
    known = ", ".join(sorted(SCENARIO_CONFIGS)) or "none"
    sys.stderr.write(
        f"tennis-stroke scenario error: no scenario {wildcards.unknown!r} is declared "
        f"(declared: {known}; config/scenarios.yaml, or --config "
        f"'scenarios={{{wildcards.unknown}: {{...}}}}')\n"
    )
    sys.exit(1)


# A scenario wildcard matches a declared scenario's name only (none: nothing); a run is
# the paper's (empty: its files under results/) or a declared scenario's
# (scenarios/NAME/: under results/scenarios/NAME/).
wildcard_constraints:
    scenario=DECLARED_SCENARIO,
    run=f"({SCENARIO_FOLDER}/({DECLARED_SCENARIO})/)?",


def template_files(page):
    """A page's template and the style sheet it includes: code of its job too (not
    modules: no import edge)."""
    folder = PACKAGE_DIR / "replication" / "templates"
    return [checkout_path(folder / page), checkout_path(folder / "style.css")]


def figure_inputs(wildcards):
    """The result files a figure is drawn from: the registry's for the paper's; for a
    scenario's, its own where it changes them and the paper's elsewhere (and, once, what
    of the scenario does not reach them)."""
    name = scenario_name(wildcards)
    if name is None:
        return FIGURES[wildcards.name].inputs
    say_unreached(name, FIGURES[wildcards.name].files)
    files = scenario_files(name)
    return [files[key] for key in FIGURES[wildcards.name].files]


#: The registry of figures: not a code input of the figure jobs, each of which gets its
#: entry as a param (figure_entry).
REGISTRY = PACKAGE_DIR / "replication" / "registry.py"


@cache
def drawing_code(draw):
    """The code inputs of a figure job: the figure script's imports and the figure's own
    drawing module (figures.py imports it by name, so only that drawing's edit reruns the
    figure), less the registry."""
    return code_inputs("figure.py", f"replication.drawing.{draw}", leave_out=[REGISTRY])


def figure_code(wildcards):
    """The code inputs of the job of figure ``name`` (:func:`drawing_code`)."""
    return drawing_code(FIGURES[wildcards.name].draw)


def paper_figure_inputs(wildcards):
    """The paper's result files a figure is drawn from (a scenario's comparison)."""
    return [PAPER_RESULTS[key] for key in FIGURES[wildcards.name].files]


def comparison_code(wildcards):
    """The code inputs of a scenario's comparison of figure ``name``: the comparison
    script's imports and the figure's drawing module, less the registry."""
    return code_inputs(
        "compare.py",
        f"replication.drawing.{FIGURES[wildcards.name].draw}",
        leave_out=[REGISTRY],
    )


def figure_entry(wildcards):
    """A figure's registry entry as plain data (a param: editing one entry reruns its
    figure only)."""
    return sorted_data(asdict(FIGURES[wildcards.name]))


#: The declared claims by id (config/claims.yaml, checked above).
DECLARED_CLAIMS = {c["id"]: c for c in load_claims("config/claims.yaml")}


def figure_marks(wildcards):
    """The paper's values of the claims a figure marks (a param: editing one of them in
    config/claims.yaml reruns the figures that draw it, and no other)."""
    return sorted_data(mark_values(FIGURES[wildcards.name], DECLARED_CLAIMS))


#: The paper's figures, drawn from the paper's experiments only: the figures a scenario
#: draws (a regex of their names).
PAPER_FIGURES = [
    name for name, f in FIGURES.items() if set(f.files) <= set(PAPER_RESULTS)
]
PAPER_FIGURE_NAMES = "|".join(re.escape(name) for name in PAPER_FIGURES)


@cache
def scenario_files(name):
    """The paper's result files as scenario ``name`` reads them, by key: its own where
    it changes what their jobs read, the paper's elsewhere."""
    return resolved_results(config, SCENARIO_CONFIGS[name], name)


def run_files(wildcards):
    """The result files of a job's run by key (the claims job's named inputs and a
    param): the paper's, or the scenario's (:func:`scenario_files`)."""
    name = scenario_name(wildcards)
    return dict(PAPER_RESULTS) if name is None else scenario_files(name)


def claim_inputs(wildcards):
    """The claims job's result files by key; for the paper's run, with its robustness
    analysis (a scenario is an exploration, not graded)."""
    files = run_files(wildcards)
    if scenario_name(wildcards) is None:
        files["robustness"] = RESULT_FILES["robustness"]
    return files


def run_record(wildcards):
    """The scenario's record (:func:`scenario_record`), or None for the paper's run."""
    return None if scenario_name(wildcards) is None else scenario_record(wildcards)


def scenario_record(wildcards):
    """What a scenario is: its name, its overrides and every change of the paper's
    configuration they make (key, the paper's value, the scenario's)."""
    name = scenario_name(wildcards)
    return {
        "name": name,
        "overrides": SCENARIOS[name],
        "changes": [
            {
                "key": k,
                "paper": old,
                "scenario": new,
                "text": describe(k, old, new, FITTED, STATED),
            }
            for k, old, new in changes(config, SCENARIO_CONFIGS[name])
        ],
    }


def scenario_changed_figures(name):
    """The paper's figures scenario ``name`` changes (one of their files is its own)."""
    files = scenario_files(name)
    return [
        f
        for f in PAPER_FIGURES
        if any(files[k] != PAPER_RESULTS[k] for k in FIGURES[f].files)
    ]


def scenario_report_figures(wildcards):
    """A scenario's page's figure inputs: its own of the figures it changes, and each
    against the paper's (shared scales, the difference); and, once, what of the
    scenario reaches none of them."""
    say_unreached(wildcards.scenario)
    folder = scenario_folder(wildcards.scenario)
    changed = scenario_changed_figures(wildcards.scenario)
    return [f"{folder}/figures/{f}.png" for f in changed] + [
        f"{folder}/compare/{f}.png" for f in changed
    ]


def scenario_comparisons(wildcards):
    """The comparison images of the figures a scenario changes (its article)."""
    folder = scenario_folder(wildcards.scenario)
    return [
        f"{folder}/compare/{f}.png"
        for f in scenario_changed_figures(wildcards.scenario)
    ]


def scenario_figure_table(wildcards):
    """Each paper figure on a scenario's page: the paper's file, the scenario's (None
    where it changes nothing the figure shows) and what it changes of its inputs."""
    name = wildcards.scenario
    changed = set(scenario_changed_figures(name))
    out = []
    for f in PAPER_FIGURES:
        read = changes_read(FIGURES[f].files, config, SCENARIO_CONFIGS[name])
        out.append(
            {
                "name": f,
                "paper": f"results/figures/{f}.png",
                "scenario": (
                    f"{scenario_folder(name)}/figures/{f}.png" if f in changed else None
                ),
                "compare": (
                    f"{scenario_folder(name)}/compare/{f}.png" if f in changed else None
                ),
                "changes": [describe(*c, FITTED, STATED) for c in read],
                "files": [
                    [PAPER_RESULTS[k], scenario_files(name)[k]]
                    for k in FIGURES[f].files
                    if scenario_files(name)[k] != PAPER_RESULTS[k]
                ],
            }
        )
    return out


#: The scenario notes said in this run: (scenario, override, row) triples.
_SAID = set()


def say_unreached(name, files=None):
    """At planning, once per override and row: each model override of scenario ``name``
    that the rows of ``files`` (default all) set themselves, and the key each reads
    instead (one line per override; the jobs neither rerun nor relabel those rows)."""
    rows = {}
    for key in PAPER_RESULTS if files is None else files:
        for line in unreached(config, SCENARIO_CONFIGS[name], [key]):
            override, _, row = line.partition(" does not reach ")
            if (name, override, row) not in _SAID:
                _SAID.add((name, override, row))
                rows.setdefault(override, []).append(row)
    for override, missed in rows.items():
        sys.stderr.write(
            f"tennis-stroke scenario note: scenario {name!r}: {override} does not reach "
            f"{', '.join(missed)}\n"
        )


def figure_note(wildcards):
    """A figure's second title line: none for the paper's; for a scenario's, the
    scenario and what it changes of what the figure's files read."""
    name = scenario_name(wildcards)
    if name is None:
        return ""
    read = changes_read(FIGURES[wildcards.name].files, config, SCENARIO_CONFIGS[name])
    what = (
        "; ".join(describe(*change, FITTED, STATED) for change in read)
        or "no change to its inputs"
    )
    return f"scenario {name}: {what}"


def relabel_map(wildcards):
    """A map of the table gets its labels from the units table when gathered (plain
    bool: a params value)."""
    return wildcards.map in CHUNKED


#: The paths a scenario's rules make below its folders.
SCENARIO_PATHS = "|".join(
    [
        rf"chunks/({SCENARIO_MAPS})/\d+-of-\d+\.nc",
        *(
            re.escape(f"{e.stem}.nc")
            for e in EXPERIMENTS.values()
            if e.family == "paper"
        ),
        rf"figures/({PAPER_FIGURE_NAMES})\.png",
        rf"compare/({PAPER_FIGURE_NAMES})\.png",
        r"claims\.csv",
        r"configuration\.yaml",
        r"index\.html",
        r"article\.pdf",
    ]
)
#: Any other path (rule unknown_scenario_file refuses it in one line).
UNKNOWN_SCENARIO_PATH = rf"(?!(?:{SCENARIO_PATHS})$).+"


def refuse_unknown_scenario_file(wildcards):
    """The input function of rule unknown_scenario_file: one line, then exit status 1."""
    where = f"{wildcards.top}/scenarios/{wildcards.declared}/{wildcards.path}"
    sys.stderr.write(
        f"tennis-stroke scenario error: no rule makes {where}: a scenario makes the paper "
        "experiments' files, the paper's figures (figures/fig02_angle_map.png ... "
        "figures/fig14_elbow_paths.png), claims.csv and its page (docs/scenarios.md)\n"
    )
    sys.exit(1)
