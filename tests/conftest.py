"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

import fcntl
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke.io.compare import result_differences
from tennis_stroke.model.dynamics import coefficients
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver._kernels import coefficient_tuple
from tennis_stroke.solver.integrate import specialised

#: The two strokes of the paper's Fig. 4: (theta0, delta0) in degrees.
FIG4_A = (120.0, 81.5)
FIG4_B = (75.0, 39.0)


def pytest_configure(config):
    """A test run started in the background by a shell without job control (``nohup cmd
    &``) inherits SIGINT ignored, and so would every process it starts: the tests of
    Ctrl-C need Python's default handling, which a user's terminal gives."""
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    require_browser()


#: Set (to anything but empty) where the browser tests must run: a CI that installed
#: Chromium sets it, so that a missing browser fails the run instead of skipping them.
REQUIRE_BROWSER = "TENNIS_STROKE_REQUIRE_BROWSER"


def require_browser() -> None:
    """Stop the run in one line if :data:`REQUIRE_BROWSER` is set and Debian's Chromium
    or chromedriver is missing (the browser tests would skip silently)."""
    from chromium import CHROMIUM, DRIVER, MISSING

    if os.environ.get(REQUIRE_BROWSER) and (CHROMIUM is None or DRIVER is None):
        raise pytest.UsageError(
            f"{REQUIRE_BROWSER} is set and the browser tests cannot run: {MISSING}"
        )


#: Fixtures that run the workflow (or plan it): a test using one is a workflow test.
WORKFLOW_FIXTURES = ("tiny_run", "moved", "report_plan")
#: The kinds of test that ``make check`` leaves out, by their markers (pyproject.toml), in
#: the order a test's kind is named by (docs/testing.md, "Where the time goes").
SLOW_KINDS = ("slurm", "browser", "compile", "workflow", "signals", "process")
#: The order the kinds run in: the longest first (the first workflow test builds the
#: shared tiny run at once; the browser tests read it, so they come later; the tiny run's
#: build keeps both cores busy, docs/changes.md 2026-12-07).
RUN_ORDER = ("workflow", "slurm", "compile", "browser", "signals", "process", "unit")


def pytest_collection_modifyitems(items):
    """A test's kind: a test on a workflow fixture is a workflow test; every test of a
    kind of :data:`SLOW_KINDS` is also ``slow``, so ``pytest -m "not slow"`` (``make
    check``) runs the fast tier.  The kind goes into the JUnit report as the property
    ``kind`` (``tools/test_durations.py`` sums the durations by it)."""
    for item in items:
        fixtures = set(getattr(item, "fixturenames", ()))
        if set(WORKFLOW_FIXTURES) & fixtures:
            item.add_marker(pytest.mark.workflow)
        kinds = [k for k in SLOW_KINDS if item.get_closest_marker(k)]
        if kinds:
            item.add_marker(pytest.mark.slow)
        item.user_properties.append(("kind", kinds[0] if kinds else "unit"))
    # the long kinds first (a stable sort: each kind in its files' order), so the longest
    # tests start early on their worker and the short ones fill in at the end, instead of
    # a workflow run starting last beside an idle worker
    rank = {kind: n for n, kind in enumerate(RUN_ORDER)}
    items.sort(key=lambda item: rank[dict(item.user_properties)["kind"]])


@pytest.fixture(autouse=True)
def _raise_on_float_errors():
    """Floating-point warnings are errors in tests."""
    with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
        yield


def coefficient_row(theta0=90.0, delta0=30.0, **overrides):
    """One coefficient row (array) for the given angles and parameter overrides."""
    return coefficients(resolve_params(overrides), theta0, delta0)[0]


def coefficient_tup(theta0=90.0, delta0=30.0, **overrides):
    """The same as a tuple, as the compiled kernels take it."""
    return coefficient_tuple(coefficient_row(theta0, delta0, **overrides))


def swings_while(run):
    """``(strokes, swings)``: what the compiled solver was given and the swings it
    integrated while ``run()`` ran (``solver.stroke.swings_integrated``), its compiled
    code loaded before (the first load runs strokes of its own); and ``run()``'s result."""
    from tennis_stroke.solver.stroke import strike, swings_integrated

    strike(90.0, 45.0)
    before = swings_integrated()
    result = run()
    after = swings_integrated()
    return (after[0] - before[0], after[1] - before[1]), result


def by_entry(dispatcher):
    """``dispatcher(method, *args)`` called through its compiled entry for the argument
    types (``solver.integrate.specialised``, kept per types): the same machine code,
    without numba's literal dispatch, which compiles again at every call from Python
    (about 50 ms a call, most of a test that steps in a Python loop)."""
    import numba

    entries = {}

    def call(method, *args):
        key = (method, tuple(numba.typeof(a) for a in args))
        if key not in entries:
            entries[key] = specialised(dispatcher, method, *args)
        return entries[key](*args)

    return call


ROOT = Path(__file__).resolve().parents[1]
#: What a checkout needs to run the workflow (the package is imported from the
#: environment; its sources are the simulations' inputs).
CHECKOUT = ("workflow", "src", "docs")


def snakemake_command(targets, workdir, *options) -> list[str]:
    """Command line running this project's Snakefile on ``targets`` (a path or a list) in
    ``workdir``; targets come first, as options that take several values would swallow
    them."""
    targets = [targets] if isinstance(targets, str) else list(targets)
    snakemake = Path(sys.executable).with_name("snakemake")
    return [
        str(snakemake),
        *targets,
        "-s",
        str(ROOT / "workflow" / "Snakefile"),
        "--directory",
        str(workdir),
        *options,
    ]


def run_snakemake(targets, workdir, *options, timeout=300):
    """Run :func:`snakemake_command`; returns the completed process."""
    command = snakemake_command(targets, workdir, *options)
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)


def paused_write(target, workdir, pause: float, timeout: float = 300) -> subprocess.Popen:
    """Force ``target``'s job in ``workdir`` on one core, its write paused ``pause`` s
    (``tests/pause/sitecustomize.py``, on the jobs' PYTHONPATH), in a session of its own
    (``os.killpg`` signals the whole run), and return the running process once the job
    is inside its write (a ``.tmp`` file under ``results/``).  Fails, the run killed, if
    it ends before writing or writes nothing within ``timeout`` s."""
    path = os.pathsep.join(
        filter(None, [str(ROOT / "tests" / "pause"), os.environ.get("PYTHONPATH")])
    )
    run = subprocess.Popen(
        snakemake_command(target, workdir, "--cores", "1", "-f"),
        start_new_session=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": path, "TENNIS_STROKE_TEST_WRITE_PAUSE": str(pause)},
    )
    deadline = time.monotonic() + timeout
    try:
        while not list((Path(workdir) / "results").rglob("*.tmp")):
            assert run.poll() is None, "the run ended before its job wrote"
            assert time.monotonic() < deadline, f"no write after {timeout:g} s"
            time.sleep(0.01)
    except BaseException:
        if run.poll() is None:
            os.killpg(run.pid, signal.SIGKILL)
        raise
    return run


def work_precision_table(v_out, events, evals, failed, scenes=("contact",)):
    """A made-up work-precision table: the v_out and event-time errors, evaluations and
    failed strokes per (scene, method, setting), each array of that shape, the same for
    each of 3 strokes; methods compiled DOP853 and scipy RK45 at the settings 1e-4 and
    5e-8, the default DOP853 at 5e-8, the requirement 1e-4 km/h and 1e-6 s."""
    import xarray as xr

    dims = ("scene", "method", "setting", "stroke")
    shape = (len(scenes), 2, 2, 3)

    def per_stroke(values):
        return (dims, np.broadcast_to(np.asarray(values, dtype=float)[..., None], shape).copy())

    data = {
        "v_out_error": per_stroke(v_out),
        "event_time_error": per_stroke(events),
        "state_error": (dims, np.zeros(shape)),
        "rhs_evals": per_stroke(evals),
        "failed": (dims[:3], np.asarray(failed, dtype=float)),
    }
    coords = {
        "scene": list(scenes),
        "method": ["tennis_stroke.DOP853", "scipy.RK45"],
        "setting": [1e-4, 5e-8],
        "stroke": np.arange(3),
    }
    attrs = {
        "required_v_out_error_kmh": 1e-4,
        "required_event_time_error_s": 1e-6,
        "reference": "scipy DOP853, rtol = atol = 1e-13",
        "default_method": "tennis_stroke.DOP853",
        "default_setting": 5e-8,
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def assert_same_results(a, b, also_differ=()):
    """Two results (datasets or netCDF paths) are the same
    (:func:`tennis_stroke.io.compare.result_differences`)."""
    problems = result_differences(a, b, also_differ)
    assert not problems, "; ".join(problems)


def merged(base, update):
    """``base`` with the nested mapping ``update`` merged over it (a new dict)."""
    out = dict(base)
    for key, value in update.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merged(out[key], value)
        else:
            out[key] = value
    return out


def workdir(parent, config, readings=None):
    """A working directory for the Snakefile holding ``config``, the claims and the
    declared reading space (with ``readings`` merged over it)."""
    (parent / "config").mkdir(parents=True)
    (parent / "config" / "config.yaml").write_text(yaml.safe_dump(config))
    shutil.copy(ROOT / "config" / "claims.yaml", parent / "config" / "claims.yaml")
    space = yaml.safe_load((ROOT / "config" / "readings.yaml").read_text())
    text = yaml.safe_dump(merged(space, readings or {}), sort_keys=False)
    (parent / "config" / "readings.yaml").write_text(text)
    return parent


def result_files(work, chunks=False):
    """The paper's result files under ``work`` (relative paths, no scenario's); with
    ``chunks``, map chunks too."""
    return sorted(
        str(p.relative_to(work))
        for p in (work / "results").rglob("*.nc")
        if (chunks or "chunks" not in p.parts) and "scenarios" not in p.relative_to(work).parts
    )


def shared_folder(tmp_path_factory, name: str) -> Path:
    """A folder ``name`` that every pytest-xdist worker of this test run shares, at the
    depth of each worker's own temporary folders (a copy of it made by a test keeps the
    relative paths of its code inputs); without xdist, one in the run's own folder."""
    base = tmp_path_factory.getbasetemp()
    root = base.parent / "shared" if os.environ.get("PYTEST_XDIST_WORKER") else base
    return root / name


def built_once(folder: Path, build) -> Path:
    """``folder``, built by ``build(folder)`` by the first test process that asks for it
    (an xdist worker) while the others wait on a file lock and then reuse it.  A build
    that failed is not tried again: each asking process fails with its message."""
    folder.parent.mkdir(parents=True, exist_ok=True)
    done, failed = (folder.parent / f"{folder.name}.{s}" for s in ("done", "failed"))
    with open(folder.parent / f"{folder.name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if failed.exists():
            pytest.fail(failed.read_text(), pytrace=False)
        if not done.exists():
            try:
                build(folder)
            except BaseException as error:
                failed.write_text(f"building {folder.name} failed: {error}")
                raise
            done.touch()
    return folder


@pytest.fixture(scope="session")
def tiny_run(tmp_path_factory):
    """The whole workflow run once on the tiny configuration (tests/tiny.py), for the
    whole test run (every xdist worker reads the same run): shared by the workflow,
    report and file-format tests, which only read it.  A test that runs Snakemake in it
    is in the xdist group ``tiny_run`` (one worker at a time)."""
    from tiny import TINY, TINY_READINGS

    def build(folder):
        work = workdir(folder, TINY, TINY_READINGS)
        done = run_snakemake("report", work, "--cores", "2", timeout=1200)
        assert done.returncode == 0, done.stderr[-3000:]

    return built_once(shared_folder(tmp_path_factory, "workflow0"), build)


#: The scenario of :func:`tiny_scenario`: its name, its override and its page.
SCENARIO = ("strong", "scenarios={strong: {torque_delay: {base_stroke: {C2: 8.0}}}}")
SCENARIO_PAGE = "report/scenarios/strong/index.html"


def file_states(folder: Path) -> dict[str, list]:
    """Every file below ``folder`` with the SHA-256 of its bytes and its modification
    time (ns)."""
    return {
        str(p.relative_to(folder)): [
            hashlib.sha256(p.read_bytes()).hexdigest(),
            p.stat().st_mtime_ns,
        ]
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


@pytest.fixture(scope="session")
def tiny_scenario(tiny_run, tmp_path_factory):
    """A copy of the tiny run (at its depth, times kept) with the scenario of
    :data:`SCENARIO` run beside the paper (its page :data:`SCENARIO_PAGE`), once per test
    run: ``(folder, states)``, ``states`` the paper's ``results`` and ``report`` files
    before the scenario ran (:func:`file_states`)."""
    folder = shared_folder(tmp_path_factory, "scenario0")
    before = folder.parent / "scenario0.before.json"

    def build(work):
        shutil.copytree(tiny_run, work, symlinks=True)
        states = {top: file_states(work / top) for top in ("results", "report")}
        before.write_text(json.dumps(states))
        done = run_snakemake(
            SCENARIO_PAGE, work, "--cores", "2", "--config", SCENARIO[1], timeout=1200
        )
        assert done.returncode == 0, done.stderr[-3000:]

    built_once(folder, build)
    return folder, json.loads(before.read_text())


@dataclass(frozen=True)
class Plan:
    """What a dry run plans: its jobs as (rule, input files, output files), and the
    names of every rule of the workflow."""

    jobs: list[tuple[str, list[str], list[str]]]
    rules: list[str]
    #: Each job's ``resources:`` line as a mapping, by its first output (or its rule).
    resources: dict[str, dict[str, str]]

    def writers(self, path: str) -> list[str]:
        """The rules of the planned jobs that write ``path``."""
        return [rule for rule, _, outputs in self.jobs if path in outputs]


def planned_jobs(log: str) -> list[tuple[str, list[str], list[str]]]:
    """The jobs of a dry run's log (``snakemake -n``): each ``rule NAME:`` block with
    its ``input:`` and ``output:`` lines, split at ", "."""
    jobs = []
    for block in re.split(r"\n(?=(?:local)?rule \w+:\n)", log):
        head = re.match(r"(?:local)?rule (\w+):\n", block)
        if head:
            files = dict(re.findall(r"^    (input|output): (.*)$", block, re.M))
            split = [[f for f in files.get(k, "").split(", ") if f] for k in ("input", "output")]
            jobs.append((head[1], *split))
    return jobs


#: The rules that write the files of the table's rows (one rule per kind of job).
ROW_RULES = ("simulate", "simulate_chunk", "study")


def job_kind(rule: str, outputs: list[str]) -> str:
    """What a planned job is: for a job of a row of the table, the row's name (its
    ``rule`` field: ``fig9``, ``delay_strokes``), from the file it writes (a scenario's
    or a chunk's too); any other job, its rule."""
    if rule not in ROW_RULES:
        return rule
    from tennis_stroke.experiments.specs import EXPERIMENTS

    path = re.sub(r"^results/(scenarios/[^/]+/)?", "", outputs[0])
    stem = re.sub(r"^chunks/(.*)/\d+-of-\d+\.nc$", r"\1", path).removesuffix(".nc")
    (row,) = [e.rule for e in EXPERIMENTS.values() if e.stem == stem]
    return row


def planned_kinds(log: str) -> dict[str, int]:
    """The jobs of a dry run's log counted by :func:`job_kind` (empty: nothing to do)."""
    counts: dict[str, int] = {}
    for rule, _, outputs in planned_jobs(log):
        kind = job_kind(rule, outputs)
        counts[kind] = counts.get(kind, 0) + 1
    return counts


@pytest.fixture(scope="session")
def report_plan(tmp_path_factory) -> Plan:
    """A dry run of ``report`` on the shipped configuration in an empty working
    directory, so every job is planned; the workflow's own rules and file patterns, not
    the package's tables, say what it writes."""
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    work = workdir(tmp_path_factory.mktemp("plan"), config)
    done = run_snakemake("report", work, "-n")
    assert done.returncode == 0, done.stderr[-3000:]
    listed = run_snakemake([], work, "--list-rules")
    assert listed.returncode == 0, listed.stderr[-3000:]
    log = done.stdout + done.stderr
    return Plan(planned_jobs(log), listed.stdout.split(), planned_resources(log))


def planned_resources(log: str) -> dict[str, dict[str, str]]:
    """Each job of a dry run's log with its ``resources:`` line (``{name: value}``), by
    its first output, or its rule for a job without output."""
    out = {}
    for block in re.split(r"\n(?=(?:local)?rule \w+:\n)", log):
        head = re.match(r"(?:local)?rule (\w+):\n", block)
        if head:
            output = re.search(r"^    output: ([^,\n]*)", block, re.M)
            line = re.search(r"^    resources: (.*)$", block, re.M)
            pairs = (item.split("=", 1) for item in line[1].split(", ")) if line else ()
            out[output[1] if output else head[1]] = dict(pairs)
    return out


def record_configuration(folder, scenario=None, departures=()) -> None:
    """The record the claims job writes beside a claims table in ``folder``: the paper's
    configuration unless a ``scenario`` or ``departures`` are given."""
    from tennis_stroke.inference.paper_config import RECORD_NAME, write_record

    record = {"scenario": scenario, "departures": list(departures)}
    write_record(record, Path(folder) / RECORD_NAME)
