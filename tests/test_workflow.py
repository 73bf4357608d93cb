"""A tiny end-to-end run of the Snakemake workflow: every rule, small grids."""

import shutil

import pandas as pd
import pytest
import xarray as xr
import yaml
from conftest import ROOT, run_snakemake

TINY = {
    "threads": 1,
    "angle_maps": {
        "L1": [0.3, 0.4],
        "theta0": {"start": 60.0, "stop": 120.0, "step": 30.0},
        "delta0": {"start": 0.0, "stop": 90.0, "step": 30.0},
    },
    "fig4": {"strokes": [[120.0, 81.5], [75.0, 39.0]], "t_end": 0.32, "samples": 33},
    "mass_length": {
        "M2": {"start": 0.2, "stop": 0.5, "step": 0.3},
        "L1": {"start": 0.2, "stop": 0.5, "step": 0.3},
        "theta0_range": [60.0, 120.0],
        "delta0_range": [0.0, 100.0],
        "coarse_step": 20.0,
        "fine_step": 10.0,
    },
    "torque_delay": {
        "L1": 0.4,
        "theta0": 90.0,
        "fig7": {
            "delta0": 26.1,
            "C2": {"start": 0.0, "stop": 10.0, "step": 5.0},
            "tau": {"start": 0.0, "stop": 0.2, "step": 0.1},
        },
        "fig8": {
            "C2": 5.0,
            "delta0": {"start": 0.0, "stop": 100.0, "step": 50.0},
            "tau": {"start": 0.0, "stop": 0.2, "step": 0.1},
        },
        "fig9": {"C2": 5.0, "delta0": 52.5, "tau": {"start": 0.0, "stop": 0.2, "step": 0.05}},
        "strokes": {"tau_L": 0.0, "tau_H": 0.185, "t_end": 0.32, "samples": 33},
    },
    "solver_study": {
        "strokes": 2,
        "seed": 1,
        "compiled_tolerances": [1e-6, 1e-8],
        "scipy_tolerances": [1e-6],
        "rk4_steps": [1e-3],
        "repeats": 1,
        "stability": {
            "k_contact": {"start": 2.0, "stop": 7.0, "num": 2},
            "cases": [["tennis_stroke.DOP853", 5e-8], ["fixed.RK4", 1e-3]],
        },
        "optimum": {"M2": [0.3], "L1": [0.4], "steps": [[20.0, 5.0]], "reference_step": 2.0},
    },
    "elbow_force": {
        "F0": 20.0,
        "t_d": 0.05,
        "psi_F": {"start": 0.0, "stop": 270.0, "step": 90.0},
        "tau_F": {"start": -0.05, "stop": 0.05, "step": 0.05},
        "table1_psi": [180.0, 275.0, 76.0],
    },
}


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    work = tmp_path_factory.mktemp("workflow")
    (work / "config").mkdir()
    (work / "config" / "config.yaml").write_text(yaml.safe_dump(TINY))
    shutil.copy(ROOT / "config" / "claims.yaml", work / "config" / "claims.yaml")
    done = run_snakemake("report", work, "--cores", "2", timeout=1200)
    assert done.returncode == 0, done.stderr[-3000:]
    return work


def test_report_and_claims_are_built(tiny_run):
    html = (tiny_run / "report" / "index.html").read_text()
    assert "Claims" in html and "data:image/png;base64," in html
    claims = pd.read_csv(tiny_run / "results" / "claims.csv")
    expected = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())["claims"]
    assert list(claims["id"]) == [c["id"] for c in expected]
    assert set(claims["status"]) <= {"pass", "fail", "known_deviation"}
    assert list(claims.columns[:8]) == [
        "id",
        "source",
        "quantity",
        "unit",
        "paper_value",
        "reproduced_value",
        "tolerance",
        "status",
    ]


def test_every_result_file_has_cf_metadata_and_provenance(tiny_run):
    files = sorted((tiny_run / "results").rglob("*.nc"))
    assert len(files) == 14
    for path in files:
        with xr.open_dataset(path) as ds:
            for name in [*ds.data_vars, *ds.coords]:
                assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, (path, name)
            for key in (
                "tennis_stroke_version",
                "git_commit",
                "config_sha256_16",
                "wall_time_s",
                "solver_rtol",
            ):
                assert key in ds.attrs, (path, key)


def test_every_figure_is_drawn(tiny_run):
    figures = sorted(p.name for p in (tiny_run / "results" / "figures").glob("*.png"))
    assert len(figures) == 16 and figures[0].startswith("fig02")


def test_changing_one_parameter_reruns_only_its_jobs(tiny_run):
    done = run_snakemake("report", tiny_run, "-n", "--config", "figure_curves=with_ball")
    assert done.returncode == 0, done.stderr[-2000:]
    stats = (done.stdout + done.stderr).split("Job stats:")[1].split("Reasons:")[0]
    rerun = {line.split()[0] for line in stats.splitlines()[3:] if line.strip()}
    assert "fig4_strokes" in rerun and "delay_strokes" in rerun
    assert "angle_map" not in rerun and "mass_length" not in rerun
