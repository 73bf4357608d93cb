"""A tiny end-to-end run of the Snakemake workflow: every rule, small grids; chunked maps,
a map with too many failed strokes, and a run killed midway and restarted."""

import json
import os
import re
import shutil
import signal
import subprocess
import time

import pandas as pd
import pytest
import xarray as xr
import yaml
from conftest import (
    ROOT,
    SCENARIO_PAGE,
    assert_same_results,
    file_states,
    planned_kinds,
    result_files,
    run_snakemake,
    snakemake_command,
    workdir,
)
from tiny import MAPS, ROBUSTNESS_CHUNKS, TINY, TINY_READINGS

from tennis_stroke.experiments.specs import EXPERIMENTS, RESULT_FILES
from tennis_stroke.replication.claims import COLUMNS
from tennis_stroke.replication.registry import FIGURES
from tennis_stroke.replication.robustness import COLUMNS as ROBUSTNESS_COLUMNS
from tennis_stroke.replication.robustness import ROBUSTNESS

#: The workflow end to end (make check leaves it out).
pytestmark = pytest.mark.workflow


def test_report_and_claims_are_built(tiny_run):
    html = (tiny_run / "report" / "index.html").read_text()
    assert 'id="scoreboard"' in html and "data:image/png;base64," in html
    claims = pd.read_csv(tiny_run / "results" / "claims.csv")
    expected = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())["claims"]
    assert list(claims["id"]) == [c["id"] for c in expected]
    assert set(claims["status"]) <= {"pass", "fail", "known_deviation", "used_for_fit"}
    fitted = claims[claims["fit_set"].notna()]
    assert set(fitted["status"]) <= {"used_for_fit", "fail", "known_deviation"}
    assert list(claims.columns) == [*COLUMNS, *ROBUSTNESS_COLUMNS]
    assert set(claims["robustness"]) <= set(ROBUSTNESS)
    assert (claims["robustness"] == "used_for_fit").sum() == claims["fit_set"].notna().sum()
    with xr.open_dataset(tiny_run / RESULT_FILES["robustness"]) as ds:
        assert ds.sizes["reading"] == TINY_READINGS["multiverse"]["readings"]
        assert list(ds["claim"].values) == list(claims["id"])


def test_every_result_file_has_cf_metadata_and_provenance(tiny_run):
    """Units everywhere, and what is needed to rerun: the job's config, versions, commit."""
    files = sorted((tiny_run / "results").rglob("*.nc"))
    expected = len(RESULT_FILES)
    assert len(result_files(tiny_run)) == expected
    # one chunk per map by default and per scene of the work-precision study; the
    # robustness analysis as readings.yaml says
    scenes = len(TINY["solver_study"]["scenes"])
    assert len(files) == expected + len(MAPS) + scenes + ROBUSTNESS_CHUNKS
    for path in files:
        with xr.open_dataset(path) as ds:
            for name in [*ds.data_vars, *ds.coords]:
                assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, (path, name)
            for key in (
                "tennis_stroke_version",
                "git_commit",
                "python_version",
                "numpy_version",
                "numba_version",
                "scipy_version",
                "xarray_version",
                "config",
                "config_sha256_16",
                "wall_time_s",
                "solver_rtol",
            ):
                assert key in ds.attrs, (path, key)


def test_every_figure_is_drawn(tiny_run):
    figures = sorted(p.stem for p in (tiny_run / "results" / "figures").glob("*.png"))
    assert figures == sorted(FIGURES)


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_each_figure_draws_from_the_tiny_files_with_labelled_axes(tiny_run, name):
    import matplotlib.pyplot as plt

    from tennis_stroke.replication.figures import drawer

    figure = FIGURES[name]
    datasets = [xr.load_dataset(tiny_run / path) for path in figure.inputs]
    drawn = drawer(figure.draw)(datasets, figure.title, *figure.args)
    try:
        main = drawn.axes[0]
        assert main.get_xlabel() and main.get_ylabel() and main.get_title()
    finally:
        plt.close(drawn)


def test_the_report_shows_every_figure_and_every_claim(tiny_run):
    html = (tiny_run / "report" / "index.html").read_text()
    for name in FIGURES:
        assert f'alt="{name}"' in html, name
    for claim in yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())["claims"]:
        assert f">{claim['id']}<" in html, claim["id"]


def test_changing_one_parameter_reruns_only_its_jobs(tiny_run):
    done = run_snakemake("report", tiny_run, "-n", "--config", "figure_curves=with_ball")
    assert done.returncode == 0, done.stderr[-2000:]
    rerun = set(planned_kinds(done.stdout + done.stderr))
    assert "fig4" in rerun and "delay_strokes" in rerun
    assert "fig2" not in rerun and "mass_length" not in rerun


def test_a_map_with_too_many_failed_strokes_stops_the_run_loudly(tmp_path):
    work = workdir(tmp_path, {**TINY, "solver": {"t_max": 0.05}})
    done = run_snakemake("results/torque_delay/fig9.nc", work, "--cores", "1")
    assert done.returncode != 0
    lines = [line for line in done.stderr.splitlines() if "tennis-stroke job failed" in line]
    assert lines == [
        "tennis-stroke job failed: FailureShareError: results/torque_delay/fig9.nc: 5 of 5 "
        "strokes failed (100.00 %) (no_phi_zero 5), above max_failure_share 1 % "
        "(traceback in logs/gather_map/torque_delay/fig9.log)"
    ]
    assert "Traceback" not in done.stderr
    assert not (work / "results/torque_delay/fig9.nc").exists()
    assert "Traceback" in (work / "logs/gather_map/torque_delay/fig9.log").read_text()
    with xr.open_dataset(work / "results/chunks/torque_delay/fig9/0-of-1.nc") as chunk:
        assert (chunk["status"] == 1).all()  # the failures themselves are statuses


def test_a_killed_run_restarts_to_the_same_results(tiny_run, tmp_path_factory):
    """A run killed at once (SIGKILL to its process group, as a power cut) and started
    again gives the tiny run's result files bit for bit.  It starts from a copy of the
    tiny run less the claims table and what it reads last (Fig. 9's map, the robustness
    analysis' chunks and claims), so the killed run is one that computes maps and
    searches; the figures, the page and the article only read those files again."""
    # a copy at the same depth: the code inputs' relative paths stay the same
    work = tmp_path_factory.mktemp("killed")
    shutil.copytree(tiny_run, work, symlinks=True, dirs_exist_ok=True)
    target = "results/claims.csv"
    dropped = [work / target, work / "results/torque_delay/fig9.nc"]
    dropped += [work / "results/robustness/claims.nc"]
    dropped += [*(work / "results/chunks/torque_delay/fig9").glob("*.nc")]
    dropped += [*(work / "results/chunks/robustness/claims").glob("*.nc")]
    for path in dropped:
        path.unlink()
    before = len(list((work / "results").rglob("*.nc")))
    command = snakemake_command(target, work, "--cores", "2")
    run = subprocess.Popen(
        command, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    deadline = time.monotonic() + 600
    try:
        while len(list((work / "results").rglob("*.nc"))) < before + 1:
            assert run.poll() is None, "the run ended before it could be killed"
            assert time.monotonic() < deadline, "no results after 600 s"
            time.sleep(0.05)
    finally:
        os.killpg(run.pid, signal.SIGKILL)  # the whole run at once, as a power cut would
        run.wait()
    assert not (work / target).exists()
    written = sorted((work / "results").rglob("*.nc"))
    for path in written:  # whatever has a final name is complete
        with xr.open_dataset(path) as ds:
            ds.load()
    # a killed Snakemake leaves its locks: the next run finds no live run holding the
    # folder and removes them (no --unlock), and reruns what was left incomplete
    assert list((work / ".snakemake" / "locks").iterdir())
    done = run_snakemake(target, work, "--cores", "2", "--rerun-incomplete", timeout=1200)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "tennis-stroke: removed the locks of an earlier run" in done.stderr
    made = result_files(work)
    assert "results/robustness/claims.nc" in made and set(made) <= set(result_files(tiny_run))
    for name in made:
        assert_same_results(work / name, tiny_run / name)
    claims = pd.read_csv(work / "results/claims.csv")
    pd.testing.assert_frame_equal(claims, pd.read_csv(tiny_run / "results/claims.csv"))


@pytest.mark.parametrize("key", sorted(EXPERIMENTS))
def test_every_row_of_the_table_is_wired_end_to_end(tiny_run, key):
    """Every row of the table of experiments has its jobs' logs and benchmarks,
    and its file, with exactly the variables the row declares, computed by the row's
    function from the row's config keys."""
    e = EXPERIMENTS[key]
    with xr.open_dataset(tiny_run / e.path) as ds:
        assert set(ds.data_vars) == set(e.variables), key
        job = json.loads(ds.attrs["config"])
    assert job["experiment"]["key"] == key and job["experiment"]["function"] == e.function
    assert set(job["args"]) == set(e.args)
    assert ("common" in job) == e.model
    logs = list((tiny_run / "logs").glob(f"{e.stem}.log")) + list(
        (tiny_run / "logs" / e.stem).glob("*.log")
    )
    assert logs, f"no log of row {key}"
    assert list((tiny_run / "logs" / "benchmarks").glob(f"{e.stem}*.tsv")), key


def override(section, value) -> str:
    """A --config item setting a whole top-level section."""
    return f"{section}={yaml.safe_dump(value, default_flow_style=True).strip()}"


def test_a_scenario_runs_beside_the_paper_and_touches_none_of_its_files(tiny_scenario):
    """A scenario given on the command line computes only the files its override changes,
    under results/scenarios/NAME/; every paper file keeps its bytes and time, the paper's
    configuration then plans no job, and the scenario's page and claims are explorations
    (no scoreboard, the gate says not graded)."""
    tiny_run, paper = tiny_scenario  # a copy of the tiny run, the scenario run beside it
    page = SCENARIO_PAGE
    for top in ("results", "report"):
        now = file_states(tiny_run / top)
        assert {k: v for k, v in now.items() if not k.startswith("scenarios/")} == paper[top]
    own = sorted(
        str(p.relative_to(tiny_run / "results/scenarios/strong"))
        for p in (tiny_run / "results/scenarios/strong").rglob("*.nc")
        if "chunks" not in p.parts
    )
    assert own == [  # the Sec. V stroke's C2: Fig. 8's map reads it too
        "elbow_force/map.nc",
        "strokes/delay.nc",
        "strokes/elbow_force.nc",
        "torque_delay/fig8.nc",
        "torque_delay/fig9.nc",
    ]
    with xr.open_dataset(tiny_run / "results/scenarios/strong/torque_delay/fig9.nc") as ds:
        assert float(ds.attrs["param_C2"]) == 8.0
    again = run_snakemake("report", tiny_run, "-n")
    assert "Nothing to be done" in again.stdout + again.stderr, again.stdout[-2000:]
    html = (tiny_run / page).read_text()
    assert "torque_delay.base_stroke.C2 = 8 N m (paper: 5 N m)" in html
    # each changed figure against the paper's: one scale, and the difference
    compared = sorted(p.name for p in (tiny_run / "results/scenarios/strong/compare").iterdir())
    assert "fig09_v_tau.png" in compared and "fig02_angle_map.png" not in compared
    for name in compared:
        alt = f'alt="{name[:-4]}: the paper&#39;s configuration, scenario strong and their'
        assert alt in html or alt.replace("&#39;", "'") in html, name
    words = re.sub(  # what a reader reads: not the images, styles and scripts (BokehJS)
        r"data:image/png;base64,[A-Za-z0-9+/=]+|<style>.*?</style>|<script.*?</script>",
        "",
        html,
        flags=re.S,
    )
    words = words.lower()
    assert 'id="scoreboard"' not in words and not re.search(r"\bfail", words)
    assert html.count('<tr id="claim-') == len(pd.read_csv(tiny_run / "results" / "claims.csv"))
    checked = subprocess.run(
        [str(ROOT / ".venv/bin/tennis-stroke"), "claims", "results/scenarios/strong/claims.csv"],
        cwd=tiny_run,
        capture_output=True,
        text=True,
    )
    assert checked.returncode == 0 and "not graded" in checked.stdout, checked.stderr


def test_a_departing_configuration_is_said_so_and_refused_by_the_gate(tiny_run, tmp_path_factory):
    """A paper input changed (the k range of Sec. II, of the inputs the one that reruns
    fewest jobs: its sensitivity row, the claims and what reads them): the page opens
    with the departure and `tennis-stroke claims` refuses in one line naming it.  What
    counts as a departure, and the page and the gate on a record, are tested in-process
    (test_scenarios.py, test_report.py); this is the claims job passing the run's config."""
    # a copy at the same depth: the code inputs' relative paths stay the same
    work = tmp_path_factory.mktemp("departing")
    shutil.copytree(tiny_run, work, symlinks=True, dirs_exist_ok=True)
    section = {**TINY["k_sensitivity"], "k_contact": [188.0, 10000.0]}
    done = run_snakemake(  # the page: the article says the same from the same table
        "report/index.html",
        work,
        "--cores",
        "2",
        "--config",
        override("k_sensitivity", section),
        timeout=1200,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    # the maps and the fits were not recomputed (a cheap departure, as meant)
    kept = [work / m for m in MAPS] + sorted((work / "results" / "identification").glob("*.nc"))
    assert all(
        p.stat().st_mtime_ns == (tiny_run / p.relative_to(work)).stat().st_mtime_ns for p in kept
    )
    html = (work / "report" / "index.html").read_text()
    assert "departs from the paper&#39;s" in html or "departs from the paper's" in html
    assert "k_sensitivity.k_contact = [188, 10000]" in html, html[:3000]
    gate = subprocess.run(
        [str(ROOT / ".venv/bin/tennis-stroke"), "claims"], cwd=work, capture_output=True, text=True
    )
    assert gate.returncode == 2 and len(gate.stderr.strip().splitlines()) == 1
    assert "departs from the paper's" in gate.stderr
    assert "k_sensitivity.k_contact = [188, 10000]" in gate.stderr, gate.stderr


def test_every_job_of_a_run_writes_its_benchmark_file(tiny_run):
    """Each job that ran (Snakemake's log: "Finished jobid: N (Rule: R)") left a
    benchmark file, figures and gathers too: the job CPU summed from
    logs/benchmarks covers the whole run (issue 35)."""
    import re

    logs = sorted((tiny_run / ".snakemake" / "log").glob("*.snakemake.log"))
    assert logs, "the tiny run kept no Snakemake log"
    finished = [
        rule
        for log in logs
        for rule in re.findall(r"Finished jobid: \d+ \(Rule: (\w+)\)", log.read_text())
        if rule not in ("all", "report")  # targets only: no job runs
    ]
    benchmarks = list((tiny_run / "logs" / "benchmarks").rglob("*.tsv"))
    kinds = {path.relative_to(tiny_run / "logs" / "benchmarks").parts[0] for path in benchmarks}
    assert "gather_map" in kinds and any(k.startswith("figure_") for k in kinds)
    assert len(benchmarks) == len(finished) > 0, (len(benchmarks), len(finished))
