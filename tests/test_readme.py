"""The README's results at a glance are generated from the claims table
(tools/readme_results.py); ``make report`` fails when they are stale."""

import subprocess
import sys
from pathlib import Path

import pandas as pd
from conftest import record_configuration

ROOT = Path(__file__).resolve().parents[1]
TOOL = ROOT / "tools" / "readme_results.py"


def _claims(path: Path, status="pass") -> Path:
    rows = [
        {
            "id": "a",
            "paper_value": 1.0,
            "reproduced_value": 1.1,
            "unit": "km/h",
            "status": status,
            "robustness": "robust",
            "evidence": "",
        },
        {
            "id": "b",
            "paper_value": 76.0,
            "reproduced_value": 232.0,
            "unit": "degree",
            "status": "known_deviation",
            "robustness": "not_reproduced",
            "evidence": "irreducible",
        },
    ]
    pd.DataFrame(rows).to_csv(path, index=False)
    record_configuration(path.parent)
    return path


def _run(*args):
    return subprocess.run(
        [sys.executable, str(TOOL), *map(str, args)], capture_output=True, text=True, timeout=60
    )


def test_the_block_is_written_and_then_checks_clean(tmp_path):
    claims = _claims(tmp_path / "claims.csv")
    readme = tmp_path / "README.md"
    readme.write_text("# x\n<!-- results:begin -->\nold\n<!-- results:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", readme, "--check").returncode == 1
    assert _run("--claims", claims, "--readme", readme).returncode == 0
    text = readme.read_text()
    assert (
        "| pass | 1 | 1 | 0 | 0 |" in text and "| `b` | 76 | 232 | degree | irreducible |" in text
    )
    assert text.startswith("# x\n") and text.endswith("<!-- results:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", readme, "--check").returncode == 0


def test_a_changed_result_makes_the_readme_stale(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("<!-- results:begin -->\n<!-- results:end -->\n")
    _run("--claims", _claims(tmp_path / "one.csv"), "--readme", readme)
    done = _run("--claims", _claims(tmp_path / "two.csv", "fail"), "--readme", readme, "--check")
    assert done.returncode == 1 and "stale" in done.stderr


def test_a_readme_without_markers_is_refused_in_one_line(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("no markers\n")
    done = _run("--claims", _claims(tmp_path / "c.csv"), "--readme", readme)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1


def test_the_readme_has_one_results_block():
    text = (ROOT / "README.md").read_text()
    assert text.count("<!-- results:begin -->") == 1 and text.count("<!-- results:end -->") == 1
