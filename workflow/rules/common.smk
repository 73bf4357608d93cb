# Config validation and helpers shared by all rules.
from pathlib import Path

import os
import re
import sys

from snakemake.utils import validate

from tennis_stroke._imports import PACKAGE as INSTALLED
from tennis_stroke._imports import closure
from tennis_stroke.experiments.grids import chunk_count
from tennis_stroke.experiments.specs import (
    IDENTIFICATION_FILES,
    INFERENCE_RESULTS,
    PAPER_RESULTS,
    RESULT_FILES,
    EXPERIMENTS,
    VALIDATION_GROUPS,
    fit_set_arguments,
    plain,
    value_at,
)
from tennis_stroke.inference.multiverse import MULTIVERSE_SETS
from tennis_stroke.inference.claims import claim_errors, load_claims
from tennis_stroke.inference.reading_space import ReadingSpaceError, load_reading_space
from tennis_stroke.inference.targeted import targeted_config
from tennis_stroke.inference.validation import group_config
from tennis_stroke.pipeline.config_check import config_errors, numbers_from_strings
from tennis_stroke.pipeline.targets import damaged_results
from tennis_stroke.replication.registry import FIGURES

# Nested --config values arrive as strings: numbers again, as from the YAML file.
config.update(numbers_from_strings(config))
# One line naming the key and the rule it breaks, before any job starts (no traceback).
_errors = config_errors(
    config, Path(workflow.basedir) / "workflow/schemas/config.schema.yaml"
)
if _errors:
    sys.stderr.write(f"tennis-stroke config error: {_errors[0]}\n")
    sys.exit(1)
validate(config, "../schemas/config.schema.yaml", set_default=True)
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

# A damaged result file (truncated, garbage) is named before any job: Snakemake would take
# it for up to date, and every job reading it would fail.
_damaged = damaged_results()
if _damaged:
    _path, _problem = _damaged[0]
    sys.stderr.write(
        f"tennis-stroke results error: {_path} is damaged ({_problem}): remove it and run "
        "make report (it names every result as a target, so it is rebuilt)\n"
    )
    sys.exit(1)

#: The workflow's scripts: each rule's code inputs are the package modules its job
#: imports (tennis_stroke._imports), so an edit reruns exactly the jobs that run it
#: (Snakemake does not see code changes in an imported package).
SCRIPTS = Path(workflow.basedir) / "workflow" / "scripts"
PACKAGE_DIR = Path(workflow.basedir) / "src" / "tennis_stroke"
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


def simulation_params(experiment):
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
        out["common"] = common_params()
    return out


wildcard_constraints:
    chunk=r"\d+",
    chunks=r"\d+",


#: Maps computed in chunks (paths under results/, without .nc) and gathered by rule
#: gather_map: the table's chunked rows and the robustness analysis.
CHUNKED = {e.stem: e for e in EXPERIMENTS.values() if e.chunks}
CHUNKED_MAPS = "|".join(re.escape(stem) for stem in [*CHUNKED, "robustness/claims"])


def map_rows(name):
    """Requested chunks and number of rows of the first axis of map ``name``
    (CHUNKED_MAPS); the robustness analysis' from config/readings.yaml (its rows: at
    most the declared number of readings)."""
    if name == "robustness/claims":
        spec = READING_SPACE.raw["multiverse"]
        return spec["chunks"], spec["readings"]
    experiment = CHUNKED[name]
    requested = value_at(config, experiment.chunks)
    return requested, experiment.row_count(experiment.arguments(config))


def chunk_files(wildcards):
    """The chunk files of a map: the requested chunk count, at most one per row."""
    n = chunk_count(*map_rows(wildcards.map))
    return [f"results/chunks/{wildcards.map}/{i}-of-{n}.nc" for i in range(n)]


def model():
    """Model overrides as a plain dict in a fixed order (params compare by repr)."""
    return dict(sorted(config.get("model", {}).items()))


def solver():
    """Solver settings as a plain dict."""
    return dict(sorted(config["solver"].items()))


def common_params():
    """Params every model simulation needs."""
    return {"model": model(), "solver": solver()}


def paper_sections():
    """The config sections the paper's experiments read and the claims' search settings
    (section ``search``), less those the multiverse sets itself."""
    sections = {
        key.split(".")[0]
        for e in EXPERIMENTS.values()
        if e.family == "paper"
        for key in e.keys()
    }
    sections.add("search")
    # plain: keys sorted, as a --config merge reorders them (params compare by repr)
    return plain({k: config[k] for k in sections - set(MULTIVERSE_SETS)})


def paper_experiments():
    """What the targeted evaluation of the claims reads (the claims job and the
    robustness analysis rerun it): :func:`paper_sections` less the steps of the maps it
    searches instead (tennis_stroke.inference.targeted.targeted_config)."""
    return plain(targeted_config(paper_sections()))


def figure_inputs(wildcards):
    """The result files a figure is drawn from (the registry)."""
    return FIGURES[wildcards.name].inputs


def relabel_map(wildcards):
    """A map of the table gets its labels from the units table when gathered (plain
    bool: a params value)."""
    return wildcards.map in CHUNKED
