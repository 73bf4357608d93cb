"""Fail safe, round three, on the command line: outputs through links, never onto a
device; long output names; overflowing ranges; an unusable cache folder; claims tables
that are not one the claims job wrote; an identify config with a bad model section."""

import contextlib
import io
import os
import re
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
import yaml
from conftest import record_configuration

from tennis_stroke.cli import main

ROOT = Path(__file__).resolve().parents[1]
SMALL = ["sweep", "--theta0", "60:120:2", "--delta0", "0:90:2", "--no-progress"]


def _run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:  # argparse and the one-line errors exit with status 2
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def _one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tennis-stroke: error:"), err
    return lines[0]


def test_an_output_link_is_written_through_and_stays_a_link(tmp_path, capsys):
    (tmp_path / "real.nc").write_text("old")
    (tmp_path / "link.nc").symlink_to("real.nc")
    code, _, err = _run(capsys, *SMALL, "--out", str(tmp_path / "link.nc"))
    assert code == 0, err
    assert (tmp_path / "link.nc").is_symlink()
    assert (tmp_path / "real.nc").read_bytes()[:4] == b"\x89HDF"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.nc", "real.nc"]


def test_an_output_that_is_not_a_regular_file_is_refused(tmp_path, capsys):
    """A pipe stands for a device here (the old code, run as root, replaced /dev/null)."""
    import os
    import stat

    fifo = tmp_path / "pipe.nc"
    os.mkfifo(fifo)
    code, _, err = _run(capsys, *SMALL, "--out", str(fifo))
    assert code == 2 and "is not a regular file" in _one_error_line(err)
    assert stat.S_ISFIFO(fifo.stat().st_mode) and [p.name for p in tmp_path.iterdir()] == [
        fifo.name
    ]


def test_a_long_output_name_that_the_folder_takes_is_written(tmp_path, capsys):
    out = tmp_path / (("a" * 240) + ".nc")  # 243 characters: the folder takes 255
    code, _, err = _run(capsys, *SMALL, "--out", str(out))
    assert code == 0, err
    assert [p.name for p in tmp_path.iterdir()] == [out.name]


def test_a_range_whose_span_overflows_is_one_line_without_warnings(tmp_path, capsys):
    argv = ["sweep", "--theta0", "-1.7e308:1.7e308:3", "--delta0", "0:1:2"]
    code, _, err = _run(capsys, *argv, "--out", str(tmp_path / "x.nc"))
    assert code == 2 and "overflows" in _one_error_line(err)


def test_a_range_of_huge_angles_is_one_line_without_warnings(tmp_path, capsys):
    """numpy's RuntimeWarning lines came before the error line (issue 66, case 14): the
    rule of the initial angles refuses the grid at its ends, before it is made."""
    argv = ["sweep", "--theta0", "1e308:1.7e308/1e307", "--delta0", "0:1:2"]
    code, _, err = _run(capsys, *argv, "--out", str(tmp_path / "x.nc"))
    assert code == 2 and "'theta0' must be <= 360 degree" in _one_error_line(err)


@pytest.mark.process
def test_a_cache_folder_that_is_a_file_is_one_line(tmp_path):
    (tmp_path / "cache").write_text("a file")
    env = {"PATH": "/usr/bin:/bin", "XDG_CACHE_HOME": str(tmp_path / "cache")}
    cmd = [sys.executable, "-m", "tennis_stroke.cli", "strike", "--theta0", "90", "--delta0", "45"]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 2
    assert "cannot use the compiled code's cache folder" in _one_error_line(done.stderr)


@pytest.mark.parametrize(
    "variable, below",
    [("HOME", ""), ("XDG_CACHE_HOME", ""), ("NUMBA_CACHE_DIR", ""), ("HOME", "locked")],
)
def test_a_cache_variable_that_names_no_usable_folder_is_named(tmp_path, variable, below):
    """HOME, XDG_CACHE_HOME, NUMBA_CACHE_DIR: a file, or a folder that cannot be written
    (a missing folder below a writable one is fine: it is made)."""
    from tennis_stroke._cache import cache_problem

    (tmp_path / "file").write_text("a file")
    (tmp_path / "locked").mkdir(mode=0o500)
    good = {"HOME": str(tmp_path / "home"), "NUMBA_CACHE_DIR": str(tmp_path / "new" / "n")}
    assert cache_problem(good) is None
    bad = str(tmp_path / below) if below else str(tmp_path / "file")
    problem = cache_problem({**good, variable: bad})
    if below and os.access(tmp_path / "locked", os.W_OK):  # root writes anywhere
        pytest.skip("this user can write a folder of mode 0500")
    assert problem.startswith(f"{variable}={bad!r} cannot hold"), problem
    assert ("is not writable" if below else "is not a folder") in problem


@pytest.mark.process
def test_whatif_with_a_home_that_is_a_file_is_one_line(tmp_path):
    """HOME=/etc/hostname: `tennis-stroke whatif ... -n` and `make report` printed 29-44
    lines of Snakemake's traceback (NotADirectoryError .../.cache), before the Snakefile
    was read; both now ask first (tools/cache_check.py for make report)."""
    (tmp_path / "home").write_text("a file, not a folder")
    env = {k: v for k, v in os.environ.items() if k not in ("XDG_CACHE_HOME", "NUMBA_CACHE_DIR")}
    env["HOME"] = str(tmp_path / "home")
    whatif = [sys.executable, "-m", "tennis_stroke.cli", "whatif", "x", "--set", "M2=0.35"]
    done = subprocess.run(
        [*whatif, "--figure", "fig2", "-n"],
        capture_output=True,
        text=True,
        env=env,
        cwd=ROOT,
        timeout=300,
    )
    assert done.returncode == 2
    line = _one_error_line(done.stderr)
    assert f"HOME={str(tmp_path / 'home')!r} cannot hold the caches" in line
    check = [sys.executable, str(ROOT / "tools" / "cache_check.py")]
    done = subprocess.run(check, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 2 and _one_error_line(done.stderr) == line


def _table(tmp_path):
    """The claims table of a run: one row per declared claim, each reproducing the paper's
    value (so passing), as the claims job would write it."""
    declared = __import__("yaml").safe_load((ROOT / "config" / "claims.yaml").read_text())
    from tennis_stroke.replication.claims import COLUMNS, measure_text

    record_configuration(tmp_path)

    rows = [
        {
            **dict.fromkeys(COLUMNS, ""),
            **{k: str(c.get(k, "")) for k in ("id", "source", "quantity", "unit", "reason")},
            "measure": measure_text(c["measure"]),
            "status": "pass",
            "reproduced_value": c["paper_value"],
            "paper_value": c["paper_value"],
            "tolerance": c["tolerance"],
            "expectation": c["expectation"],
            "map_cause": "agrees",
        }
        for c in declared["claims"]
    ]
    return pd.DataFrame(rows, columns=COLUMNS)


@pytest.mark.parametrize(
    "damage, fragment",
    [
        (lambda t: t.iloc[:0], "holds 0 claims"),
        (lambda t: t.iloc[: len(t) // 2], "claims, config/claims.yaml declares"),
        (lambda t: t.assign(status=["FAIL"] * len(t)), "has status 'FAIL'"),
        (lambda t: t.assign(status=["Fail"] * len(t)), "has status 'Fail'"),
        (lambda t: t.assign(status=[""] * len(t)), "has status ''"),
        (lambda t: t.drop(columns=["status"]), "column 'status' is missing"),
        (lambda t: t.assign(reproduced_value=[""] * len(t)), "has no reproduced value"),
    ],
)
def test_claims_refuses_a_broken_table_with_exit_2(tmp_path, capsys, monkeypatch, damage, fragment):
    monkeypatch.chdir(ROOT)
    csv = tmp_path / "claims.csv"
    damage(_table(tmp_path)).to_csv(csv, index=False)
    code, _, err = _run(capsys, "claims", str(csv))
    assert code == 2 and fragment in _one_error_line(err)


def test_claims_reads_a_table_with_a_byte_order_mark(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    csv = tmp_path / "claims.csv"
    csv.write_bytes(b"\xef\xbb\xbf" + _table(tmp_path).to_csv(index=False).encode())
    code, out, err = _run(capsys, "claims", str(csv))
    assert code == 0 and re.search(r"^claims: \d+ \(\d+ reproduce", out, re.M), (out, err)


def test_claims_exits_1_only_for_a_failed_claim(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    csv = tmp_path / "claims.csv"
    table = _table(tmp_path)
    assert table.loc[0, "expectation"] == "reproduce"
    table.loc[0, "reproduced_value"] = float(table.loc[0, "paper_value"]) + 100.0
    table.loc[0, "status"] = "fail"
    table.to_csv(csv, index=False)
    code, out, _ = _run(capsys, "claims", str(csv))
    assert code == 1 and out.count("FAIL ") == 1


@pytest.mark.parametrize(
    "column, value, fragment",
    [
        ("status", "pass", "gives 'fail' (edited by hand?)"),  # a failure marked pass
        ("tolerance", 1000.0, "has tolerance 1000.0, config/claims.yaml"),
        ("expectation", "known_deviation", "has expectation 'known_deviation'"),
    ],
)
def test_claims_refuses_a_table_edited_by_hand(
    tmp_path, capsys, monkeypatch, column, value, fragment
):
    """A claims table whose statuses do not follow from its values and the declared
    claims was not written by the claims job (the report refuses it too)."""
    monkeypatch.chdir(ROOT)
    csv = tmp_path / "claims.csv"
    table = _table(tmp_path)
    table.loc[0, "reproduced_value"] = float(table.loc[0, "paper_value"]) + 100.0
    table.loc[0, "status"] = "fail"
    table[column] = table[column].astype(object)
    table.loc[0, column] = value
    table.to_csv(csv, index=False)
    code, _, err = _run(capsys, "claims", str(csv))
    assert code == 2 and fragment in _one_error_line(err)


@pytest.mark.parametrize(
    "field, change",
    [
        ("measure", lambda c: c["measure"].update(theta0=90.0)),  # issue 66, case 11
        ("quantity", lambda c: c.update(quantity="another quantity")),
        ("source", lambda c: c.update(source="Sec. IX")),
    ],
)
def test_claims_names_a_table_older_than_an_edit_of_its_claims(
    tmp_path, capsys, monkeypatch, field, change
):
    """Was: the table passed (only ids, paper values, tolerances and expectations were
    compared), its value measured at theta0 = 120 graded as the claim at 90."""
    monkeypatch.chdir(ROOT)
    csv = tmp_path / "claims.csv"
    _table(tmp_path).to_csv(csv, index=False)
    raw = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())
    change(next(c for c in raw["claims"] if c["id"] == "fig2_best_delta0_at_120"))
    (tmp_path / "claims.yaml").write_text(yaml.safe_dump(raw))
    assert _run(capsys, "claims", str(csv))[0] == 0  # the table of config/claims.yaml
    code, _, err = _run(capsys, "claims", str(csv), "--claims", str(tmp_path / "claims.yaml"))
    line = _one_error_line(err)
    assert code == 2 and f"(claim 'fig2_best_delta0_at_120') has {field} " in line
    assert "stale" in line


def test_identify_refuses_a_model_section_that_is_a_list(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    config = (ROOT / "config" / "config.yaml").read_text().replace("\nmodel: {}", "\nmodel: [1, 2]")
    assert "model: [1, 2]" in config
    (tmp_path / "config.yaml").write_text(config)
    code, _, err = _run(capsys, "identify", "--config", str(tmp_path / "config.yaml"))
    assert code == 2 and "'model' must be a mapping" in _one_error_line(err)


# stdout that cannot take the output (issue 66, cases 6 and 7): one line, exit 1.


@pytest.mark.parametrize("argv", [["params"], ["config", "explain", "model.M2"]])
def test_a_full_stdout_is_one_line_and_exit_1(argv, capsys, monkeypatch):
    """Was: an OSError traceback (the output is flushed inside the guard now)."""
    full = open("/dev/full", "w")  # noqa: SIM115 (closed below, whatever it holds)
    monkeypatch.setattr(sys, "stdout", full)
    try:
        code = main(argv)
    finally:
        monkeypatch.undo()
        with contextlib.suppress(OSError):
            full.close()
    err = capsys.readouterr().err
    assert code == 1 and "stdout" in _one_error_line(err) and "No space left" in err


@pytest.mark.parametrize("argv", [["params"], ["config", "explain", "model.M2"]])
def test_a_closed_stdout_is_one_line_and_exit_1(argv, capsys, monkeypatch):
    """Was: exit 0 with the output lost (Python gives a closed stdout as None, and
    print writes nothing there), or a traceback from ``isatty``."""
    monkeypatch.setattr(sys, "stdout", None)
    code = main(argv)
    assert code == 1 and "stdout is closed" in _one_error_line(capsys.readouterr().err)


def test_a_reader_that_went_away_is_exit_1_without_a_line(capsys, monkeypatch):
    """``tennis-stroke params | head -1``: the reader chose to stop, nothing to tell."""

    class Gone(io.StringIO):
        def write(self, text):
            raise BrokenPipeError(32, "Broken pipe")

    monkeypatch.setattr(sys, "stdout", Gone())
    assert main(["params"]) == 1
    assert capsys.readouterr().err == ""


def test_a_closed_stderr_still_gives_the_exit_status(monkeypatch):
    """The error line has nowhere to go; writing it must not raise in its place."""
    monkeypatch.setattr(sys, "stderr", None)
    with pytest.raises(SystemExit) as stop:
        main(["params", "--no-such-option"])
    assert stop.value.code == 2
    monkeypatch.setattr(sys, "stdout", None)
    assert main(["params"]) == 1


@pytest.mark.process
def test_a_full_or_closed_stdout_in_a_process_exits_with_one_line():
    """What only a process shows: Python's own flush at exit adds no second message
    (nor exit status 120), and a shell's ``>&-`` closes the descriptor itself."""
    cli = f"{sys.executable} -m tennis_stroke.cli"
    script = (
        f"{cli} params > /dev/full; echo rc=$?; "
        f"{cli} config explain model.M2 >&-; echo rc=$?; "
        f"{cli} params >&- 2>&-; echo rc=$? >&2"
    )
    done = subprocess.run(["sh", "-c", script], capture_output=True, text=True, timeout=120)
    assert done.stdout.split() == ["rc=1", "rc=1"], done
    lines = done.stderr.splitlines()
    assert len(lines) == 3 and lines[2] == "rc=1", done.stderr
    assert "No space left" in lines[0] and "stdout is closed" in lines[1], done.stderr
