"""The examples run as documented: each writes its figure and prints numbers that the
compiled path confirms."""

import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import FIG4_A

from tennis_stroke import strike

ROOT = Path(__file__).resolve().parents[1]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _run(*args, cwd):
    return subprocess.run(
        [sys.executable, str(ROOT / "examples" / "stroke_speeds.py"), *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )


@pytest.mark.process
def test_stroke_speeds_draws_the_stroke_and_prints_the_compiled_rebound_speed(tmp_path):
    out = tmp_path / "speeds.png"
    done = _run(out, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    data = out.read_bytes()
    assert data.startswith(PNG_SIGNATURE)
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    assert (width, height) == (1000, 400)  # figsize (10, 4) at 100 dpi
    v_out = float(re.search(r"v_out (\S+) km/h", done.stdout).group(1))
    assert abs(v_out - strike(*FIG4_A)["v_out_kmh"]) < 1e-5
    racket = float(re.search(r"racket speed at the contact start (\S+) m/s", done.stdout)[1])
    assert 20.0 < racket < v_out / 3.6  # the ball leaves faster than the racket came


@pytest.mark.process
def test_stroke_speeds_writes_its_default_file_where_it_runs(tmp_path):
    assert _run("--theta0", 75, "--delta0", 39, cwd=tmp_path).returncode == 0
    assert (tmp_path / "stroke_speeds.png").read_bytes().startswith(PNG_SIGNATURE)


@pytest.mark.process
@pytest.mark.parametrize(
    "setting, code, fragment",
    [
        ("contact_lead=0.5", 1, "the stroke failed: early_contact"),
        ("M2=-1", 2, "M2"),
    ],
)
def test_a_failed_stroke_or_a_bad_parameter_is_one_line_and_no_figure(
    tmp_path, setting, code, fragment
):
    done = _run(tmp_path / "x.png", "--set", setting, cwd=tmp_path)
    assert done.returncode == code and not (tmp_path / "x.png").exists()
    assert done.stderr.strip().count("\n") == 0 and fragment in done.stderr, done.stderr
