"""The generated kernels are up to date with their generator and the tableaux."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.process
def test_generated_kernels_are_up_to_date():
    done = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "generate_kernels.py"), "--check"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
