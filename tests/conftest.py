"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

import re
import shutil
import signal
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke.io.compare import result_differences
from tennis_stroke.model.dynamics import coefficients
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver._kernels import coefficient_tuple

#: The two strokes of the paper's Fig. 4: (theta0, delta0) in degrees.
FIG4_A = (120.0, 81.5)
FIG4_B = (75.0, 39.0)


def pytest_configure(config):
    """A test run started in the background by a shell without job control (``nohup cmd
    &``) inherits SIGINT ignored, and so would every process it starts: the tests of
    Ctrl-C need Python's default handling, which a user's terminal gives."""
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


#: Fixtures that run the workflow: a test using one is slow.
WORKFLOW_FIXTURES = ("tiny_run", "moved")


def pytest_collection_modifyitems(items):
    """Tests on a workflow run are marked slow: ``pytest -m "not slow"`` is the quick loop
    while editing (``make test`` runs everything)."""
    for item in items:
        if set(WORKFLOW_FIXTURES) & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)


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


ROOT = Path(__file__).resolve().parents[1]


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
        str(ROOT / "Snakefile"),
        "--directory",
        str(workdir),
        *options,
    ]


def run_snakemake(targets, workdir, *options, timeout=300):
    """Run :func:`snakemake_command`; returns the completed process."""
    command = snakemake_command(targets, workdir, *options)
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)


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


@pytest.fixture(scope="session")
def tiny_run(tmp_path_factory):
    """The whole workflow run once on the tiny configuration (tests/tiny.py); shared by the
    workflow, report and file-format tests."""
    from tiny import TINY, TINY_READINGS

    work = workdir(tmp_path_factory.mktemp("workflow"), TINY, TINY_READINGS)
    done = run_snakemake("report", work, "--cores", "2", timeout=1200)
    assert done.returncode == 0, done.stderr[-3000:]
    return work


@dataclass(frozen=True)
class Plan:
    """What a dry run plans: its jobs as (rule, input files, output files), and the
    names of every rule of the workflow."""

    jobs: list[tuple[str, list[str], list[str]]]
    rules: list[str]

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
    return Plan(planned_jobs(done.stdout + done.stderr), listed.stdout.split())


def record_configuration(folder, scenario=None, departures=()) -> None:
    """The record the claims job writes beside a claims table in ``folder``: the paper's
    configuration unless a ``scenario`` or ``departures`` are given."""
    from tennis_stroke.inference.paper_config import RECORD_NAME, write_record

    record = {"scenario": scenario, "departures": list(departures)}
    write_record(record, Path(folder) / RECORD_NAME)
