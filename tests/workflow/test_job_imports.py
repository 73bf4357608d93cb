"""Each job imports only what it runs: the imports of every workflow script, run in a
fresh interpreter, leave out the heavy modules its kind of job never uses (a job's
start-up is mostly imports: docs/performance.md).  The solver (and numba with it) loads
on a job's first stroke, not at import."""

import json
import os
import subprocess
import sys

import pytest
from conftest import ROOT
from scripts import top_level_imports

SCRIPTS = ROOT / "workflow" / "scripts"
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
#: What no job imports at start: the solver loads when a job simulates.
SOLVER = ("numba", "tennis_stroke.solver.stroke", "tennis_stroke.solver.compiled")
#: Modules only some kinds of job use: drawing, the page's views, the searches and fits.
DRAWING, VIEWS, SCIPY = ("matplotlib",), ("bokeh",), ("scipy",)
#: The samplers' module (about 1 s to import): only the jobs that draw a Sobol design
#: (the identification's starts, the screen's candidates) load it, when they sample.
SAMPLING = ("scipy.stats",)
#: Each script's heavy modules it must not import, by what the job does.
ABSENT = {
    "simulate.py": (*SOLVER, *DRAWING, *VIEWS, *SCIPY),  # the solver loads on its first stroke
    "gather_map.py": (*SOLVER, *DRAWING, *VIEWS, *SCIPY),  # reads chunks, writes a file
    "figure.py": (*SOLVER, *VIEWS, *SCIPY),  # draws from files
    "compare.py": (*SOLVER, *VIEWS, *SCIPY),  # draws from files, as figure.py
    "report.py": (*SOLVER, *DRAWING, *SCIPY),  # embeds the drawn figures, views on demand
    "article.py": (*SOLVER, *DRAWING, *SCIPY),  # typesets the results, draws nothing
    "scenario_article.py": (*SOLVER, *DRAWING, *SCIPY),  # typesets the results
    "scenario_report.py": (*SOLVER, *DRAWING, *SCIPY),
    "claims.py": (*DRAWING, *VIEWS, *SAMPLING),  # searches: the solver and scipy.optimize
    "claims_validation.py": (*DRAWING, *VIEWS, *SAMPLING),
    "identification.py": (*DRAWING, *VIEWS, *SAMPLING),  # samples when it fits
    "model_ladder.py": (*DRAWING, *VIEWS, *SAMPLING),
    "robustness_chunk.py": (*DRAWING, *VIEWS, *SAMPLING),
    "robustness_screen.py": (*DRAWING, *VIEWS, *SAMPLING),  # samples when it screens
}


def loaded_after(code: str, watched) -> list[str]:
    report = f"print(json.dumps([m for m in {list(watched)!r} if m in sys.modules]))"
    probe = f"{code}\nimport json, sys\n{report}"
    done = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


#: Modules every job imports and none of :data:`ABSENT` comes with (checked): loaded
#: once before the scripts' imports run, each in a fork of that interpreter.
PRELOADED = ("numpy", "pandas", "xarray", "yaml")
#: One interpreter: the preloaded modules, then per script a fork running its imports
#: and printing which of its watched modules they loaded (as JSON, one line per script).
FORKED = """
import json, os, sys
import numpy, pandas, xarray, yaml
scripts = json.loads(sys.stdin.read())
watched = sorted({m for _, mods in scripts.values() for m in mods})
print(json.dumps({"preloaded": [m for m in watched if m in sys.modules]}), flush=True)
for name, (code, mods) in sorted(scripts.items()):
    pid = os.fork()
    if pid == 0:
        exec(compile(code, name, "exec"), {"__name__": "__job__"})
        print(json.dumps({name: [m for m in mods if m in sys.modules]}), flush=True)
        os._exit(0)
    assert os.waitpid(pid, 0)[1] == 0, name
"""


@pytest.fixture(scope="module")
def loaded_by_script() -> dict[str, list[str]]:
    """What each workflow script's top-level imports load of its :data:`ABSENT` modules,
    each in a fresh fork of one interpreter that imported only :data:`PRELOADED` (a
    fresh interpreter per script imported those fourteen times over)."""
    scripts = {s: (top_level_imports(SCRIPTS / s), ABSENT[s]) for s in ABSENT}
    done = subprocess.run(
        [sys.executable, "-c", FORKED],
        input=json.dumps(scripts),
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "OPENBLAS_NUM_THREADS": "1"},
    )
    assert done.returncode == 0, done.stderr[-2000:]
    out = {}
    for line in done.stdout.strip().splitlines():
        out.update(json.loads(line))
    assert out.pop("preloaded") == []  # the common modules load none of the watched ones
    return out


def test_every_script_is_a_kind_of_job():
    assert {p.name for p in SCRIPTS.glob("*.py")} == set(ABSENT)


@pytest.mark.process
@pytest.mark.parametrize("script", sorted(ABSENT))
def test_a_job_imports_only_what_it_runs(script, loaded_by_script):
    assert loaded_by_script[script] == []


@pytest.mark.process
def test_the_workflow_s_plan_loads_no_search_and_no_solver():
    """What the Snakefile imports to plan the jobs (every snakemake call, a dry run too):
    numba comes with the memory estimate's layout constants (and numba brings scipy's
    core), but no search, fit, integrator, drawing or view."""
    rules = (ROOT / "workflow" / "rules" / "common.smk").read_text()
    code, block = [], False
    for line in rules.splitlines():  # the import statements, multi-line ones whole
        if line.startswith("from tennis_stroke"):
            block = line.rstrip().endswith("(")
            code.append(line)
        elif block:
            code.append(line)
            block = not line.startswith(")")
    assert len(code) > 10
    code += [  # and the checks of the config it runs before any job
        "from tennis_stroke.io.config_files import load_yaml",
        "from tennis_stroke.pipeline.config_check import config_errors",
        f"config = load_yaml({str(ROOT / 'config' / 'config.yaml')!r})",
        f"assert config_errors(config, {str(SCHEMA)!r}) == []",
    ]
    heavy = ("scipy.optimize", "scipy.stats", "scipy.integrate", "matplotlib", "bokeh")
    assert loaded_after("\n".join(code), (*heavy, "tennis_stroke.solver.stroke")) == []
