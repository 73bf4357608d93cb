# What every rule reads, checked before any job (each failure one line, exit status 1):
# the paper's configuration and the declared what-if scenarios' as runs
# (tennis_stroke.pipeline.runs: a job's configuration, files and params from its
# wildcards), and the code inputs of the jobs (tennis_stroke.pipeline.code_inputs: the
# package modules each job imports, so an edit reruns exactly the jobs that run it).
import os
import sys
from pathlib import Path

from tennis_stroke.experiments.specs import (
    IDENTIFICATION_FILES,
    INFERENCE_RESULTS,
    PAPER_RESULTS,
    RESULT_FILES,
    STUDY_RESULTS,
    VALIDATION_GROUPS,
    fit_set_arguments,
    sorted_data,
)
from tennis_stroke.io.interrupts import PARENT_ENV, process_identity
from tennis_stroke.pipeline import params as job_params
from tennis_stroke.pipeline.checkout import (
    planned_files,
    shell_safe,
    unwritable_folders,
)
from tennis_stroke.pipeline.code_inputs import CodeInputs
from tennis_stroke.pipeline import earlier
from tennis_stroke.pipeline.runs import (
    CHUNKED,
    CHUNKED_MAPS,
    PAPER_FIGURES,
    ROWS,
    UNKNOWN_SCENARIO_PATH,
    UNKNOWN_FIGURE,
    PlanningError,
    Runs,
    checked_config,
    guard_checkout,
    refuse_unknown_figure,
    stems,
)
from tennis_stroke.pipeline.resources import asked
from tennis_stroke.pipeline.targets import targets
from tennis_stroke.replication.registry import FIGURES

# This checkout: the folder of workflow/ (workflow.basedir is the importing workflow's
# when another one imports this as a module; current_basedir is this file's folder).
CHECKOUT = Path(workflow.current_basedir).parents[1]
SCHEMA = CHECKOUT / "workflow/schemas/config.schema.yaml"
try:
    # the claims, the reading space and the config (its defaults filled in, checked
    # against its schema and bounds, one spelling per value): once per start
    _adhoc, READING_SPACE = checked_config(config, SCHEMA)
    # the scenarios (config/scenarios.yaml and --config scenarios=...), each checked as
    # the paper's configuration is; a bad one is a warning line, never a stop
    RUNS = Runs.declared(config, READING_SPACE, _adhoc, SCHEMA)
    # no damaged result file, and the checkout's code is the code the jobs import
    guard_checkout(CHECKOUT, sys.argv[1:])
except PlanningError as _exc:
    sys.stderr.write(_exc.line() + "\n")
    sys.exit(1)
# Snakemake runs a script job as `{sys.executable} {script}` without quoting the
# interpreter's path: quoted here, a checkout under a folder with a space runs
# (tennis_stroke.pipeline.checkout; docs/workflow.md).
sys.executable = shell_safe(sys.executable)
# Each job stops when this Snakemake process ends (killed, say) instead of computing on
# and writing after it (tennis_stroke.io.interrupts.stop_with_snakemake).
os.environ[PARENT_ENV] = process_identity(os.getpid())
CODE = CodeInputs(CHECKOUT)
# What a job without points asks of the scheduler (tennis_stroke.pipeline.resources).
LIGHT = asked(0)
# The earlier file of each output a job is about to replace, kept beside it until the
# job has made the new one (Snakemake removes a job's outputs when it starts the job);
# at the end each is dropped or, for a failed or stopped job, put back dated 1970 and
# unrecorded, so that its job runs again (tennis_stroke.pipeline.earlier).


onstart:
    if workflow.is_main_process:
        earlier.settle(workflow.persistence)  # a killed run's
        # every folder the planned jobs write, once, before the first job: a folder
        # not writable (or a file in its place) is one line, not a job's traceback
        _blocked = unwritable_folders(planned_files(workflow.persistence))
        if _blocked:
            sys.stderr.write(f"tennis-stroke error: {_blocked}\n")
            sys.exit(1)
        earlier.keep(workflow.persistence.all_outputfiles())


onsuccess:
    earlier.settle(workflow.persistence)


onerror:
    put_back = earlier.settle(workflow.persistence)
    if put_back:
        sys.stderr.write(
            f"tennis-stroke: {len(put_back)} earlier result(s) put back until their jobs "
            f"complete (dated 1970, so they run again): {', '.join(put_back)}\n"
        )


# A run is the paper's ({run} empty: its files under results/) or a declared scenario's
# (scenarios/NAME/: under results/scenarios/NAME/); a scenario's own jobs have a
# {scenario} wildcard.  Both match declared names only (none: nothing).
wildcard_constraints:
    chunk=r"\d+",
    chunks=r"\d+",
    scenario=RUNS.declared_names,
    run=RUNS.run_pattern,
