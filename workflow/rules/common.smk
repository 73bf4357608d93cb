# Config validation and helpers shared by all rules.
from pathlib import Path

import os
import sys

from snakemake.utils import validate

from tennis_stroke.experiments.grids import chunk_count, grid
from tennis_stroke.experiments.specs import (
    ANGLE_MAP_FIGURES,
    IDENTIFICATION_FILES,
    INFERENCE_RESULTS,
    PAPER_RESULTS,
    RESULT_FILES,
)
from tennis_stroke.experiments.strokes import sec5_stroke
from tennis_stroke.inference.claims import claim_errors, load_claims
from tennis_stroke.inference.reading_space import ReadingSpaceError, load_reading_space
from tennis_stroke.pipeline.config_check import config_errors, numbers_from_strings
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

#: The package, by layer (folders) and module; rules declare the sources they run as
#: inputs, so an edit reruns exactly the jobs that read it (Snakemake does not see code
#: changes in an imported package).
PACKAGE_DIR = Path(workflow.basedir) / "src" / "tennis_stroke"


def checkout_path(path):
    """A file of the checkout (the Snakefile's folder) as an input path relative to the
    working directory.  Snakemake records input paths: relative ones stay the same when
    the checkout and its working directory move together, so a moved or copied checkout
    reruns nothing (``workflow.source_path`` records the absolute path)."""
    return os.path.relpath(path, os.getcwd())


#: Top-level modules every simulation job runs: package start-up, files, chunks.
JOB_MODULES = ("__init__.py", "_cache.py", "io", "pipeline")


def sources(*parts):
    """Source files of the package's ``parts``: a layer folder (every module in it) or a
    module path, as sorted paths relative to the working directory (checkout_path)."""
    out = set()
    for part in parts:
        path = PACKAGE_DIR / part
        out.update(
            checkout_path(p) for p in (path.glob("*.py") if path.is_dir() else [path])
        )
    return sorted(out)


#: What a simulation runs: the model, the solver and the experiments.
SIMULATION_SOURCES = sources("model", "solver", "experiments", *JOB_MODULES)
#: What an inference job runs: the same and the inference.
INFERENCE_SOURCES = sources("model", "solver", "experiments", "inference", *JOB_MODULES)
#: What a solver study runs: the same and the studies.
STUDY_SOURCES = sources("model", "solver", "experiments", "studies", *JOB_MODULES)


def grid_spec(spec):
    """A range of the config as a plain list [start, stop, step] (a params value)."""
    return [float(spec["start"]), float(spec["stop"]), float(spec["step"])]


wildcard_constraints:
    chunk=r"\d+",
    chunks=r"\d+",


#: Maps computed in chunks (paths under results/, without .nc) and gathered by rule
#: gather_map.
CHUNKED_MAPS = (
    r"angle_maps/fig[23]|mass_length/map|torque_delay/fig[789]|elbow_force/map"
    r"|robustness/claims"
)


def map_rows(name):
    """Requested chunks and number of rows of the first axis of map ``name``
    (CHUNKED_MAPS); the robustness analysis' from config/readings.yaml (its rows: at
    most the declared number of readings)."""
    section, item = name.split("/")
    chunks = config["chunks"]
    if section == "robustness":
        spec = READING_SPACE.raw["multiverse"]
        return spec["chunks"], spec["readings"]
    if section == "angle_maps":
        return (
            chunks["angle_map"],
            grid(*grid_spec(config["angle_maps"]["theta0"])).size,
        )
    if section == "mass_length":
        return chunks["mass_length"], grid(*grid_spec(config["mass_length"]["M2"])).size
    if section == "elbow_force":
        rows = grid(*grid_spec(config["elbow_force"]["psi_F"])).size
        return chunks["elbow_force_map"], rows
    first = config["torque_delay"][item]["C2" if item == "fig7" else "delta0"]
    rows = grid(*grid_spec(first)).size if isinstance(first, dict) else 1
    return chunks["delay_map"], rows


def chunk_files(wildcards):
    """The chunk files of a map: the requested chunk count, at most one per row."""
    n = chunk_count(*map_rows(wildcards.map))
    return [f"results/chunks/{wildcards.map}/{i}-of-{n}.nc" for i in range(n)]


def angle_map_L1(wildcards):
    """The rod-1 length (m) of the angle map of a paper figure: ``angle_maps.L1`` lists
    them in the order of ANGLE_MAP_FIGURES (Fig. 2, Fig. 3)."""
    lengths = dict(zip(ANGLE_MAP_FIGURES, config["angle_maps"]["L1"], strict=True))
    return float(lengths[wildcards.fig])


def model():
    """Model overrides as a plain dict in a fixed order (params compare by repr)."""
    return dict(sorted(config.get("model", {}).items()))


def solver():
    """Solver settings as a plain dict."""
    return dict(sorted(config["solver"].items()))


def delay_stroke():
    """The Sec. V-VI base stroke (plain dict): only what the stroke rules need, so that
    changing a map's grid does not rerun them."""
    return sec5_stroke(config)


def work_precision_study():
    """The work-precision settings of the solver study (plain dict): only what the rule
    reads, so that changing the stability or optimum study does not rerun it."""
    keys = (
        "strokes",
        "seed",
        "compiled_tolerances",
        "scipy_tolerances",
        "rk4_steps",
        "repeats",
    )
    return {k: config["solver_study"][k] for k in keys}


def delay_section(wildcards):
    """The config of one Sec. V map (fig7, fig8 or fig9) with the shared L1 and theta0."""
    d = config["torque_delay"]
    return {**d[wildcards.fig], "L1": d["L1"], "theta0": d["theta0"]}


def paper_experiments():
    """The config sections of the paper's experiments (the robustness analysis reruns
    them under each reading)."""
    keys = (
        "angle_maps",
        "fig4",
        "k_sensitivity",
        "mass_length",
        "torque_delay",
        "elbow_force",
    )
    return {k: config[k] for k in keys}


def common_params():
    """Params every simulation script needs."""
    return {"model": model(), "solver": solver()}


def figure_inputs(wildcards):
    """The result files a figure is drawn from (the registry)."""
    return FIGURES[wildcards.name].inputs
