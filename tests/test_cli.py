"""The ``tennis-stroke`` command: output formats, netCDF contents, bad input, help."""

import argparse
import json
import os
import re
import resource
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import ROOT, record_configuration

from tennis_stroke import strike, strike_batch
from tennis_stroke.cli import main
from tennis_stroke.replication.claims import measure_text

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


#: A tiny grid, and the options after a bad --theta0.
SMALL_GRID = ["--theta0", "60:120:3", "--delta0", "0:90:3", "--out", "x.nc"]
DELTA_OUT = ["--delta0", "0:90:3", "--out", "x.nc"]


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
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "nope=1"], "is no model parameter"),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "C2=x"], "must be a number"),
        (
            ["strike", "--theta0", "90", "--delta0", "3", "--set", "C2"],
            "--set 'C2': expected KEY=VALUE",
        ),
        (["strike", "--theta0", "90", "--delta0", "3", "--set", "tau=nan"], "must be finite"),
        (["strike", "--theta0", "90", "--delta0", "3", "--method", "RK4"], "invalid choice"),
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
        (
            ["strike", "--theta0", "90", "--delta0", "3", "--method", "RK5"],
            "argument --method: invalid choice: 'RK5' (choose from 'DP54', 'DOP853')",
        ),
        (["sweep", *SMALL_GRID, "--method", "dop853"], "invalid choice: 'dop853'"),
        # memory: refused before anything is allocated (this grid needs about 104 GiB)
        (
            ["sweep", "--theta0", "0:120:31623", "--delta0", "0:90:31623", "--out", "x.nc"],
            "a sweep of 31623 x 31623 strokes needs about 104 GiB of memory, above the limit",
        ),
        (
            ["sweep", "--theta0", "0:120:300", "--delta0", "0:90:300", "--out", "x.nc"]
            + ["--max-memory", "1M"],
            "needs about 13.4 MiB of memory, above the limit of 1 MiB (--max-memory)",
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
        (["sweep", "--theta0", "a:120:3", "--delta0", "0:90:3", "--out", "x.nc"], "START must"),
        # the step form START:STOP/STEP, and forms that are neither
        (["sweep", "--theta0", "60:120/7", *DELTA_OUT], "step 7 does not land on STOP 120"),
        (["sweep", "--theta0", "60:120/0", *DELTA_OUT], "--theta0 STEP must be > 0, got 0"),
        (["sweep", "--theta0", "60:120/-1", *DELTA_OUT], "STEP must be > 0"),
        (["sweep", "--theta0", "120:60/1", *DELTA_OUT], "STOP 60 is below START 120"),
        (["sweep", "--theta0", "60:120/x", *DELTA_OUT], "--theta0 STEP must be a number"),
        (["sweep", "--theta0", "60:120/inf", *DELTA_OUT], "--theta0 STEP must be finite"),
        (["sweep", "--theta0", "60:120:3/1", *DELTA_OUT], "or START:STOP/STEP"),
        (["sweep", "--theta0", "60/1", *DELTA_OUT], "expects START:STOP:NUM"),
        (["sweep", "--theta0", "60:90:120:3", *DELTA_OUT], "expects START:STOP:NUM"),
        (["sweep", "--theta0", "60:120:2.5", *DELTA_OUT], "NUM (of START:STOP:NUM) must be"),
        (["sweep", "--theta0", "0:90:3", "--delta0", "0:90/0.7", "--out", "x.nc"], "--delta0"),
        (
            ["sweep", "--theta0", "0:120/1e-9", "--delta0", "0:90/1e-9", "--out", "x.nc"],
            "a sweep of 120000000001 x 90000000001 strokes needs about",
        ),
        (["sweep", "--theta0", "60:inf:3", "--delta0", "0:90:3", "--out", "x.nc"], "finite"),
        # issue 66: a turn too far gave ok and 258.2 km/h (case 2); NUM 1 dropped STOP and
        # START = STOP gave NUM equal points (case 13); the last of two --set won (case 12)
        (["strike", "--theta0", "480", "--delta0", "81.5"], "'theta0' must be <= 360 degree"),
        (["sweep", "--theta0", "280:300:3", *DELTA_OUT], "got 300 + 90 = 390"),
        (["sweep", "--theta0", "60:120:1", *DELTA_OUT], "--theta0 NUM 1 gives START alone"),
        (["sweep", "--theta0", "60:60:5", *DELTA_OUT], "--theta0 START = STOP is one point"),
        (
            ["strike", "--theta0", "90", "--delta0", "3", "--set", "M2=0.3", "--set", "M2=0.5"],
            "--set 'M2=0.5': 'M2' is set twice (also --set 'M2=0.3')",
        ),
        (["sweep", *SMALL_GRID, "--set", "C2=1", "--set", " C2 =2"], "'C2' is set twice"),
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
    from tennis_stroke.cli import sweep

    monkeypatch.setattr(sweep, "SWEEP_BLOCK_PER_THREAD", 7)
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


@pytest.mark.signals
@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="needs /proc (Linux)")
def test_ctrl_c_stops_a_sweep_at_once_with_one_line(tmp_path, startup):
    """Ctrl-C while the sweep computes: exit 130 within a few seconds (a fail-safe bound,
    not a timing: the whole grid takes tens of seconds), one line, no output file."""
    exe, env = SWEEP_EXE, SWEEP_ENV
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
    stdout, stderr, stopped_after = _signal_when_computing(proc, startup, signal.SIGINT)
    assert proc.returncode == 130, stderr
    assert stderr == "tennis-stroke: interrupted\n" and stdout == ""
    assert stopped_after < 3.0, f"stopped {stopped_after:.1f} s after Ctrl-C"
    assert not list(tmp_path.iterdir()), "no output file after Ctrl-C"


#: The sweep command of the signal tests and its environment (one BLAS thread).
SWEEP_EXE = os.path.join(os.path.dirname(sys.executable), "tennis-stroke")
SWEEP_ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}


@pytest.fixture(scope="module")
def startup(tmp_path_factory) -> float:
    """CPU time of a tiny sweep, start-up and all (cache warm): beyond it, a process
    of the same command is computing.  Measured once per worker for the signal tests
    (each measured its own: two processes more per test)."""
    out = tmp_path_factory.mktemp("startup") / "warm.nc"
    tiny = [SWEEP_EXE, "sweep", "--theta0", "60:61:2", "--delta0", "0:1:2", "--no-progress"]
    subprocess.run([*tiny, "--out", str(out)], env=SWEEP_ENV, timeout=600, check=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([*tiny, "--out", str(out)], env=SWEEP_ENV, timeout=600, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def _signal_when_computing(proc: subprocess.Popen, startup: float, signum: int):
    """Send ``signum`` to the sweep ``proc`` once it has computed for a while (its CPU
    time past ``startup`` and a second); its stdout, stderr and the seconds it took to
    end after the signal."""
    try:
        deadline = time.monotonic() + 300
        while _cpu_seconds(proc.pid) < startup + 1.0:  # computing for a while now
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "the sweep never started computing"
            time.sleep(0.05)
        sent = time.monotonic()
        proc.send_signal(signum)
        stdout, stderr = proc.communicate(timeout=120)
        return stdout, stderr, time.monotonic() - sent
    finally:
        proc.kill()


@pytest.mark.signals
@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="needs /proc (Linux)")
@pytest.mark.parametrize(
    ("threads", "signum", "status", "line"),
    [
        (1, signal.SIGINT, 130, "tennis-stroke: interrupted\n"),
        (2, signal.SIGTERM, 143, "tennis-stroke: terminated\n"),
    ],
)
def test_a_sweep_of_strokes_that_fail_slowly_stops_within_a_stroke(
    tmp_path, startup, threads, signum, status, line
):
    """Strokes that cannot finish run to the step limit (100,000 steps each): a signal
    stopped the sweep only after its block of strokes (8192 per thread: 76 s after
    SIGINT in issue 56).  The compiled solver looks for a stop before every stroke, so
    the sweep ends within about one stroke (a fail-safe bound below, not a timing: the
    1681 strokes take tens of seconds)."""
    exe, env = SWEEP_EXE, SWEEP_ENV
    grid = ["--theta0", "60:120:41", "--delta0", "0:100:41", "--set", "C1=-1e6"]
    proc = subprocess.Popen(
        [exe, "sweep", *grid, "--threads", str(threads), "--no-progress"]
        + ["--out", str(tmp_path / "slow.nc")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    stdout, stderr, stopped_after = _signal_when_computing(proc, startup, signum)
    assert proc.returncode == status, stderr
    assert stderr == line and stdout == ""
    assert stopped_after < 3.0, f"stopped {stopped_after:.1f} s after the signal"
    assert not list(tmp_path.iterdir()), "no output file after a signal"


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


@pytest.mark.process
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


#: The measure of most hand-written claims tables below, a time (unit s).
_TIME = {"file": "fig9", "var": "best_tau"}


def _cell(spec) -> str:
    """A claim's measure as a claims table's CSV cell holds it."""
    return '"' + measure_text(spec).replace('"', '""') + '"'


_MEASURE = _cell(_TIME)


def test_claims_command_exits_1_on_a_failed_claim(tmp_path, capsys):
    table = tmp_path / "claims.csv"
    record_configuration(tmp_path)
    row = "x,s,q,s,1.0,{value},0.1,{status},reproduce,,{measure},,{value},0,agrees,,,\n"
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,measure,fit_set,map_value,map_difference,map_cause,"
    header += "objective_gap,flat,edge\n"
    declared = tmp_path / "claims.yaml"  # the one claim the table holds
    claim = {"id": "x", "source": "s", "quantity": "q", "unit": "s", "paper_value": 1.0}
    claim.update(tolerance=0.1, expectation="reproduce")
    claim["measure"] = {"file": "fig9", "var": "best_tau"}
    declared.write_text(json.dumps({"claims": [claim]}))
    table.write_text(header + row.format(value=1.5, status="fail", measure=_MEASURE))
    assert main(["claims", str(table), "--claims", str(declared)]) == 1
    assert "FAIL x" in capsys.readouterr().out
    table.write_text(header + row.format(value=1.05, status="pass", measure=_MEASURE))
    assert main(["claims", str(table), "--claims", str(declared)]) == 0


def test_claims_command_exits_1_when_a_search_and_its_map_differ_without_cause(tmp_path, capsys):
    import numpy as np
    import xarray as xr

    table = tmp_path / "claims.csv"
    record_configuration(tmp_path)
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,measure,fit_set,map_value,map_difference,map_cause,"
    header += "objective_gap,flat,edge\n"
    declared = tmp_path / "claims.yaml"
    claim = {"id": "x", "source": "s", "quantity": "q", "unit": "s", "paper_value": 1.0}
    claim.update(tolerance=0.1, expectation="reproduce")
    claim["measure"] = {"file": "fig9", "var": "best_tau"}
    declared.write_text(json.dumps({"claims": [claim]}))
    table.write_text(
        header + f"x,s,q,s,1.0,1.05,0.1,pass,reproduce,,{_MEASURE},,1.0,0.5,unexplained,,,\n"
    )
    assert main(["claims", str(table), "--claims", str(declared)]) == 1
    assert "UNEXPLAINED x (default reading)" in capsys.readouterr().out
    table.write_text(
        header + f"x,s,q,s,1.0,1.05,0.1,pass,reproduce,,{_MEASURE},,1.0,0.5,grid_step\n"
    )
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


def test_identify_prints_the_fits_and_the_default(tmp_path, capsys, monkeypatch):
    """The command on the declared fit sets and their claims, each discrete reading
    narrowed to one choice, one start per fit and the shortest profiles the schema
    allows (what the identification finds is tests/inference/test_identification.py's
    and the workflow's): each fit set printed with its default and a leave-one-out line
    per fit claim."""
    space = yaml.safe_load((ROOT / "config" / "readings.yaml").read_text())
    for reading in [*space["model"].values(), *space["quoting"].values()]:
        reading["choices"] = reading["choices"][:1]
    for fit in ("model", "elbow_force"):
        space["fits"][fit]["starts"] = 1
    space["fits"]["profile_points"] = 3
    readings = tmp_path / "readings.yaml"
    readings.write_text(yaml.safe_dump(space, sort_keys=False))
    monkeypatch.chdir(ROOT)  # the claims and config at their default paths
    assert main(["identify", "--rows", "2", "--readings", str(readings)]) == 0
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


def test_strike_labels_say_which_stroke_each_value_comes_from(capsys):
    """Issue 66, case 24: for M2 = 0.34, L2 = 0.69 ``omega2_phi0`` (the swing without the
    ball, run on to phi = 0) is above ``omega2_max``, "the maximum over the stroke" (the
    stroke with the ball, which leaves that swing at the contact start): each line says
    which stroke its value comes from, and the values at phi = 0 are never those of the
    stroke with the ball."""
    argv = ["--theta0", "90", "--delta0", "52.5", "--set", "M2=0.34", "--set", "L2=0.69"]
    assert main(["strike", *argv]) == 0
    out = capsys.readouterr().out.splitlines()
    lines = {line.split()[0]: line for line in out if line.startswith("  ")}
    value = {name: float(line.split()[1]) for name, line in lines.items()}
    assert value["omega2_phi0"] > value["omega2_max"]
    strokes = ("[the swing without the ball]", "[the stroke with the ball]", "[both strokes")
    for line in lines.values():
        assert sum(stroke in line for stroke in strokes) == 1, line
    for name in ("t_phi0", "theta_deg_at_phi0", "omega1_phi0", "omega2_phi0"):
        assert strokes[0] in lines[name]
    for name in ("v_out_kmh", "t_separation", "omega2_max"):
        assert strokes[1] in lines[name]


# --- ranges: a count of points or a step ------------------------------------------------


@pytest.mark.parametrize(
    "text, expected",
    [
        ("60:120:4", [60, 80, 100, 120]),  # NUM points, both ends included
        ("60:120/20", [60, 80, 100, 120]),  # a step of 20 from 60, landing on 120
        ("0:1:3", [0, 0.5, 1]),
        ("0:1/0.5", [0, 0.5, 1]),
        ("-30:10/20", [-30, -10, 10]),
        ("5:5:1", [5]),
        ("5:5/1", [5]),
        ("120:60:3", [120, 90, 60]),  # a count may go down; a step goes up only
    ],
)
def test_a_range_is_a_count_of_points_or_a_step(text, expected):
    from tennis_stroke.cli.ranges import parse_range

    np.testing.assert_allclose(parse_range(text, "theta0"), expected, rtol=0, atol=1e-12)


def test_the_step_form_is_the_workflows_axis():
    """``START:STOP/STEP`` gives the very axis a configured ``{start, stop, step}`` gives
    (Fig. 3's theta0: 241 points), and its count is known before the axis is made."""
    from tennis_stroke.cli.ranges import range_spec
    from tennis_stroke.experiments.grids import axis

    spec = range_spec("60:120/0.25", "theta0")
    values = spec.values()
    assert spec.num == values.size == 241
    np.testing.assert_array_equal(values, axis({"start": 60, "stop": 120, "step": 0.25}))
    assert range_spec("0:0.3/0.0025", "delta0").num == 121  # 0.3 / 0.0025 is not exact


def test_a_sweep_in_the_step_form_writes_its_axes(tmp_path, capsys):
    out = tmp_path / "steps.nc"
    code, stdout, err = _run(
        capsys, "sweep", "--theta0", "60:120/30", "--delta0=-10:10/10", "--out", str(out)
    )
    assert code == 0, err
    assert stdout.startswith(f"{out}: 9 strokes")
    with xr.open_dataset(out) as ds:
        np.testing.assert_allclose(ds["theta0"], [60, 90, 120])
        np.testing.assert_allclose(ds["delta0"], [-10, 0, 10])


# --- help that reads as plain text and says units --------------------------------------


def _help(capsys, *argv) -> str:
    code, out, err = _run(capsys, *argv, "--help")
    assert code == 0 and not err, err
    return out


def _subcommands():
    from tennis_stroke.cli import build_parser

    parser = build_parser()
    (sub,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices


def test_the_top_help_is_the_docstrings_first_paragraph_as_plain_text(capsys):
    import tennis_stroke.cli as cli

    text = " ".join(_help(capsys).split())
    first = " ".join(cli.__doc__.split("\n\n")[0].split())
    assert first in text, "the description is the docstring's whole first paragraph"
    assert first.endswith(".") and "``" not in text and ":func:" not in text
    for name in _subcommands():  # every command is listed
        assert re.search(rf"^\s+{name}\s+\S", _help(capsys), re.M), name


def test_every_option_of_every_command_says_what_it_is(capsys):
    """No option or argument without a description, in any command's --help."""
    commands = dict(_subcommands())
    explain = commands.pop("config")._subparsers._group_actions[0].choices["explain"]
    for name, parser in [*commands.items(), ("config explain", explain)]:
        for action in parser._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            assert action.help, f"{name}: {action.option_strings or action.dest} has no help"


@pytest.mark.parametrize("command", ["strike", "sweep"])
def test_angle_options_say_their_unit_and_sign_from_the_table(command, capsys):
    """--theta0 and --delta0: the long name and unit of the one table of units
    (io/units.py) and the sign of the angles."""
    from tennis_stroke.io.units import VARIABLES

    text = " ".join(_help(capsys, command).split())
    for name in ("theta0", "delta0"):
        unit, long_name = VARIABLES[name]
        entry = text.split(f"--{name} ", 2)[-1]
        assert entry.startswith(("DEG ", "RANGE ")), entry[:40]
        description = entry.split(" --", 1)[0]
        assert long_name in description and f"({unit})" in description, description
        assert "counter-clockwise positive" in description, description
    if command == "sweep":  # both forms of a range
        assert "START:STOP:NUM" in text and "START:STOP/STEP" in text


def test_method_choices_and_defaults_are_the_solvers(capsys):
    """--method offers exactly the compiled methods, and the help's defaults are the
    solver's own."""
    from tennis_stroke.solver.settings import METHOD_IDS, SolverSettings

    for command in ("strike", "sweep"):
        parser = _subcommands()[command]
        (method,) = (a for a in parser._actions if "--method" in a.option_strings)
        assert tuple(method.choices) == tuple(METHOD_IDS)
        assert method.default == SolverSettings().method
        text = " ".join(_help(capsys, command).split())
        assert "{" + ",".join(METHOD_IDS) + "}" in text
        assert f"default {SolverSettings().rtol:g}" in text
    for name in METHOD_IDS:  # every choice runs
        code, out, err = _run(
            capsys, "strike", "--theta0", "120", "--delta0", "81.5", "--method", name, "--json"
        )
        assert code == 0 and json.loads(out)["solver"]["method"] == name, err


# --- params -----------------------------------------------------------------------------


def _columns(header: str, line: str) -> dict[str, str]:
    """A line of an aligned table cut at its header's column starts."""
    starts = [m.start() for m in re.finditer(r"\S+", header)]
    names = header.split()
    cells = [line[a:b].strip() for a, b in zip(starts, [*starts[1:], None], strict=True)]
    return dict(zip(names, cells, strict=True))


def test_params_lists_every_parameter_with_unit_default_and_bounds(capsys):
    from tennis_stroke.model.params import PARAMETERS, resolve_params

    code, out, err = _run(capsys, "params")
    assert code == 0 and not err
    lines = out.splitlines()
    header = next(line for line in lines if line.startswith("name ") and "bounds" in line)
    rows = {}
    for line in lines[lines.index(header) + 1 :]:
        if not line.strip():
            break
        if not line.startswith(" "):  # a wrapped meaning continues indented
            row = _columns(header, line)
            rows[row["name"]] = row
    assert list(rows) == list(PARAMETERS)
    defaults = resolve_params()
    for name, spec in PARAMETERS.items():
        row = rows[name]
        assert row["unit"] == spec.unit, name
        assert float(row["default"]) == pytest.approx(defaults[name], rel=1e-3), name
        low, high = row["bounds"].split(", ")
        assert low[0] == ("(" if spec.strict or spec.lower is None else "["), name
        assert float(low[1:]) == (-np.inf if spec.lower is None else spec.lower), name
        assert float(high[:-1]) == (np.inf if spec.upper is None else spec.upper), name
        assert (row["source"] == "derived") == spec.derived, name
    # fitted: what config/readings.yaml's fit sets fit, and nothing else
    fitted = {n for n, row in rows.items() if row["source"] == "fitted"}
    assert fitted == {"ball_mass", "k_contact", "elbow_force_mass"}


def test_the_explorer_and_params_mark_each_default_from_one_declaration(capsys):
    """The explorer called fitted defaults "paper" (k_contact, ball_mass, the readings'
    defaults): every control now says what `tennis-stroke params` says of its default."""
    from tennis_stroke.inference.reading_space import load_reading_space
    from tennis_stroke.live import controls
    from tennis_stroke.model.listing import origin

    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    fitted = load_reading_space(ROOT / "config" / "readings.yaml").fitted()
    by_key = {c.key: c for c in controls.controls(config, "fig2", fitted)}
    for key, control in by_key.items():
        section, _, name = key.partition(".")
        if section == "model":
            assert control.origin == origin(name, fitted), key
    assert by_key["model.k_contact"].origin == "fitted"
    assert by_key["model.ball_mass"].origin == "fitted"
    assert by_key["model.contact_lead_rule"].origin == "fitted"
    assert by_key["model.M2"].origin == "paper"
    assert by_key["solver.method"].origin == "ours"
    code, out, _ = _run(capsys, "params")
    assert "quarter_period [default, fitted]" in out and "half_period [paper]" in out


def test_params_lists_every_reading_and_model_option_with_its_choices(capsys):
    from tennis_stroke.model.params import CHOICES

    code, out, _ = _run(capsys, "params")
    text = " ".join(out.split())
    for name, choice in CHOICES.items():
        entry = text.split(f" {name} ", 1)[1]
        assert f"{choice.default} [default" in entry, name
        assert all(option in entry for option in choice.choices), name
    help_text = " ".join(_help(capsys, "strike").split())
    assert "--set KEY=VALUE" in help_text and "'tennis-stroke params' lists" in help_text


def test_bounds_read_as_intervals():
    from tennis_stroke.model.listing import bounds_text
    from tennis_stroke.model.params import ParamSpec

    def spec(**kw):
        return ParamSpec("x", 1.0, "m", "x", **kw)

    assert bounds_text(spec(lower=0, upper=5, strict=True)) == "(0, 5]"
    assert bounds_text(spec(lower=0, upper=10)) == "[0, 10]"
    assert bounds_text(spec()) == "(-inf, inf)"
    assert bounds_text(spec(lower=-5)) == "[-5, inf)"


# --- claims as a table ------------------------------------------------------------------


def test_claims_prints_every_claim_as_a_table_then_the_counts(tmp_path, capsys):
    table = tmp_path / "claims.csv"
    record_configuration(tmp_path)
    header = "id,source,quantity,unit,paper_value,reproduced_value,tolerance,status,"
    header += "expectation,reason,measure,fit_set,map_value,map_difference,map_cause,"
    header += "objective_gap,flat,edge\n"
    speed, angle = {"file": "fig9", "var": "best_v_out"}, {"file": "fig2", "var": "best_delta0"}
    rows = [
        f"speed,s,q,km/h,150.0,151.234567,2.0,pass,reproduce,,{_cell(speed)},,151.2,0,agrees,,,\n",
        f"angle,s,q,degree,76.0,232.4,5.0,known_deviation,known_deviation,r,{_cell(angle)},,"
        "232.4,0,agrees,,,\n",
    ]
    declared = tmp_path / "claims.yaml"
    claims = [
        {"id": "speed", "unit": "km/h", "paper_value": 150.0, "tolerance": 2.0},
        {"id": "angle", "unit": "degree", "paper_value": 76.0, "tolerance": 5.0, "reason": "r"},
    ]
    for claim, expectation, spec in zip(
        claims, ("reproduce", "known_deviation"), (speed, angle), strict=True
    ):
        claim.update(source="s", quantity="q", expectation=expectation, measure=spec)
    declared.write_text(json.dumps({"claims": claims}))
    table.write_text(header + "".join(rows))
    code, out, err = _run(capsys, "claims", str(table), "--claims", str(declared))
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0].split() == ["claim", "status", "paper", "ours", "unit", "tolerance"]
    assert lines[1].split() == ["speed", "reproduces", "150", "151.2", "km/h", "2"]
    assert lines[2].split() == ["angle", "deviates", "76", "232.4", "degree", "5"]
    assert lines[3] == "claims: 2 (1 reproduces, 1 deviates)"
    assert "{" not in out
    # with the robustness analysis: each claim across the readings, with its bound
    robust = ",robustness,pass_share,readings,pass_share_low,pass_share_high,class_bound,"
    robust += "class_sure\n"
    table.write_text(
        header.replace("\n", robust)
        + rows[0].replace("\n", ",robust,1.0,300,0.988,1.0,0.00994,True\n")
        + rows[1].replace("\n", ",reading_dependent,0.5,60,0.37,0.63,,True\n")
    )
    code, out, err = _run(capsys, "claims", str(table), "--claims", str(declared))
    lines = out.splitlines()
    assert code == 0 and lines[0].split()[-2:] == ["across", "readings"], (out, err)
    assert lines[1].endswith("all 300, fails <= 0.99 %")
    assert lines[2].endswith("50 % (37 %-63 %)")
    assert lines[3].startswith("across readings: the consistent readings it passes under")
    # a table the check refuses prints nothing but the one error line
    table.write_text(header + rows[0].replace(",pass,", ",fail,") + rows[1])
    code, out, err = _run(capsys, "claims", str(table), "--claims", str(declared))
    assert code == 2 and out == "" and err.count("\n") == 1, (out, err)


def test_a_table_wraps_its_last_column_to_the_width_under_itself():
    from tennis_stroke.cli.tables import text_table

    rows = [("a", "1.5", "one two three four five six seven eight nine ten")]
    text = text_table(("name", "value", "meaning"), rows, width=40, right=(1,))
    assert text.splitlines() == [
        "name  value  meaning",
        "a       1.5  one two three four five six",
        "             seven eight nine ten",
    ]
    assert text_table(("name", "value", "meaning"), rows).count("\n") == 1  # no width


@pytest.mark.parametrize(
    ("argv", "hint"),
    [
        (["strike", "--theta0", "90", "--delta0", "30", "--set", "M22=0.3"], "(did you mean M2?)"),
        (
            ["sweep", "--theta0", "60:120:3", "--delta0", "0:90:3", "--set", "M22=0.3"],
            "(did you mean M2?)",
        ),
        (["whatif", "x", "--set", "M22=0.3", "-n"], "(did you mean M2?)"),
        (["whatif", "x", "--set", "model.M22=0.3", "-n"], "(did you mean M2?)"),
        (
            ["whatif", "x", "--set", "torque_delay.base_strok.C2=8", "-n"],
            "(did you mean torque_delay.base_stroke,",
        ),
        (["config", "explain", "M22"], "(did you mean M2"),
        (
            ["config", "explain", "torque_delay.base_strok.C2"],
            "(did you mean torque_delay.base_stroke.C2,",
        ),
    ],
)
def test_every_command_that_takes_a_name_or_key_says_the_closest(
    argv, hint, monkeypatch, capsys, tmp_path
):
    """Issue 53: `strike --set M22=0.3` listed every key while `whatif --set M22=...`
    said 'did you mean M2?'.  Every command that takes --set or a config key refuses a
    name it does not know in one line with the closest names (one function:
    tennis_stroke.io.config_files.did_you_mean)."""
    monkeypatch.chdir(ROOT)  # whatif and config explain read the project's files
    with pytest.raises(SystemExit) as info:
        main([*argv, *(["--out", str(tmp_path / "x.nc")] if argv[0] == "sweep" else [])])
    err = capsys.readouterr().err
    assert info.value.code == 2 and err.count("\n") == 1 and hint in err, err
    assert "known:" not in err  # not every name there is
    assert not list(tmp_path.iterdir())
