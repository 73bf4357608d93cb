"""The workflow through SLURM: a single-node cluster on localhost (tools/slurm/) runs a
small configuration with profiles/slurm, and every file equals a local run's.

Needs Debian's slurm-wlm and munge (``tools/slurm/localhost_slurm.sh install``, root);
skips with the reason where they cannot be installed or started.
"""

import os
import subprocess
import time
from pathlib import Path

import pytest
from conftest import ROOT, assert_same_results, result_files, run_snakemake, workdir
from tiny import TINY

#: One worker runs the module (its two tests share the SLURM run of the module fixture).
pytestmark = [pytest.mark.slurm, pytest.mark.xdist_group("slurm")]

SCRIPT = ROOT / "tools" / "slurm" / "localhost_slurm.sh"
#: The cluster's run directory, as in localhost_slurm.sh.
RUN_DIR = Path(os.environ.get("TENNIS_STROKE_SLURM_DIR", "/tmp/tennis-stroke-slurm"))
#: A map gathered from two chunk jobs and a single-chunk map: few jobs, as each SLURM
#: job starts Snakemake twice (about 10 s here).
TARGETS = ["results/torque_delay/fig9.nc", "results/angle_maps/fig2.nc"]
CONFIG = {**TINY, "chunks": {"angle_map": 2}}
#: A hung run (e.g. job states that never arrive) is killed after this (s).
TIMEOUT_S = 600


def cluster(command: str) -> subprocess.CompletedProcess:
    """Run ``localhost_slurm.sh command`` (start, stop, status)."""
    return subprocess.run(
        [str(SCRIPT), command], capture_output=True, text=True, timeout=180, check=False
    )


@pytest.fixture(scope="module")
def slurm_cluster():
    """The localhost cluster, started here (and stopped afterwards) unless it already ran;
    yields with SLURM_CONF and PATH set for the clients (see localhost_slurm.sh env)."""
    already_running = cluster("status").returncode == 0
    started = cluster("start")
    if started.returncode != 0:
        lines = started.stderr.strip().splitlines() or [f"exit status {started.returncode}"]
        reason = lines[-1].removeprefix("localhost_slurm.sh: ")
        pytest.skip(f"no localhost SLURM cluster: {reason}")
    try:
        with pytest.MonkeyPatch.context() as env:
            env.setenv("SLURM_CONF", str(RUN_DIR / "etc" / "slurm.conf"))
            env.setenv("PATH", f"{RUN_DIR / 'bin'}{os.pathsep}{os.environ['PATH']}")
            yield
    finally:
        if not already_running:
            stopped = cluster("stop")
            assert stopped.returncode == 0, stopped.stderr


def timed_run(work: Path, *options: str) -> float:
    """Run the targets in ``work``; returns the wall time (s).  A run still going after
    TIMEOUT_S is killed (SIGKILL: a run waiting for job states ignores SIGTERM)."""
    start = time.perf_counter()
    try:
        done = run_snakemake(TARGETS, work, *options, timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        pytest.fail(
            f"snakemake {' '.join(options)} hung for {TIMEOUT_S} s and was killed; "
            f"job logs: {work / '.snakemake' / 'slurm_logs'}"
        )
    assert done.returncode == 0, done.stderr[-3000:]
    return time.perf_counter() - start


@pytest.fixture(scope="module")
def runs(slurm_cluster, tmp_path_factory):
    """The same targets run locally and through SLURM, in two working directories."""
    local = workdir(tmp_path_factory.mktemp("local"), CONFIG)
    slurm = workdir(tmp_path_factory.mktemp("slurm"), CONFIG)
    # Local first: it also compiles the solver if the numba cache is cold, so that the
    # SLURM jobs (same user, same environment, hence the same cache) find it compiled.
    local_s = timed_run(local, "--cores", "2")
    slurm_s = timed_run(
        slurm,
        "--profile",
        str(ROOT / "profiles" / "slurm"),
        "--workflow-profile",
        str(ROOT / "profiles" / "slurm-localhost"),
    )
    # Shown with pytest -s (the SLURM run's cost is mostly the plugin's polling).
    print(f"\nwall time: local (--cores 2) {local_s:.1f} s, SLURM {slurm_s:.1f} s")
    return {"local": local, "slurm": slurm, "local_s": local_s, "slurm_s": slurm_s}


def test_jobs_ran_through_slurm(runs):
    # The plugin writes one log per SLURM job (kept: slurm-keep-successful-logs).
    logs = sorted((runs["slurm"] / ".snakemake" / "slurm_logs").rglob("*.log"))
    rules = {log.relative_to(runs["slurm"] / ".snakemake" / "slurm_logs").parts[0] for log in logs}
    assert {"rule_fig2", "rule_fig9", "rule_gather_map"} <= rules, logs
    angle_chunks = runs["slurm"] / "results" / "chunks" / "angle_maps" / "fig2"
    assert sorted(p.name for p in angle_chunks.glob("*.nc")) == ["0-of-2.nc", "1-of-2.nc"]
    for log in logs:
        assert "Finished jobid" in log.read_text(), log


def test_slurm_results_equal_local_results(runs):
    files = result_files(runs["local"], chunks=True)
    assert set(TARGETS) <= set(files)
    assert result_files(runs["slurm"], chunks=True) == files
    for name in files:
        assert_same_results(runs["local"] / name, runs["slurm"] / name)
