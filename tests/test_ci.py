"""The CI recipes run the browser tests, and fail (not skip) where they cannot."""

import os
import subprocess
import sys

import yaml
from conftest import REQUIRE_BROWSER, ROOT


def test_a_required_browser_that_is_missing_fails_the_run_in_one_line(tmp_path):
    env = {**os.environ, REQUIRE_BROWSER: "1", "PATH": str(tmp_path)}  # no chromium here
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider"],
        cwd=ROOT / "tests",
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode != 0
    assert f"{REQUIRE_BROWSER} is set and the browser tests cannot run" in done.stderr


def test_the_ci_recipes_install_debian_s_browser_and_require_it():
    job = yaml.safe_load((ROOT / ".github/workflows/replication.yml").read_text())["jobs"]
    replicate = job["replicate"]
    assert replicate["env"][REQUIRE_BROWSER] == "1"
    assert "bookworm" in replicate["container"]  # Debian: real packages, not snap stubs
    steps = " ".join(step.get("run", "") for step in replicate["steps"])
    assert "chromium chromium-driver" in steps and "|| true" not in steps
    script = (ROOT / ".ci" / "run").read_text()
    assert f"export {REQUIRE_BROWSER}=1" in script
