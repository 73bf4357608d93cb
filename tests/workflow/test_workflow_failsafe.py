"""The workflow fails safe: every value of the config reaches the jobs that use it (or
the run is refused), bad claims are refused before any job, and a moved checkout
reruns nothing.

Dry runs (``snakemake -n``) on a copy of the checkout and of the tiny run's directory,
moved together to another folder: the copied sources are older than every result, so
edits of the checkout while the tests run do not plan jobs (Snakemake reruns a job whose
input is newer than its output whatever ``--rerun-triggers`` says)."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from conftest import (
    CHECKOUT,
    ROOT,
    paused_write,
    planned_kinds,
    run_snakemake,
    snakemake_command,
    workdir,
)
from tiny import TINY, TINY_READINGS

from tennis_stroke.experiments.specs import EXPERIMENTS
from tennis_stroke.pipeline.explain import rows_reading

#: The workflow end to end: slow (pytest -m 'not slow' leaves it out).
pytestmark = pytest.mark.workflow

#: The rules that must plan a job when a config key changes, by the key's path (the
#: longest prefix applies): each key belongs to an experiment or a solver study, not only
#: to the inference that reruns them all.  An empty set: a key that changes no result (a
#: resource limit), not run.
#: The rules of the table of experiments (one per row).
TABLE_RULES = {e.rule for e in EXPERIMENTS.values()}


def expected_rules(parts) -> set[str]:
    """The rules a change of config key ``parts`` must plan: the rows of the table that
    the package says read it (tennis_stroke.pipeline.explain, the table of
    docs/config_keys.md and `tennis-stroke config explain`), and the gathering of the
    maps for their failure limit."""
    key = ".".join(map(str, parts))
    if key == "max_failure_share":
        return {"gather_map"}
    return {EXPERIMENTS[k].rule for k in rows_reading(key)}


SCHEMA = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())


def leaves(node, parts=()):
    """The values of a config a user sets, by path: scalars, lists and ranges
    (``{start, stop, ...}``); other mappings are walked."""
    if isinstance(node, dict) and not {"start", "stop"} <= set(node):
        for key, value in node.items():
            yield from leaves(value, (*parts, key))
    else:
        yield parts, node


def choices(parts) -> list:
    """The values the schema allows at ``parts`` (its ``enum``; empty: any)."""
    node = SCHEMA
    for part in parts:
        node = node.get("properties", {}).get(part, {})
    return node.get("enum") or node.get("items", {}).get("enum", [])


def changed(value, parts=()):
    """Another valid value: a range with half its step (or one point more), numbers
    scaled by 0.9 (0 becomes 0.01, an integer grows by one), a string the next of its
    schema's choices."""
    if isinstance(value, dict):
        if "step" in value:
            return {**value, "step": value["step"] / 2}
        return {**value, "num": value["num"] + 1}
    if isinstance(value, list):
        return [changed(v, parts) for v in value]
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return value + 1
    if isinstance(value, float):
        return round(value * 0.9, 12) if value else 0.01
    if isinstance(value, str):
        return next((c for c in choices(parts) if c != value), value)
    return value


def get(config, parts):
    for part in parts:
        config = config[part]
    return config


def has(config, parts) -> bool:
    """Whether ``config`` holds a value at ``parts``."""
    for part in parts:
        if not isinstance(config, dict) or part not in config:
            return False
        config = config[part]
    return True


def with_value(config, parts, value):
    """``config`` (a copy) with ``value`` at ``parts``."""
    out = yaml.safe_load(yaml.safe_dump(config))
    if len(parts) == 1:
        out[parts[0]] = value
    else:
        get(out, parts[:-1])[parts[-1]] = value
    return out


#: The jobs of a dry run counted by kind (a row's job by the row's name, others by rule).
planned_jobs = planned_kinds


def override(section, value) -> str:
    """A --config item setting a whole top-level section (nothing depends on how
    Snakemake merges nested values)."""
    return f"{section}={yaml.safe_dump(value, default_flow_style=True).strip()}"


def dry_runs(snakefile, work, overrides=(), runs=None):
    """Dry runs of the report, one per config override (or per run of ``runs``: a config,
    a target, files written first; tests/dry_runs.py), in one process: ``[{"exit":
    status, "output": log, "stderr": its stderr}, ...]``."""
    command = [sys.executable, str(Path(__file__).parents[1] / "dry_runs.py")]
    runs = [{"config": o} for o in overrides] if runs is None else runs
    done = subprocess.run(
        [*command, str(snakefile), str(work), "report"],
        input=json.dumps(runs),
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout)


#: A time before the tiny run (2001): the copied sources are older than every result.
OLD = 1_000_000_000


@pytest.fixture(scope="module")
def moved(tiny_run, tmp_path_factory):
    """The checkout and the tiny run's directory copied together into one folder (in
    their relative position), brought up to date there (``--touch``: the copy's sources
    are frozen, so edits of the checkout after the tiny run do not count), then the
    folder renamed; a function running the moved Snakefile on the moved directory."""
    here = tmp_path_factory.mktemp("here")
    code = ROOT.relative_to(ROOT.anchor)
    work = tiny_run.resolve().relative_to(tiny_run.anchor)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
    for name in CHECKOUT:
        if (ROOT / name).is_dir():
            shutil.copytree(ROOT / name, here / code / name, ignore=ignore)
        else:
            (here / code).mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, here / code / name)
    for path in (here / code).rglob("*"):
        if path.is_file():
            os.utime(path, (OLD, OLD))
    shutil.copytree(tiny_run, here / work, symlinks=True)

    def snakemake(root, *options):
        command = snakemake_command("report", root / work, *options)
        command[command.index("-s") + 1] = str(root / code / "workflow" / "Snakefile")
        return subprocess.run(command, capture_output=True, text=True, timeout=600)

    touched = snakemake(here, "--touch", "--cores", "1")
    assert touched.returncode == 0, touched.stderr[-3000:]
    elsewhere = here.with_name(here.name.replace("here", "elsewhere"))
    here.rename(elsewhere)

    def run(*options):
        return snakemake(elsewhere, *options)

    run.snakefile, run.work = elsewhere / code / "workflow" / "Snakefile", elsewhere / work
    return run


def test_a_moved_checkout_reruns_nothing(moved):
    """Rule inputs are relative to the working directory: the moved checkout's dry run
    plans no job (absolute paths plan every job: 'set of input files has changed')."""
    done = moved("-n")
    assert done.returncode == 0, done.stderr[-2000:]
    output = done.stdout + done.stderr
    assert planned_jobs(output) == {} and "Nothing to be done" in output, output[-3000:]


def test_every_key_of_the_config_is_used_or_refused(moved):
    """Changing any value of config/config.yaml (every grid, list and number, and every
    string with choices) plans the jobs of exactly the rows of the table of experiments
    that read it (and no other row), or the run is refused with one line naming it; never
    a report over results of the old value."""
    tiny = yaml.safe_load((moved.work / "config" / "config.yaml").read_text())
    paper = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    keys = [parts for parts, _ in leaves(paper) if expected_rules(parts)]
    assert len(keys) >= 50 and ("angle_maps", "L1") in keys
    overrides = []
    for parts in list(keys):
        # the tiny run's value, or the paper's for a key the tiny config leaves out (a
        # section, or a scene of the solver study)
        base = tiny if parts[0] in tiny else paper
        if not has(base, parts):  # the paper's subtree added where the tiny one stops
            at = next(i for i in range(len(parts)) if not has(base, parts[: i + 1]))
            base = with_value(base, parts[: at + 1], get(paper, parts[: at + 1]))
        value = changed(get(base, parts), parts)
        if value == get(base, parts) and isinstance(value, str) and not choices(parts):
            keys.remove(parts)  # a string whose choices the schema leaves to the model
            continue
        assert value != get(base, parts), parts
        overrides.append({parts[0]: with_value(base, parts, value)[parts[0]]})
    unchanged, *runs = dry_runs(moved.snakefile, moved.work, [{}, *overrides])
    # else every key would seem to plan its jobs
    assert unchanged["exit"] == 0 and planned_jobs(unchanged["output"]) == {}, unchanged
    problems = []
    for parts, done in zip(keys, runs, strict=True):
        key = ".".join(map(str, parts))
        if done["exit"]:
            lines = [line for line in done["output"].splitlines() if "tennis-stroke" in line]
            if len(lines) != 1 or f"'{key}" not in lines[0]:
                problems.append(f"{key}: refused without one line naming it: {lines}")
            continue
        planned = set(planned_jobs(done["output"]))
        expected = expected_rules(parts)
        # exactly the rows that read the key among the table's rules (a chunk count
        # changes nothing of a map with one row: Fig. 9)
        table = planned & TABLE_RULES
        exact = table <= expected if key.startswith("chunks.") else table == expected & TABLE_RULES
        if not expected & planned or not exact:
            problems.append(f"{key}: plans {sorted(planned)}, expected {sorted(expected)}")
    assert not problems, "\n".join(problems)


def test_the_angle_maps_follow_their_L1(moved):
    """Figs. 2 and 3 are the maps at angle_maps.L1 (in that order): changing Fig. 2's
    length reruns its map, its figure and the claims, and leaves Fig. 3's map; one length
    alone is refused."""
    section = {**TINY["angle_maps"], "L1": [0.35, 0.4]}
    done = moved("-n", "--config", override("angle_maps", section))
    assert done.returncode == 0, done.stderr[-2000:]
    text = done.stdout + done.stderr
    assert planned_jobs(text)["fig2"] == 1 and "fig3" not in planned_jobs(text)
    assert "output: results/chunks/angle_maps/fig2/0-of-1.nc" in text
    assert "output: results/figures/fig02_angle_map.png" in text
    assert "output: results/figures/fig03_angle_map.png" not in text
    assert {"claims", "report"} <= set(planned_jobs(text))
    section["L1"] = [0.35]
    done = moved("-n", "--config", override("angle_maps", section))
    assert done.returncode == 1
    assert done.stderr.strip().splitlines() == [
        "tennis-stroke config error: config key 'angle_maps.L1': [0.35] is too short "
        "(rule: minItems)"
    ]


def test_a_figure_no_rule_makes_or_no_folder_takes_is_one_line_naming_it(tmp_path):
    """Issue 66, case 20, as Snakemake shows it: one dry-run process, four targets. Then
    case 8 (results/figures not writable: a 60-line traceback): a run of the figure with
    a file where results/figures goes stops before any job, in one line naming it (the
    check runs in the Snakefile's onstart, which a dry run skips; the tests run as root,
    for whom no mode bit makes a folder read-only; in-process: test_one_run.py)."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    names = ["fig9", "fig99", "fig09_v_tua", "fig09_v_tau"]
    runs = [{"target": f"results/figures/{name}.png"} for name in names]
    blocked = {"files": {"results/figures": "not a folder\n"}, "execute": True}
    runs.append({"target": "results/figures/fig09_v_tau.png", **blocked})
    *refused, known, stopped = dry_runs(ROOT / "workflow" / "Snakefile", work, runs=runs)
    lines = [x for x in stopped["stderr"].splitlines() if "error" in x or "Traceback" in x]
    assert stopped["exit"] == 1 and len(lines) == 1, stopped["output"][-3000:]
    assert lines[0].startswith("tennis-stroke error: 'results/figures' is not a folder: "), lines
    assert "results/figures/fig09_v_tau.png" in lines[0], lines
    assert not (work / "logs").exists() and not (work / "results" / "chunks").exists()
    for name, run in zip(names, refused, strict=False):
        lines = [x for x in run["output"].splitlines() if "error" in x or "Traceback" in x]
        assert run["exit"] == 1 and len(lines) == 1, run["output"][-2000:]
        assert lines[0].startswith(
            f"tennis-stroke figure error: no rule makes results/figures/{name}.png (nearest: "
            "results/figures/fig09_v_tau.png"
        ), lines
    assert known["exit"] == 0 and "rule figure:" in known["output"], known["output"][-2000:]


def test_a_bad_claim_is_refused_before_any_job(tmp_path):
    work = workdir(tmp_path, TINY, TINY_READINGS)
    path = work / "config" / "claims.yaml"
    raw = yaml.safe_load(path.read_text())
    claim = next(c for c in raw["claims"] if c["id"] == "fig2_best_delta0_at_120")
    claim["measure"]["file"] = "fig44"
    path.write_text(yaml.safe_dump(raw, sort_keys=False))
    done = run_snakemake("report", work, "-n")
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith(
        "tennis-stroke claims error: config/claims.yaml: claim 'fig2_best_delta0_at_120': "
        "unknown result file 'fig44' (known: delay, elbow, elbow_map, fig2, fig3, fig4,"
    )
    assert not (work / "results").exists() and not (work / "logs").exists()


#: The lines Snakemake itself writes before it builds the plan.
PREAMBLE = ("host: " + os.uname().nodename, "Building DAG of jobs...")
#: Bad scenario files, the file a user asks for, and the first words of the one line.
BAD_SCENARIOS = [
    # a name no scenario declares, as a target (Snakemake's own message is a traceback)
    (
        "a: {model: {M2: 0.35}}\n",
        "results/scenarios/b/figures/fig02_angle_map.png",
        "tennis-stroke scenario error: no scenario 'b' is declared (declared: a;",
    ),
    # a path no rule makes under a declared scenario
    (
        "a: {model: {M2: 0.35}}\n",
        "results/scenarios/a/figures/study01_work_precision.png",
        "tennis-stroke scenario error: no rule makes results/scenarios/a/figures/study01",
    ),
    # a bad override
    (
        "a: {model: {M2: -1.0}}\n",
        "report/scenarios/a/index.html",
        "tennis-stroke scenario error: scenario 'a': config key 'model': parameter 'M2' "
        "must be > 0 kg, got -1",
    ),
    # a scenario that changes nothing (the explorer's Save at the defaults wrote one;
    # whatif refused it while its page planned jobs)
    (
        "good-one: {}\n",
        "report/scenarios/good-one/index.html",
        "tennis-stroke scenario error: scenario 'good-one' changes nothing of the paper's",
    ),
    (
        "good-one: {model: {M2: 0.3}}\n",
        "results/scenarios/good-one/claims.csv",
        "tennis-stroke scenario error: scenario 'good-one' changes nothing of the paper's",
    ),
    # a section only the paper's configuration runs
    (
        "a: {solver_study: {seed: 3}}\n",
        "results/scenarios/a/claims.csv",
        "tennis-stroke scenario error: scenario 'a': may not override 'solver_study'",
    ),
    (
        "- a\n",
        "report/scenarios/a/index.html",
        "tennis-stroke scenario error: config/scenarios.yaml: must map",
    ),
    # an alias bomb inside one scenario (minutes and gigabytes of planning before)
    (
        "a:\n  model:\n    l0: &l0 [1, 2, 3, 4, 5, 6, 7, 8, 9]\n"
        + "".join(f"    l{i}: &l{i} [{', '.join([f'*l{i - 1}'] * 9)}]\n" for i in range(1, 9)),
        "report/scenarios/a/index.html",
        "tennis-stroke scenario error: config/scenarios.yaml: holds 4.9e+08 values once its",
    ),
]


def test_a_bad_scenario_is_one_line_before_any_job(tmp_path):
    """Asking for a bad scenario's files is refused in one line before any job; the
    paper's run goes on with a warning naming it (a scenario never stops it).  Every case
    and the paper's run beside it are dry runs of one process (tests/dry_runs.py)."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    runs = []
    for scenarios, target, _ in BAD_SCENARIOS:
        files = {"config/scenarios.yaml": scenarios}
        runs += [{"target": target, "files": files}, {"target": "report", "files": files}]
    done = dry_runs(ROOT / "workflow" / "Snakefile", work, runs=runs)
    pairs = zip(BAD_SCENARIOS, done[::2], done[1::2], strict=True)
    for (scenarios, target, line), asked, paper in pairs:
        assert asked["exit"] == 1, (target, asked["output"][-2000:])
        err = asked["stderr"].strip().splitlines()
        # Snakemake's own preamble (its API logs it; the command line with -n too)
        lines = [x for x in err if x.strip() and "scenario warning" not in x and x not in PREAMBLE]
        assert len(lines) == 1 and lines[0].startswith(line), (target, lines)
        assert paper["exit"] == 0, (scenarios, paper["output"][-2000:])
        warnings = [x for x in paper["stderr"].splitlines() if x.startswith("tennis-stroke")]
        assert all("scenario warning" in x for x in warnings), warnings
    assert not (work / "results").exists()


def test_an_override_a_row_sets_itself_is_said_once_at_planning(tmp_path):
    """Snakemake run by hand for a scenario says, in one line per override, which rows
    of its targets set an overridden parameter themselves and the key each reads
    instead (as whatif does), each row once however many targets read it; a target
    every override reaches gets no note."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    (work / "config" / "scenarios.yaml").write_text("c: {model: {C2: 3.0, M2: 0.35}}\n")
    head = "tennis-stroke scenario note: scenario 'c': "
    fig = "results/scenarios/c/figures/"
    for targets, says, not_says in (
        (["report/scenarios/c/index.html"], ["Fig. 7", "Fig. 9"], []),
        ([fig + "fig09_v_tau.png"], ["Fig. 9"], ["Fig. 7"]),
        ([fig + "fig07_torque_delay.png", fig + "fig09_v_tau.png"], ["Fig. 7", "Fig. 9"], []),
        ([fig + "fig02_angle_map.png"], None, []),
    ):
        done = run_snakemake(targets, work, "-n")
        assert done.returncode == 0, done.stderr[-2000:]
        notes = [x for x in done.stderr.splitlines() if "scenario note" in x]
        if says is None:
            assert notes == [], notes
            continue
        c2 = " ".join(x for x in notes if x.startswith(head + "model.C2 does not reach"))
        for row in says:  # each row once, with the key it reads instead
            assert c2.count(f"the {row} map (it reads torque_delay.") == 1, (row, c2)
        assert not any(row in c2 for row in not_says), c2
        assert any(x.startswith(head + "model.M2 does not reach") for x in notes) == (
            "report" in targets[0]
        )


def test_a_bad_scenario_does_not_block_a_good_one(tmp_path):
    """Another scenario's bad name is a warning naming it; the good one's page plans."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    (work / "config" / "scenarios.yaml").write_text(
        "ok_one: {model: {M2: 0.35}}\n'a b': {model: {M2: 0.4}}\n"
    )
    done = run_snakemake("report/scenarios/ok_one/index.html", work, "-n")
    assert done.returncode == 0, done.stderr[-2000:]
    lines = [
        x
        for x in done.stderr.splitlines()
        if x.startswith("tennis-stroke") and "scenario note" not in x  # M2: not Figs. 5-6
    ]
    assert len(lines) == 1 and "scenario warning: scenario name 'a b'" in lines[0], lines


def test_a_yaml_syntax_error_in_the_config_names_file_and_line(tmp_path):
    """Snakemake's own message names neither; the workflow reads the file first."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    path = work / "config" / "config.yaml"
    lines = path.read_text().splitlines()
    lines.insert(2, "  broken: a: b")
    path.write_text("\n".join(lines) + "\n")
    done = run_snakemake("report", work, "-n")
    assert done.returncode == 1
    out = done.stderr.strip().splitlines()
    assert len(out) == 1, out
    assert out[0].startswith("tennis-stroke config error: config/config.yaml, line 3, column")
    assert "YAML syntax error" in out[0]


#: The chunked rows of the table (their chunk jobs are the costly simulations).
MAP_RULES = {e.rule for e in EXPERIMENTS.values() if e.chunks}
INFERENCE_RULES = {
    "identification",
    "robustness_screen",
    "robustness_chunk",
    "claims_validation",
    "model_ladder",
}


def planned_after_edit(moved, module: str, old: str | None = None, new: str = "") -> set:
    """The rules a dry run plans after editing package ``module`` of the moved checkout
    (``old`` replaced by ``new``, else a comment appended); the file is restored."""
    path = moved.snakefile.parents[1] / "src" / "tennis_stroke" / module
    text, stat = path.read_text(), path.stat()
    path.write_text(text.replace(old, new) if old else text + "# edited\n")
    try:
        done = moved("-n")
    finally:
        path.write_text(text)
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert done.returncode == 0, done.stderr[-2000:]
    return set(planned_jobs(done.stdout + done.stderr))


def test_an_edit_of_the_identification_reruns_only_inference_claims_and_report(moved):
    planned = planned_after_edit(moved, "inference/identification.py")
    assert planned == {*INFERENCE_RULES, "gather_map", "claims", "figure", "report_page", "report"}


def test_a_step_of_fig9_reruns_fig9_its_check_claims_and_report_only(moved):
    """The claims' searches read no map step (targeted_config), and the validation job
    of each group only its rows' keys; a --config merge reorders keys, which must not
    look like a change (params compare by repr)."""
    done = moved("-n", "--config", "torque_delay={fig9: {tau: {step: 0.02}}}")
    assert done.returncode == 0, done.stderr[-2000:]
    planned = planned_jobs(done.stdout + done.stderr)
    assert set(planned) == {
        "fig9",
        "gather_map",
        "claims_validation",
        "claims",
        "figure",
        "report_page",
        "report",
    }
    assert planned["claims_validation"] == 1 and planned["gather_map"] == 1


def test_an_edit_of_the_figures_reruns_the_figures_and_the_report_only(moved):
    assert planned_after_edit(moved, "replication/figures.py") == {
        "figure",
        "report_page",
        "report",
    }


def test_an_edit_of_the_report_template_reruns_the_report(moved):
    """The page's template is the report's code although no module imports it."""
    assert planned_after_edit(moved, "replication/templates/report.html.j2") == {
        "report_page",
        "report",
    }


def test_a_new_long_name_reruns_no_map_chunk_and_no_inference_job(moved):
    """The chunks of a map leave their labels to gather_map; the rows that write their
    file in one job write the labels themselves and rerun."""
    planned = planned_after_edit(moved, "io/units.py", "rebound speed of the ball", "speed")
    assert not planned & (MAP_RULES | INFERENCE_RULES), planned
    unchunked = {e.rule for e in EXPERIMENTS.values() if not e.chunks}
    assert {"gather_map", "claims", "report", *unchunked} <= planned


def test_an_edit_of_a_solver_module_reruns_every_simulation(moved):
    """The other way round: the code inputs do follow the compiled solver."""
    planned = planned_after_edit(moved, "solver/integrate.py")
    model_rows = {e.rule for e in EXPERIMENTS.values() if e.model}
    assert model_rows | INFERENCE_RULES <= planned


@pytest.mark.parametrize("lost", ["results/claims.csv", "results/strokes/fig4.nc"])
def test_snakemake_report_rebuilds_a_result_lost_by_hand(moved, lost):
    """Snakemake alone said "Nothing to be done" for a lost intermediate file
    (snakemake/snakemake#1978): the target rule report names every result as an input
    and has no output of its own, so `snakemake -j2 report` plans the lost file's job."""
    path = moved.work / lost
    saved, stat = path.read_bytes(), path.stat()
    path.unlink()
    try:
        done = moved("-n")
    finally:
        path.write_bytes(saved)
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert done.returncode == 0, done.stderr[-2000:]
    planned = set(planned_jobs(done.stdout + done.stderr))
    producer = {"results/claims.csv": "claims", "results/strokes/fig4.nc": "fig4"}[lost]
    assert {producer, "claims", "report_page", "report"} <= planned, planned


def test_equal_values_spelled_differently_plan_no_job(moved):
    """C2: 5 for 5.0, and a section's keys in another order, planned 33 jobs: the config
    is put in one spelling before it becomes params (pipeline.config_check.canonical)."""
    tiny = yaml.safe_load((moved.work / "config" / "config.yaml").read_text())
    section = tiny["torque_delay"]
    section["base_stroke"]["C2"] = int(section["base_stroke"]["C2"])
    reordered = dict(reversed(list(section.items())))
    solver = {"atol": 5.0e-8, "rtol": 5e-08, "method": "DOP853"}  # the defaults, reordered
    assert "solver" not in tiny
    done = moved("-n", "--config", override("torque_delay", reordered), override("solver", solver))
    output = done.stdout + done.stderr
    assert done.returncode == 0 and planned_jobs(output) == {}, output[-3000:]


def test_a_truncated_result_is_named_before_any_job(moved):
    """Snakemake takes a truncated file for up to date (every run failed with 'NetCDF:
    HDF error' and deleted the claims table): the workflow names it and the way out."""
    path = moved.work / "results" / "torque_delay" / "fig9.nc"
    saved, stat = path.read_bytes(), path.stat()
    path.write_bytes(saved[: len(saved) // 2])
    try:
        done = moved("-n")
    finally:
        path.write_bytes(saved)
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert done.returncode == 1 and "Traceback" not in done.stderr
    lines = [line for line in done.stderr.splitlines() if "tennis-stroke" in line]
    assert lines == [
        f"tennis-stroke results error: results/torque_delay/fig9.nc is damaged (truncated "
        f"({len(saved) // 2} of its {len(saved)} bytes)): remove it and make it with: "
        "snakemake -j2 results/torque_delay/fig9.nc"
    ]


def test_a_checkout_under_a_folder_with_a_space_runs_its_jobs(tmp_path):
    """Snakemake runs a script job as `{python} {script}` without quoting the
    interpreter's path: under "my dir" every job died with 'bash: .../my: No such file or
    directory' (status 127).  The checkout is reached through a folder whose name has a
    space, a non-ASCII letter and a quote; its interpreter runs one job."""
    from tiny import TINY, TINY_READINGS

    python = Path(sys.executable)
    if not python.is_relative_to(ROOT):
        pytest.skip(f"the interpreter {python} is not in the checkout (make install puts it there)")
    odd = tmp_path / "my dir é 'q' \"x\""
    odd.mkdir()
    (odd / "tennis").symlink_to(ROOT)
    work = workdir(tmp_path / "work", TINY, TINY_READINGS)
    command = [
        str(odd / "tennis" / python.relative_to(ROOT)),
        "-m",
        "snakemake",
        "-f",
        "results/strokes/fig4.nc",
        "-s",
        str(odd / "tennis" / "workflow" / "Snakefile"),
        "--directory",
        str(work),
        "--cores",
        "1",
    ]
    done = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    assert (work / "results" / "strokes" / "fig4.nc").stat().st_size > 0


def test_a_differing_installed_copy_is_refused_before_any_job(tiny_run, tmp_path):
    """With `pip install .` the jobs import the copy in site-packages: an edit of the
    checkout reran jobs that then ran the unedited copy.  A copy that differs from the
    checkout is refused in one line before any job (a dry run only warns)."""
    copy = tmp_path / "site" / "tennis_stroke"
    shutil.copytree(
        ROOT / "src" / "tennis_stroke", copy, ignore=shutil.ignore_patterns("__pycache__")
    )
    (copy / "replication" / "figures.py").write_text(
        (copy / "replication" / "figures.py").read_text() + "# an older copy\n"
    )
    env = {**os.environ, "PYTHONPATH": str(copy.parent)}
    command = snakemake_command("report", tiny_run, "--cores", "1")
    done = subprocess.run(command, capture_output=True, text=True, timeout=600, env=env)
    lines = [line for line in done.stderr.splitlines() if "tennis-stroke" in line]
    assert done.returncode == 1 and "Traceback" not in done.stderr, done.stderr[-2000:]
    assert lines == [
        f"tennis-stroke error: the jobs would import the tennis_stroke installed at "
        f"{str(copy)!r}, whose replication/figures.py differs from this checkout's: install "
        "the checkout editable (make install, or pip install -e .)"
    ]
    dry = subprocess.run([*command, "-n"], capture_output=True, text=True, timeout=600, env=env)
    assert dry.returncode == 0 and "tennis-stroke warning: the jobs would import" in dry.stderr


#: The line a failed or stopped run says when it puts earlier results back.
PUT_BACK = (
    "tennis-stroke: 1 earlier result(s) put back until their jobs complete (dated 1970, so "
    "they run again): "
)


def test_a_failed_job_leaves_the_earlier_result_until_the_new_one_is_made(tmp_path):
    """Snakemake removes a job's output when it starts the job, so a job that failed lost
    the earlier file (issue 56, 6).  The failed run puts it back, dated 1970: the next
    plan runs its job again, and the file is the earlier one until then."""
    work = workdir(tmp_path, TINY, TINY_READINGS)
    target = "results/torque_delay/fig9.nc"
    first = run_snakemake(target, work, "--cores", "1", timeout=600)
    assert first.returncode == 0, first.stderr[-3000:]
    earlier = (work / target).read_bytes()
    config = work / "config" / "config.yaml"
    config.write_text(yaml.safe_dump({**TINY, "solver": {"t_max": 0.05}}))  # strokes fail
    failed = run_snakemake(target, work, "--cores", "1", timeout=600)
    assert failed.returncode != 0 and "FailureShareError" in failed.stderr
    assert (work / target).read_bytes() == earlier
    assert (work / target).stat().st_mtime == 0
    assert PUT_BACK + target in failed.stderr.splitlines()
    plan = run_snakemake(target, work, "-n")
    assert plan.returncode == 0 and "gather_map" in planned_jobs(plan.stdout + plan.stderr)
    config.write_text(yaml.safe_dump(TINY))
    again = run_snakemake(target, work, "--cores", "1", timeout=600)
    assert again.returncode == 0, again.stderr[-3000:]
    assert (work / target).stat().st_mtime > 0 and PUT_BACK not in again.stderr
    assert_nothing_kept(work)
    # the kept copies stayed in .snakemake: --delete-all-output freed nothing of them
    deleted = run_snakemake("report", work, "--delete-all-output", "--cores", "1")
    assert deleted.returncode == 0, deleted.stderr[-3000:]
    assert not [p for p in (work / "results").rglob("*") if p.is_file()]


def assert_nothing_kept(work):
    """A run that ended leaves no earlier file of its own (pipeline.earlier) and no copy
    of a result in Snakemake's folder."""
    assert not list(work.rglob("*.earlier"))
    snakemake = work / ".snakemake"
    assert not list(snakemake.glob("tennis-stroke-kept*")) and not (snakemake / "backups").exists()


@pytest.mark.parametrize(
    "signum, line", [(signal.SIGINT, "interrupted"), (signal.SIGTERM, "terminated")]
)
def test_a_signal_while_a_job_writes_stops_the_run_and_keeps_the_earlier_result(
    tiny_run, tmp_path_factory, signum, line
):
    """Ctrl-C (SIGINT to the whole run) or SIGTERM while a job writes its file (here the
    work-precision study's gathering, paused inside its write:
    ``tests/pause/sitecustomize.py``): the job finishes the write with the signal
    deferred, removes its temporary, ends with one line, and Snakemake stops; nothing
    hangs and no job outlives the run.  The issue's case: the stopped job took
    results/solver_study/work_precision.nc with it; now the stopped run puts the earlier
    file back, dated 1970, and plans its job again.  From a copy of the tiny run."""
    # a copy at the same depth: the code inputs' relative paths stay the same
    work = tmp_path_factory.mktemp("signal")
    shutil.copytree(tiny_run, work, symlinks=True, dirs_exist_ok=True)
    target = "results/solver_study/work_precision.nc"
    earlier = (work / target).read_bytes()
    chunks = sorted((work / "results/chunks/solver_study/work_precision").glob("*.nc"))
    inputs = [p.read_bytes() for p in chunks]
    pause = 3.0
    run = paused_write(target, work, pause)
    try:
        assert not (work / target).exists()  # removed by Snakemake when the job started
        os.killpg(run.pid, signum)
        start = time.monotonic()
        _, stderr = run.communicate(timeout=120)
    finally:
        if run.poll() is None:
            os.killpg(run.pid, signal.SIGKILL)
    # Nothing hangs.  That the write goes on with the signal deferred is shown by
    # tests/io/test_interrupts.py in one process: here a lower bound on the wait failed
    # on loaded machines (0.82 s against a 3 s pause, CI 2026-12-02), as the test cannot
    # tell when the job's pause began.
    assert time.monotonic() - start < pause + 10
    assert run.returncode != 0 and "Traceback" not in stderr
    assert f"tennis-stroke job {line}" in stderr
    assert not list(work.rglob("*.tmp"))
    assert [p.read_bytes() for p in chunks] == inputs  # the job's inputs are untouched
    left = subprocess.run(["pgrep", "-s", str(run.pid)], capture_output=True, text=True)
    assert left.stdout.split() == []  # no job outlives the run
    assert (work / target).read_bytes() == earlier
    assert (work / target).stat().st_mtime == 0
    assert PUT_BACK + target in stderr.splitlines(), stderr[-2000:]
    assert_nothing_kept(work)
    plan = run_snakemake(target, work, "-n")
    assert plan.returncode == 0 and "gather_map" in planned_jobs(plan.stdout + plan.stderr)
