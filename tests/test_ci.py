"""The CI recipes run the browser tests, and fail (not skip) where they cannot."""

import os
import subprocess
import sys

import pytest
import yaml
from conftest import REQUIRE_BROWSER, ROOT


@pytest.mark.process
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


def _recipe() -> dict:
    """The GitHub workflow (YAML 1.1 reads its key ``on`` as True)."""
    return yaml.safe_load((ROOT / ".github/workflows/replication.yml").read_text())


def _steps() -> list[dict]:
    return _recipe()["jobs"]["replicate"]["steps"]


def _first(steps: list[dict], words: str) -> int:
    return next(i for i, s in enumerate(steps) if words in s.get("run", ""))


def _git(folder, *args, env=None):
    subprocess.run(["git", *args], cwd=folder, check=True, capture_output=True, env=env)


def test_results_record_the_commit_of_a_checkout_another_user_owns(tmp_path, monkeypatch):
    """Issue 53: the CI container runs as root over the runner's checkout, so git
    reported dubious ownership and every result recorded git_commit 'unknown' in
    silence.  Without the recipe's safe.directory step git refuses the checkout and no
    result is written (one line naming git's fix); after the step, run as the recipe
    runs it, the commit is recorded.  Another owner is git's own test switch
    (GIT_TEST_ASSUME_DIFFERENT_OWNER, git >= 2.35.2), the global config a file of the
    test's (GIT_CONFIG_GLOBAL)."""
    from tennis_stroke.io.errors import ProvenanceError
    from tennis_stroke.io.netcdf import commit_of

    checkout = tmp_path / "checkout"
    (checkout / "src").mkdir(parents=True)
    (checkout / "src" / "code.py").write_text("x\n")
    _git(checkout, "init", "-q")
    _git(checkout, "add", ".")
    _git(checkout, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "c")
    monkeypatch.setenv("GIT_CONFIG_GLOBAL", str(tmp_path / "gitconfig"))
    monkeypatch.delenv("GIT_CONFIG_SYSTEM", raising=False)
    monkeypatch.setenv("GIT_CONFIG_NOSYSTEM", "1")
    owned = commit_of(checkout / "src")
    assert len(owned) == 40
    monkeypatch.setenv("GIT_TEST_ASSUME_DIFFERENT_OWNER", "1")
    with pytest.raises(ProvenanceError, match="safe.directory"):
        commit_of(checkout / "src")
    steps = _steps()
    step = _first(steps, "safe.directory")
    assert step < _first(steps, "make test") and step < _first(steps, "make report")
    env = {**os.environ, "GITHUB_WORKSPACE": str(checkout)}
    subprocess.run(["bash", "-c", steps[step]["run"]], env=env, check=True)
    assert commit_of(checkout / "src") == owned


def test_a_branch_runs_once_and_a_newer_run_of_a_pull_request_cancels_the_older():
    recipe = _recipe()
    events = recipe[True]
    assert events["push"]["branches"] == ["main"]  # a branch's commits run as its PR
    assert "pull_request" in events
    group = recipe["concurrency"]["group"]
    assert "github.event.pull_request.number" in group and "github.ref" in group


def test_the_junit_step_is_skipped_on_a_pull_request_from_a_fork():
    """A fork's pull request gets a read-only token: no `checks: write` for
    mikepenz/action-junit-report (its claims stay in the uploaded artifact)."""
    steps = _steps()
    junit = next(s for s in steps if "action-junit-report" in s.get("uses", ""))
    condition = " ".join(junit["if"].split())
    assert "github.event.pull_request.head.repo.full_name == github.repository" in condition
    assert "github.event_name != 'pull_request'" in condition
    artifact = next(s for s in steps if "upload-artifact" in s.get("uses", ""))
    assert "results/claims.xml" in artifact["with"]["path"]


def test_the_jobs_run_on_every_core_of_the_runner(tmp_path):
    """JOBS from nproc, set for every later step before make test and make report (the
    Makefile's `JOBS ?= 2` yields to the environment)."""
    steps = _steps()
    step = _first(steps, "GITHUB_ENV")
    assert step < _first(steps, "make test")
    env_file = tmp_path / "env"
    env = {**os.environ, "GITHUB_ENV": str(env_file)}
    subprocess.run(["bash", "-c", steps[step]["run"]], env=env, check=True)
    assert env_file.read_text() == f"JOBS={len(os.sched_getaffinity(0))}\n"
    assert "JOBS   ?= 2" in (ROOT / "Makefile").read_text()
