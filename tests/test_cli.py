"""The ``tennis-stroke`` command: output formats, netCDF contents, bad input."""

import json
import os
import resource
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
from conftest import record_configuration

from tennis_stroke import strike, strike_batch
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
        # tolerances beyond the accuracy bound gave 'ok' and a wrong v_out
        (["strike", "--theta0", "120", "--delta0", "81.5", "--rtol", "10"], "must be <= 0.0001"),
        (["strike", "--theta0", "120", "--delta0", "81.5", "--rtol", "1"], "must be <= 0.0001"),
        (["strike", "--theta0", "120", "--delta0", "81.5", "--atol", "100"], "'atol' must be <="),
        (["strike", "--theta0", "90", "--delta0", "3", "--rtol", "1e-3"], "claims' tolerances"),
        (
            ["sweep", "--theta0", "60:120:3", "--delta0", "0:90:3", "--out", "x.nc", "--rtol=0.1"],
            "'rtol' must be <= 0.0001",
        ),
        (["strike", "--theta0", "90", "--delta0", "3", "--method", "RK5"], "one of DP54, DOP853"),
        (["strike", "--theta0", "90", "--delta0", "3", "--method", "dop853"], "one of DP54"),
        # memory: refused before anything is allocated (this grid needs about 104 GiB)
        (
            ["sweep", "--theta0", "0:120:31623", "--delta0", "0:90:31623", "--out", "x.nc"],
            "a sweep of 31623 x 31623 strokes needs about 104 GiB of memory, above the limit",
        ),
        (
            ["sweep", "--theta0", "0:120:300", "--delta0", "0:90:300", "--out", "x.nc"]
            + ["--max-memory", "1M"],
            "needs about 13.3 MiB of memory, above the limit of 1 MiB (--max-memory)",
        ),
        (
            ["sweep", "--theta0", "0:120:3", "--delta0", "0:90:3", "--out", "x.nc"]
            + ["--max-memory", "lots"],
            "--max-memory: memory size must be",
        ),
        (
            ["sweep", "--theta0", "0:120:3", "--delta0", "0:90:3", "--out", "x.nc"]
            + ["--max-memory", "-1G"],
            "--max-memory: memory size must be",
        ),
        (
            ["sweep", "--theta0", "0:120:1000000000000", "--delta0", "0:90:3", "--out", "x.nc"],
            "a sweep of 1000000000000 x 3 strokes needs about 306 TiB",
        ),
        # a negative value after an option is a value, and a bad one is still refused
        (["strike", "--theta0", "90", "--delta0", "-1e400"], "must be finite"),
        (["strike", "--theta0", "90", "--delta0", "-inf"], "must be finite"),
        (["strike", "--theta0", "90", "--delta0", "3", "--rtol", "-1e-3"], "'rtol' must be > 0"),
        (["strike", "--theta0", "90", "--delta0", "3", "--json", "-1"], "ignored explicit"),
        (
            ["sweep", "--theta0", "-30:10:0", "--delta0", "0:90:3", "--out", "x.nc"],
            "--theta0 NUM must be >= 1",
        ),
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


def _small_sweep(capsys, out):
    """A 2 x 2 sweep written to ``out``: (exit code, stdout, stderr)."""
    return _run(capsys, "sweep", "--theta0", "60:120:2", "--delta0", "0:90:2", "--out", str(out))


def test_a_file_given_as_the_output_directory_is_named_a_file(tmp_path, capsys):
    (tmp_path / "plain").write_text("not a folder")
    for out in ("plain/x.nc", "plain/deeper/x.nc"):
        code, _, err = _small_sweep(capsys, tmp_path / out)
        assert code == 2 and err.count("\n") == 1
        assert f"output directory {str(tmp_path / 'plain')!r} is a file, not a directory" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plain"]


def test_memory_limit_from_the_environment(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("TENNIS_STROKE_MAX_MEMORY", "100K")
    code, _, err = _run(
        capsys, "sweep", "--theta0", "60:120:30", "--delta0", "0:90:30", "--out", "x.nc"
    )
    assert code == 2 and "above the limit of 100 KiB (TENNIS_STROKE_MAX_MEMORY)" in err
    # the option wins over the environment
    code, _, err = _run(
        capsys,
        "sweep",
        "--theta0",
        "60:120:3",
        "--delta0",
        "0:90:3",
        "--out",
        "x.nc",
        "--max-memory",
        "64M",
        "--threads",
        "1",
    )
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.nc"]


@pytest.mark.parametrize(
    "argv, theta0, delta0",
    [
        (["--theta0", "120", "--delta0", "-1"], 120.0, -1.0),
        (["--theta0", "120", "--delta0", "-1e1"], 120.0, -10.0),
        (["--theta0", "-.5e2", "--delta0", "-7.5"], -50.0, -7.5),
        (["--delta0", "-1", "--theta0=-30"], -30.0, -1.0),
    ],
)
def test_negative_numbers_after_an_option_are_values(argv, theta0, delta0, capsys):
    code, out, err = _run(capsys, "strike", *argv, "--json")
    assert code == 0, err
    params = json.loads(out)["params"]
    assert (params["theta0_deg"], params["delta0_deg"]) == (theta0, delta0)


def test_negative_ranges_after_an_option_are_values(tmp_path, capsys):
    out = tmp_path / "neg.nc"
    code, _, err = _run(
        capsys,
        "sweep",
        "--theta0",
        "-30:10:5",
        "--delta0",
        "-20:-10:2",
        "--out",
        str(out),
        "--threads",
        "1",
    )
    assert code == 0, err
    with xr.open_dataset(out) as ds:
        np.testing.assert_allclose(ds["theta0"], [-30, -20, -10, 0, 10])
        np.testing.assert_allclose(ds["delta0"], [-20, -10])


def test_sweep_in_blocks_is_bit_for_bit_one_batch(tmp_path, capsys, monkeypatch):
    """The sweep runs in blocks (to stop on Ctrl-C between them): the same numbers as one
    strike_batch over the grid, with blocks that end mid-row."""
    import tennis_stroke.cli as cli

    monkeypatch.setattr(cli, "SWEEP_BLOCK_PER_THREAD", 7)
    out = tmp_path / "blocks.nc"
    code, _, err = _run(
        capsys,
        "sweep",
        "--theta0",
        "60:120:9",
        "--delta0",
        "0:90:5",
        "--set",
        "L1=0.4",
        "--out",
        str(out),
        "--threads",
        "2",
    )
    assert code == 0, err
    whole = strike_batch(
        np.linspace(60, 120, 9)[:, None], np.linspace(0, 90, 5)[None, :], {"L1": 0.4}
    )
    with xr.open_dataset(out) as ds:
        for name, values in whole.items():
            file_name = {"v_out_kmh": "v_out"}.get(name, name)
            assert ds[file_name].dtype == values.dtype, name
            np.testing.assert_array_equal(ds[file_name].values, values, err_msg=name)


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of a running process (s)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="needs /proc (Linux)")
def test_ctrl_c_stops_a_sweep_at_once_with_one_line(tmp_path):
    """Ctrl-C while the sweep computes: exit 130 within a few seconds (a fail-safe bound,
    not a timing: the whole grid takes tens of seconds), one line, no output file."""
    exe = os.path.join(os.path.dirname(sys.executable), "tennis-stroke")
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    tiny = [exe, "sweep", "--theta0", "60:61:2", "--delta0", "0:1:2", "--no-progress"]
    subprocess.run([*tiny, "--out", str(tmp_path / "warm.nc")], env=env, timeout=600, check=True)
    # CPU time of the start-up alone (imports, loading the compiled code), cache warm
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([*tiny, "--out", str(tmp_path / "warm.nc")], env=env, timeout=600, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    startup = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    (tmp_path / "warm.nc").unlink()
    out = tmp_path / "big.nc"
    proc = subprocess.Popen(
        [
            exe,
            "sweep",
            "--theta0",
            "60:120:1000",
            "--delta0",
            "0:90:2000",
            "--no-progress",
            "--threads",
            "2",
            "--out",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        deadline = time.monotonic() + 300
        while _cpu_seconds(proc.pid) < startup + 1.0:  # computing for a while now
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "the sweep never started computing"
            time.sleep(0.05)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        stdout, stderr = proc.communicate(timeout=60)
        stopped_after = time.monotonic() - sent
    finally:
        proc.kill()
    assert proc.returncode == 130, stderr
    assert stderr == "tennis-stroke: interrupted\n" and stdout == ""
    assert stopped_after < 3.0, f"stopped {stopped_after:.1f} s after Ctrl-C"
    assert not list(tmp_path.iterdir()), "no output file after Ctrl-C"


def test_identify_names_file_and_line_of_a_yaml_syntax_error(tmp_path, capsys):
    bad = tmp_path / "claims.yaml"
    bad.write_text("claims:\n  - {id: a, value: 1\n  - {id: b}\n")
    code, _, err = _run(capsys, "identify", "--claims", str(bad))
    assert code == 2 and err.count("\n") == 1, err
    assert err.startswith(f"tennis-stroke: error: {bad}, line 3, column 5: YAML syntax error")
    config = tmp_path / "config.yaml"
    config.write_text("solver:\n  rtol: 1e-8\n\tatol: 1e-8\n")
    code, _, err = _run(capsys, "identify", "--config", str(config))
    assert code == 2 and err.count("\n") == 1, err
    assert f"{config}, line 3, column 1: YAML syntax error" in err


def test_unwritable_directory_leaves_nothing(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        if os.access(locked, os.W_OK):
            pytest.skip("running as a user who can write anywhere (root)")
        code, _, err = _small_sweep(capsys, locked / "x.nc")
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
    record_configuration(tmp_path)
    row = "x,s,q,s,1.0,{value},0.1,{status},reproduce,,,{value},0,agrees\n"
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,fit_set,map_value,map_difference,map_cause\n"
    declared = tmp_path / "claims.yaml"  # the one claim the table holds
    claim = {"id": "x", "source": "s", "quantity": "q", "unit": "s", "paper_value": 1.0}
    claim.update(tolerance=0.1, expectation="reproduce")
    claim["measure"] = {"file": "fig9", "var": "best_tau"}
    declared.write_text(json.dumps({"claims": [claim]}))
    table.write_text(header + row.format(value=1.5, status="fail"))
    assert main(["claims", str(table), "--claims", str(declared)]) == 1
    assert "FAIL x" in capsys.readouterr().out
    table.write_text(header + row.format(value=1.05, status="pass"))
    assert main(["claims", str(table), "--claims", str(declared)]) == 0


def test_claims_command_exits_1_when_a_search_and_its_map_differ_without_cause(tmp_path, capsys):
    import numpy as np
    import xarray as xr

    table = tmp_path / "claims.csv"
    record_configuration(tmp_path)
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,fit_set,map_value,map_difference,map_cause\n"
    declared = tmp_path / "claims.yaml"
    claim = {"id": "x", "source": "s", "quantity": "q", "unit": "s", "paper_value": 1.0}
    claim.update(tolerance=0.1, expectation="reproduce")
    claim["measure"] = {"file": "fig9", "var": "best_tau"}
    declared.write_text(json.dumps({"claims": [claim]}))
    table.write_text(header + "x,s,q,s,1.0,1.05,0.1,pass,reproduce,,,1.0,0.5,unexplained\n")
    assert main(["claims", str(table), "--claims", str(declared)]) == 1
    assert "UNEXPLAINED x (default reading)" in capsys.readouterr().out
    table.write_text(header + "x,s,q,s,1.0,1.05,0.1,pass,reproduce,,,1.0,0.5,grid_step\n")
    assert main(["claims", str(table), "--claims", str(declared)]) == 0
    folder = tmp_path / "robustness" / "validation"  # the validation files beside the table
    folder.mkdir(parents=True)
    xr.Dataset(
        {
            "cause": (("reading", "claim"), np.array([["agrees"], ["unexplained"]], dtype=object)),
            "targeted_value": (("reading", "claim"), [[1.0], [1.2]]),
            "map_value": (("reading", "claim"), [[1.0], [1.0]]),
        },
        coords={"reading": [3, 7], "claim": ["x"]},
    ).to_netcdf(folder / "fig9.nc")
    assert main(["claims", str(table), "--claims", str(declared)]) == 1
    assert "UNEXPLAINED x (reading 7)" in capsys.readouterr().out


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
