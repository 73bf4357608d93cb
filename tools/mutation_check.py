"""Mutation check: does a deliberately wrong version of a central function fail a test?

Usage: ``python tools/mutation_check.py [--only NAME ...] [--list]``

Each mutant of :data:`MUTANTS` is one text substitution in one source file: the claims'
rule (:func:`tennis_stroke.inference.claims.within`), a claim's measurement
(:func:`~tennis_stroke.inference.claims.measure`), the config's checks
(:func:`tennis_stroke.pipeline.config_check.config_errors`, and how a refusal reaches
the Snakefile) and the compiled solver's event location
(:func:`tennis_stroke.solver.integrate.locate_event`).  For each, the tests it names run
(``pytest -m "not slow"``, or all of them where a mutant needs a real process) on a copy
of the package that holds the mutant, and the table printed at the end says which tests
failed: "survived" where none did.  The
unmutated copy runs the same tests first; a test that fails there is reported and not
counted as a kill.

The working tree is never written: the package (``src/tennis_stroke``) is copied to a
temporary folder, which the pytest subprocess finds first (``PYTHONPATH``), and the
folder is removed at the end, on Ctrl-C and on SIGTERM too (the running pytest is
stopped first).  numba compiles the copy into a temporary ``NUMBA_CACHE_DIR``, one
folder per hash of the compiled sources (:func:`tennis_stroke._cache.source_hash`, as
the package itself does): numba keys its cache by each function's own file only, and
:func:`~tennis_stroke.solver.integrate.locate_event` is inlined into the compiled stroke
of another module, which would load unmutated from a shared folder.  The mutants of
uncompiled modules share the unmutated copy's folder; a mutant of a compiled module
recompiles the solver (a few minutes on two cores).  The user's cache is neither used
nor polluted.

A mutant whose text no longer occurs exactly once in its file is an error: the function
changed, and the mutant must be written again.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "tennis_stroke"

#: The tests each function's mutants run: those that call it, directly or through the
#: claims table, the robustness analysis and the ladder (within, measure), or the
#: compiled stroke (locate_event).
CLAIM_TESTS = (
    "tests/inference/test_claim_values.py",
    "tests/inference/test_claims_check.py",
    "tests/inference/test_robustness.py",
    "tests/inference/test_ladder.py",
    "tests/inference/test_validation.py",
    "tests/replication/test_claims.py",
)
SOLVER_TESTS = (
    "tests/solver/test_stroke.py",
    "tests/solver/test_integrate.py",
)
#: The config's checks: every bad case in-process, and the one Snakemake process that
#: shows a refusal reaching the user (slow: the mutants that name it run the slow tier).
#: The test of a damaged compile cache (a real process: it heals in a compile of its own).
DAMAGED_CACHE_TEST = (
    "tests/solver/test_warmup.py::test_a_damaged_cache_is_cleared_and_compiled_again_in_one_line"
)
CONFIG_TESTS = ("tests/workflow/test_config_check.py", "tests/workflow/test_scenarios.py")


@dataclass(frozen=True)
class Mutant:
    """``old`` replaced by ``new`` in ``path`` (below the package): what ``what`` says."""

    name: str
    what: str
    path: str
    old: str
    new: str
    tests: tuple[str, ...]
    #: The tests' marker expression (``pytest -m``): the fast tier unless a mutant needs
    #: a test only a real process shows.
    marker: str = "not slow"


MUTANTS = (
    Mutant(
        "within_strict",
        "within: < instead of <= (the bound excluded)",
        "inference/claims.py",
        "np.abs(value - paper) <= np.asarray(tolerance)",
        "np.abs(value - paper) < np.asarray(tolerance)",
        CLAIM_TESTS,
    ),
    Mutant(
        "within_double_tolerance",
        "within: twice the tolerance",
        "inference/claims.py",
        "np.abs(value - paper) <= np.asarray(tolerance)",
        "np.abs(value - paper) <= 2 * np.asarray(tolerance)",
        CLAIM_TESTS,
    ),
    Mutant(
        "within_no_abs",
        "within: the signed difference (abs dropped)",
        "inference/claims.py",
        "np.abs(value - paper) <= np.asarray(tolerance)",
        "(value - paper) <= np.asarray(tolerance)",
        CLAIM_TESTS,
    ),
    Mutant(
        "measure_no_abs",
        "measure: the 'abs' of a variable measure ignored",
        "inference/claims.py",
        'return np.abs(value) if spec.get("abs") else value',
        "return value",
        CLAIM_TESTS,
    ),
    Mutant(
        "measure_wrong_variable",
        "measure: the file's first variable, not the one named",
        "inference/claims.py",
        'stack, var = files[spec["file"]], spec["var"]',
        'stack, var = files[spec["file"]], files[spec["file"]].data_vars[0]',
        CLAIM_TESTS,
    ),
    Mutant(
        "measure_off_by_one",
        "measure: the selection one position lower",
        "inference/claims.py",
        "value = pick(value, 1 + dims.index(dim), index)",
        "value = pick(value, 1 + dims.index(dim), index - 1)",
        CLAIM_TESTS,
    ),
    Mutant(
        "config_semantic_checks_dropped",
        "config_errors: the checks after the schema dropped (bounds, grids, the points bound)",
        "pipeline/config_check.py",
        "return errors or list(_semantic_errors(config)) or list(points_errors(config, readings))",
        "return errors",
        CONFIG_TESTS,
    ),
    Mutant(
        "config_refusal_uncaught",
        "checked_config: a refused config raised as a bare ValueError (the Snakefile's "
        "handler misses it: a traceback, not one line)",
        "pipeline/runs.py",
        'raise PlanningError("config", errors[0])',
        "raise ValueError(errors[0])",
        ("tests/workflow/test_config_check.py",),
        marker="",
    ),
    Mutant(
        "scenario_changing_nothing_accepted",
        "changing_config: a scenario that changes nothing of the paper's accepted",
        "pipeline/scenarios.py",
        "if not changes(_complete(base, loaded), _complete(config, loaded)):",
        "if False:",
        (
            "tests/workflow/test_workflow_failsafe.py::test_a_bad_scenario_is_one_line_before_any_job",
        ),
        marker="",
    ),
    Mutant(
        "scenario_reuses_nothing",
        "resolved_results: a scenario computes its own copy of every paper file, also "
        "those its overrides do not reach",
        "pipeline/scenarios.py",
        "key: scenario_path(path, name) if key in changed else path",
        "key: scenario_path(path, name)",
        CONFIG_TESTS,
    ),
    Mutant(
        "gather_in_file_order",
        "gather_chunks: the chunks concatenated in the order given, not their chunk order",
        "pipeline/chunks.py",
        '    parts.sort(key=lambda p: int(p.attrs["chunk_index"]))\n',
        "",
        ("tests/workflow/test_chunking.py",),
    ),
    Mutant(
        "deferred_signal_swallowed",
        "deferred_signals: a signal received during a write not raised again (the job "
        "goes on after Ctrl-C)",
        "io/interrupts.py",
        "        signal.raise_signal(received[0])\n",
        "        pass\n",
        (
            "tests/workflow/test_workflow_failsafe.py::"
            "test_a_signal_while_a_job_writes_stops_the_run_and_keeps_the_earlier_result",
        ),
        marker="",
    ),
    Mutant(
        "unwritable_folder_passed",
        "unwritable_folders: a folder the planned jobs cannot write passed (a job's "
        "traceback instead of one line before any job)",
        "pipeline/checkout.py",
        "        if why:\n            problems.setdefault(why, []).extend(files)\n",
        "        if False:\n            problems.setdefault(why, []).extend(files)\n",
        (
            "tests/workflow/test_one_run.py",
            "tests/workflow/test_workflow_failsafe.py::"
            "test_a_figure_no_rule_makes_or_no_folder_takes_is_one_line_naming_it",
        ),
        marker="",
    ),
    Mutant(
        "cache_damage_raised",
        "_load: a cache file numba cannot read raised, not cleared and compiled again "
        "(a traceback on every call)",
        "solver/compiled.py",
        "        if not _cache_trouble(exc):\n            raise\n",
        "        if True:\n            raise\n",
        (DAMAGED_CACHE_TEST,),
        marker="",
    ),
    Mutant(
        "cache_compile_in_place_allowed",
        "_load: numba let compile in place where the cache lacks an entry point (the bits "
        "of a compile in place, said nowhere)",
        "solver/compiled.py",
        "    try:\n        with refusing_compiles():\n            exercise()\n        return\n",
        "    try:\n        exercise()\n        return\n",
        (DAMAGED_CACHE_TEST,),
        marker="",
    ),
    Mutant(
        "locate_event_step_end",
        "locate_event: the step's end, not the root",
        "solver/integrate.py",
        "            if gx == 0.0:\n                break\n    return hi\n",
        "            if gx == 0.0:\n                break\n    return 1.0\n",
        SOLVER_TESTS,
    ),
    Mutant(
        "locate_event_linear",
        "locate_event: the event value interpolated linearly over the step (no iteration)",
        "solver/integrate.py",
        "    side = 0\n    for _ in range(EVENT_MAX_ITER):\n",
        "    side = 0\n    hi = glo / (glo - ghi)\n    for _ in range(0):\n",
        SOLVER_TESTS,
    ),
    Mutant(
        "locate_event_early_stop",
        "locate_event: four iterations at most (was 60)",
        "solver/integrate.py",
        "    for _ in range(EVENT_MAX_ITER):\n",
        "    for _ in range(4):\n",
        SOLVER_TESTS,
    ),
    Mutant(
        "locate_event_one_fewer",
        "locate_event: one iteration fewer at most (59)",
        "solver/integrate.py",
        "    for _ in range(EVENT_MAX_ITER):\n",
        "    for _ in range(EVENT_MAX_ITER - 1):\n",
        SOLVER_TESTS,
    ),
)


class Interrupted(Exception):
    """SIGTERM: stop as Ctrl-C does (the temporary folder is removed)."""


def _on_sigterm(signum, frame):
    raise Interrupted


def _stop(proc: subprocess.Popen) -> None:
    """Stop ``proc`` and the processes of its session (SIGTERM, then SIGKILL)."""
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        pass
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()


def _copy_run(src: Path, expression: str) -> str:
    """``expression`` (of the module ``tennis_stroke``, its ``_cache`` imported) evaluated
    in a new process that imports the package's copy at ``src``."""
    code = (
        f"import tennis_stroke\nfrom tennis_stroke import _cache\nprint(tennis_stroke.{expression})"
    )
    env = {**os.environ, "PYTHONPATH": str(src)}
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    if done.returncode != 0 or not done.stdout.strip():
        raise SystemExit(f"the package's copy does not import: {done.stderr.strip()[-500:]}")
    return done.stdout.strip()


def run_tests(
    tests: tuple[str, ...], src: Path, work: Path, marker: str = "not slow"
) -> tuple[set[str], str]:
    """Run ``tests`` (those ``marker`` selects; "": all) with the package at ``src``
    first on the path: the ids of the tests that failed (collection errors included), and
    "" or why the run itself broke."""
    report = work / "junit.xml"
    report.unlink(missing_ok=True)
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(src), os.environ.get("PYTHONPATH", "")]),
        "PYTHONDONTWRITEBYTECODE": "1",  # a mutant as long as the original, written
    }  # within the second, would load the other's bytecode
    env["NUMBA_CACHE_DIR"] = str(work / "numba" / _copy_run(src, "_cache.source_hash()"))
    command = [sys.executable, "-m", "pytest", "-q", *(["-m", marker] if marker else [])]
    command += ["-p", "no:cacheprovider", f"--junitxml={report}", *tests]
    # A session of its own: an interrupt stops pytest and every process it started
    # (they write into the temporary folder) before the folder is removed.
    proc = subprocess.Popen(
        command,
        cwd=ROOT,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    try:
        out, _ = proc.communicate()
    except BaseException:
        _stop(proc)
        raise
    if proc.returncode not in (0, 1) or not report.exists():
        return set(), f"pytest exit {proc.returncode}: {out.strip().splitlines()[-1:]}"
    failed = set()
    for case in ET.parse(report).iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            module = case.get("classname", "").rpartition(".")[2]
            failed.add(f"{module}.py::{case.get('name')}")
    return failed, ""


def apply(mutant: Mutant, src: Path) -> str:
    """Write ``mutant`` into the copy at ``src``; returns the original text."""
    path = src / "tennis_stroke" / mutant.path
    text = path.read_text()
    if text.count(mutant.old) != 1:
        raise SystemExit(
            f"{mutant.name}: its text occurs {text.count(mutant.old)} times in "
            f"{mutant.path} (must be once): write the mutant again"
        )
    path.write_text(text.replace(mutant.old, mutant.new))
    return text


def check(mutants: list[Mutant]) -> list[tuple[Mutant, set[str], str]]:
    """Run every mutant's tests on the unmutated copy, then on each mutant."""
    rows = []
    with tempfile.TemporaryDirectory(prefix="mutation-check-") as tmp:
        work = Path(tmp)
        src = work / "src"
        shutil.copytree(
            PACKAGE, src / "tennis_stroke", ignore=shutil.ignore_patterns("__pycache__")
        )
        for m in mutants:  # the texts first: a stale mutant fails before any run
            (src / "tennis_stroke" / m.path).write_text(apply(m, src))
        found = _copy_run(src, "__file__")
        if Path(found).parent != src / "tennis_stroke":
            raise SystemExit(f"the copy is not the package pytest imports ({found})")
        baseline: dict[tuple[tuple[str, ...], str], set[str]] = {}
        for tests, marker in dict.fromkeys((m.tests, m.marker) for m in mutants):
            print(f"unmutated: {len(tests)} test files ({marker or 'all'}) ...", flush=True)
            key = (tests, marker)
            baseline[key], broke = run_tests(tests, src, work, marker)
            if broke or baseline[key]:
                print(f"  fails unmutated ({broke or ', '.join(sorted(baseline[key]))})")
        for m in mutants:
            print(f"{m.name}: {m.what} ...", flush=True)
            original = apply(m, src)
            try:
                failed, broke = run_tests(m.tests, src, work, m.marker)
            finally:
                (src / "tennis_stroke" / m.path).write_text(original)
            killed = failed - baseline[(m.tests, m.marker)]
            print(f"  killed by {len(killed)} tests" if killed else f"  survived {broke}")
            rows.append((m, killed, broke))
    return rows


def _tests(ids: set[str]) -> str:
    """Test ids as ``file::function`` (how many of its parameter sets failed, if several)."""
    count: dict[str, int] = {}
    for i in sorted(ids):
        count[i.partition("[")[0]] = count.get(i.partition("[")[0], 0) + 1
    return ", ".join(f"`{t}`" + (f" ({n})" if n > 1 else "") for t, n in count.items())


def table(rows: list[tuple[Mutant, set[str], str]]) -> str:
    """A Markdown table: mutant, what it changes, the tests that failed."""
    lines = ["| mutant | what it changes | killed by |", "| --- | --- | --- |"]
    for m, killed, broke in rows:
        by = _tests(killed) or f"**survived** {broke}".strip()
        lines.append(f"| `{m.name}` | {m.what} | {by} |")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="+", metavar="NAME", help="these mutants only")
    parser.add_argument("--list", action="store_true", help="list the mutants and stop")
    args = parser.parse_args()
    known = {m.name: m for m in MUTANTS}
    unknown = sorted(set(args.only or ()) - set(known))
    if unknown:
        parser.error(f"unknown mutant(s) {', '.join(unknown)} (known: {', '.join(known)})")
    mutants = [known[n] for n in args.only] if args.only else list(MUTANTS)
    if args.list:
        print("\n".join(f"{m.name}: {m.what} ({m.path})" for m in mutants))
        return 0
    signal.signal(signal.SIGTERM, _on_sigterm)
    signal.signal(signal.SIGINT, signal.default_int_handler)  # also when started with &
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    ).stdout.strip()
    try:
        rows = check(mutants)
    except (KeyboardInterrupt, Interrupted):
        print("interrupted: nothing to restore, the working tree was never written")
        return 130
    print(f"\nMutation check, {datetime.date.today()}, commit {commit}:\n")
    print(table(rows))
    return 1 if any(not killed for _, killed, _ in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
