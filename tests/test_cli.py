"""The ``tennis-stroke`` command: output formats, netCDF contents, bad input."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from tennis_stroke import strike
from tennis_stroke.cli import main

REQUIRED_PARAMS = (
    "L1",
    "M1",
    "L2",
    "M2",
    "I1_cm",
    "I2_cm",
    "C1",
    "C2",
    "tau",
    "h_hit",
    "ball_mass",
    "ball_speed",
    "k_contact",
    "contact_lead",
)
REQUIRED_RESULT = (
    "status",
    "v_out_kmh",
    "t_phi0",
    "t_contact_start",
    "t_separation",
    "theta_deg_at_phi0",
    "omega1_contact",
    "omega2_contact",
)


def _run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = exc.code
    out = capsys.readouterr()
    return code, out.out, out.err


def test_strike_json_has_the_public_fields(capsys):
    code, out, _ = _run(
        capsys,
        "strike",
        "--theta0",
        "120",
        "--delta0",
        "81.5",
        "--json",
        "--set",
        "k_contact=19000",
    )
    assert code == 0
    payload = json.loads(out)
    assert set(REQUIRED_PARAMS) <= set(payload["params"])
    assert set(REQUIRED_RESULT) <= set(payload["result"])
    assert payload["result"]["status"] == "ok"
    assert payload["params"]["I1_cm"] == pytest.approx(2.0 * 0.09 / 12)
    # the CLI and the Python API run the same solver with the same defaults
    api = strike(120.0, 81.5, {"k_contact": 19000.0})
    assert payload["result"]["v_out_kmh"] == pytest.approx(api["v_out_kmh"], abs=0.05)


def test_strike_human_readable(capsys):
    code, out, _ = _run(capsys, "strike", "--theta0", "75", "--delta0", "39")
    assert code == 0 and "v_out_kmh" in out and "ok" in out.splitlines()[0]


def test_set_accepts_overrides_and_readings(capsys):
    code, out, _ = _run(
        capsys,
        "strike",
        "--theta0",
        "90",
        "--delta0",
        "30",
        "--json",
        "--set",
        "inertia=paper_text",
        "--set",
        "I1_cm=0.02",
    )
    payload = json.loads(out)
    assert code == 0 and payload["params"]["inertia"] == "paper_text"
    assert payload["params"]["I1_cm"] == 0.02
    assert payload["params"]["I2_cm"] == pytest.approx(0.3 * 0.49 / 2)


def test_sweep_writes_cf_netcdf(tmp_path, capsys):
    out = tmp_path / "grid.nc"
    code, _, _ = _run(
        capsys,
        "sweep",
        "--theta0",
        "60:120:4",
        "--delta0",
        "0:90:3",
        "--set",
        "L1=0.4",
        "--out",
        str(out),
        "--threads",
        "1",
    )
    assert code == 0
    ds = xr.open_dataset(out)
    assert ds["v_out"].dims == ("theta0", "delta0") and ds["v_out"].shape == (4, 3)
    for name in [*ds.data_vars, *ds.coords]:
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
    assert ds["v_out"].attrs["units"] == "km/h"
    assert ds.attrs["param_L1"] == 0.4 and ds.attrs["param_L1_units"] == "m"
    assert ds.attrs["tennis_stroke_version"] and "solver_rtol" in ds.attrs
    np.testing.assert_allclose(ds["theta0"], [60, 80, 100, 120])
    assert "ok" in ds["status"].attrs["flag_meanings"]
    ds.close()


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (["strike", "--theta0", "abc", "--delta0", "3"], "invalid angle value"),
        (["strike", "--theta0", "nan", "--delta0", "3"], "must be finite"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "M2=-1"], "'M2' must be > 0"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "L2=0"], "'L2' must be > 0"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "nope=1"], "unknown parameter"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "C2=x"], "must be a number"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "C2"], "expects KEY=VALUE"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "tau=nan"], "must be finite"),
        (["strike", "--theta0", "90", "--delta0", "3", "--method", "RK4"], "solver method"),
        (["strike", "--theta0", "90", "--delta0", "3", "--rtol", "0"], "'rtol' must be > 0"),
        (["strike", "--theta0", "90"], "required"),
        (["sweep", "--theta0", "60:120:0", "--delta0", "0:90:3", "--out", "x.nc"], "NUM must be"),
        (["sweep", "--theta0", "60:120", "--delta0", "0:90:3", "--out", "x.nc"], "START:STOP:NUM"),
        (["sweep", "--theta0", "a:120:3", "--delta0", "0:90:3", "--out", "x.nc"], "numbers"),
        (["sweep", "--theta0", "60:inf:3", "--delta0", "0:90:3", "--out", "x.nc"], "finite"),
        (
            ["sweep", "--theta0", "60:120:3", "--delta0", "0:90:3", "--out", "/nonexistent/x.nc"],
            "does not exist",
        ),
        (
            [
                "sweep",
                "--theta0",
                "60:120:3",
                "--delta0",
                "0:90:3",
                "--out",
                "x.nc",
                "--threads",
                "0",
            ],
            "--threads",
        ),
    ],
)
def test_bad_input_is_one_line_and_exit_2(argv, fragment, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, *argv)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tennis-stroke: error:"), err
    assert fragment in lines[0]
    assert not list(tmp_path.iterdir()), "no output file on bad input"


def test_unwritable_directory_leaves_nothing(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        if os.access(locked, os.W_OK):
            pytest.skip("running as a user who can write anywhere (root)")
        code, _, err = _run(
            capsys,
            "sweep",
            "--theta0",
            "60:120:2",
            "--delta0",
            "0:90:2",
            "--out",
            str(locked / "x.nc"),
        )
        assert code == 2 and "cannot write" in err
    finally:
        locked.chmod(0o700)


def test_console_script_runs_as_a_process(tmp_path):
    exe = os.path.join(os.path.dirname(sys.executable), "tennis-stroke")
    done = subprocess.run(
        [exe, "strike", "--theta0", "90", "--delta0", "30", "--set", "M2=-3"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 2
    assert done.stderr.strip() == "tennis-stroke: error: parameter 'M2' must be > 0 kg, got -3"
    assert "Traceback" not in done.stderr


def test_claims_command_exits_1_on_a_failed_claim(tmp_path, capsys):
    table = tmp_path / "claims.csv"
    row = "x,s,q,s,1.0,{value},0.1,{status},reproduce,,\n"
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,fit_set\n"
    table.write_text(header + row.format(value=1.5, status="fail"))
    assert main(["claims", str(table)]) == 1
    assert "FAIL x" in capsys.readouterr().out
    table.write_text(header + row.format(value=1.05, status="pass"))
    assert main(["claims", str(table)]) == 0


def test_claims_command_without_a_table_is_one_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["claims", str(tmp_path / "none.csv")])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "does not exist" in err


def test_identify_prints_the_fits_and_the_default(capsys):
    assert main(["identify", "--rows", "2"]) == 0
    out = capsys.readouterr().out
    assert out.count("== fit set") == 2
    assert out.count("default by the declared rule") == 2
    assert out.count("leave-one-out") == 13  # ten Fig. 4 claims, three Table I speeds


def test_identify_with_a_missing_reading_space_is_one_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["identify", "--readings", str(tmp_path / "none.yaml")])
    assert exc.value.code == 2
    assert "does not exist" in capsys.readouterr().err


def test_version_prints_the_package_version(capsys):
    from tennis_stroke import __version__

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"tennis-stroke {__version__}"


def test_strike_prints_counts_as_integers(capsys):
    assert main(["strike", "--theta0", "90", "--delta0", "45"]) == 0
    lines = {line.split()[0]: line.split()[1] for line in capsys.readouterr().out.splitlines()[1:]}
    expected = strike(90.0, 45.0)
    assert lines["rhs_evals"] == str(int(expected["rhs_evals"]))
    assert lines["steps"] == str(int(expected["steps"]))
    assert "." in lines["v_out_kmh"]
