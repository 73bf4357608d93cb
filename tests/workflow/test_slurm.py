"""The workflow through SLURM: a single-node cluster on localhost (tools/slurm/) runs a
small configuration with profiles/slurm, and every file equals a local run's.

Needs Debian's slurm-wlm and munge (``tools/slurm/localhost_slurm.sh install``, root);
skips with the reason where they cannot be installed or started.
"""

import json
import os
import subprocess
import time
from pathlib import Path

import pytest
from conftest import (
    ROOT,
    assert_same_results,
    built_once,
    result_files,
    run_snakemake,
    shared_folder,
    workdir,
)
from tiny import TINY

pytestmark = pytest.mark.slurm

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


@pytest.fixture(scope="session")
def runs(tmp_path_factory):
    """The same targets run locally and through SLURM, in two working directories, once
    for the whole test run (every xdist worker reads the same two runs, built_once): the
    localhost cluster is started for them (unless it already ran) and stopped right after,
    so no worker stops it while another's run needs it.  No cluster: the tests skip."""
    folder = shared_folder(tmp_path_factory, "slurm_runs")

    def build(root):
        root.mkdir(parents=True)
        already_running = cluster("status").returncode == 0
        started = cluster("start")
        if started.returncode != 0:
            lines = started.stderr.strip().splitlines() or [f"exit {started.returncode}"]
            (root / "skip").write_text(lines[-1].removeprefix("localhost_slurm.sh: "))
            return
        try:
            with pytest.MonkeyPatch.context() as env:
                env.setenv("SLURM_CONF", str(RUN_DIR / "etc" / "slurm.conf"))
                env.setenv("PATH", f"{RUN_DIR / 'bin'}{os.pathsep}{os.environ['PATH']}")
                # Local first: it also compiles the solver if the numba cache is cold, so
                # that the SLURM jobs (same user, same environment, hence the same cache)
                # find it compiled.
                local_s = timed_run(workdir(root / "local", CONFIG), "--cores", "2")
                slurm_s = timed_run(
                    workdir(root / "slurm", CONFIG),
                    "--profile",
                    str(ROOT / "profiles" / "slurm"),
                    "--workflow-profile",
                    str(ROOT / "profiles" / "slurm-localhost"),
                )
        finally:
            if not already_running:
                stopped = cluster("stop")
                assert stopped.returncode == 0, stopped.stderr
        (root / "times.json").write_text(json.dumps({"local_s": local_s, "slurm_s": slurm_s}))

    built_once(folder, build)
    if (folder / "skip").exists():
        pytest.skip(f"no localhost SLURM cluster: {(folder / 'skip').read_text()}")
    times = json.loads((folder / "times.json").read_text())
    # Shown with pytest -s (the SLURM run's cost is mostly the plugin's polling).
    print(
        f"\nwall time: local (--cores 2) {times['local_s']:.1f} s, SLURM {times['slurm_s']:.1f} s"
    )
    return {"local": folder / "local", "slurm": folder / "slurm", **times}


def test_jobs_ran_through_slurm(runs):
    # The plugin writes one log per SLURM job (kept: slurm-keep-successful-logs).
    logs = sorted((runs["slurm"] / ".snakemake" / "slurm_logs").rglob("*.log"))
    rules = {log.relative_to(runs["slurm"] / ".snakemake" / "slurm_logs").parts[0] for log in logs}
    assert {"rule_simulate_chunk", "rule_gather_map"} <= rules, logs
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
