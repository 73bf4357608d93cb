"""The lock (requirements.lock) against pyproject.toml and the installed environment:
`make install` installs exactly the lock, and the lock holds every declared dependency
at a version the declared range admits."""

import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from tennis_stroke.io.environment import LOCK, lock_differences, locked

ROOT = Path(__file__).resolve().parents[1]


def declared() -> list[Requirement]:
    """pyproject.toml's dependencies and those of its three extras."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extras = project["optional-dependencies"]
    return [
        Requirement(r) for r in [*project["dependencies"], *(r for x in extras.values() for r in x)]
    ]


def test_the_lock_holds_every_declared_dependency_in_its_range():
    lock = locked()
    assert len(lock) >= 90
    problems = []
    for req in declared():
        name = canonicalize_name(req.name)
        if name not in lock:
            problems.append(f"{req} is not in the lock (make lock)")
        elif not req.specifier.contains(lock[name][0], prereleases=True):
            problems.append(f"{req}: the lock has {lock[name][0]} (make lock)")
    assert not problems, "\n".join(problems)


def test_every_locked_distribution_has_a_hash():
    assert all(hashes for _, hashes in locked().values())


def test_the_installed_environment_is_the_lock():
    """`pip freeze` equals the lock: the same versions of the same distributions (the
    project itself and pip aside)."""
    assert LOCK == ROOT / "requirements.lock"
    assert lock_differences() == (), "installed against locked (make install)"


def test_a_difference_from_the_lock_is_named(tmp_path):
    lock = tmp_path / "requirements.lock"
    lock.write_text(LOCK.read_text().replace("\nnumpy==", "\nnumpy==0.0.1+x\n    # was ", 1))
    differ = lock_differences(lock)
    assert any(d.startswith("numpy ") and d.endswith("(locked 0.0.1+x)") for d in differ)


@pytest.mark.process
def test_an_edit_of_the_dependencies_without_make_lock_stops_make_install_in_one_line(
    tmp_path,
):
    """make install runs tools/lock_check.py first: the shipped lock is pyproject's; a new
    range or a new dependency without `make lock` stops it in one line, before any venv
    exists; a comment or the description changes nothing."""
    for name in ("Makefile", "pyproject.toml", "requirements.lock", "tools/lock_check.py"):
        (tmp_path / name).parent.mkdir(exist_ok=True)
        shutil.copy(ROOT / name, tmp_path / name)
    check = [sys.executable, str(tmp_path / "tools/lock_check.py"), "--root", str(tmp_path)]
    assert subprocess.run(check, capture_output=True).returncode == 0
    text = (tmp_path / "pyproject.toml").read_text()
    harmless = text.replace('description = "', 'description = "A ', 1) + "\n# a comment\n"
    (tmp_path / "pyproject.toml").write_text(harmless)
    assert subprocess.run(check, capture_output=True).returncode == 0
    for edit in ('"numpy>=2.0,<2.6"', '"numpy>=2.6"'), ('"tqdm>=4.60",', '"tqdm>=4.60", "rich",'):
        (tmp_path / "pyproject.toml").write_text(text.replace(*edit, 1))
        done = subprocess.run(
            ["make", "-C", str(tmp_path), "install", "PYTHON=" + sys.executable],
            capture_output=True,
            text=True,
        )
        errors = [line for line in done.stderr.splitlines() if line.startswith("lock_check")]
        assert done.returncode != 0 and len(errors) == 1 and "run make lock" in errors[0]
        assert not (tmp_path / ".venv").exists()


#: A stand-in for the interpreters `make install` calls (the system's python3 and the
#: venv's): it records each call; `--installed` (the check of the environment) fails
#: until a `pip install` has run; `-m venv DIR` makes DIR/bin/python (itself).
FAKE_PYTHON = """#!/bin/sh
echo "$*" >> "$FAKE_LOG"
case "$*" in
  "tools/lock_check.py --installed")
    [ -f "$FAKE_STATE" ] && exit 0
    echo "lock_check: .venv is not requirements.lock: pytest-xdist missing" >&2; exit 1;;
  "-m venv "*) mkdir -p "$3/bin" && cp "$0" "$3/bin/python";;
  "-m pip install"*) touch "$FAKE_STATE";;
esac
exit 0
"""


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
@pytest.mark.parametrize(
    "case", ["a distribution missing", "the interpreter gone", "the environment is the lock"]
)
def test_make_install_checks_the_environment_not_only_its_stamp(tmp_path, case):
    """`rm .venv/bin/python; make install` said 'Nothing to be done' (it trusted its
    stamp), and with pytest-xdist uninstalled `make check` failed on '-n' while make
    install repaired nothing (issue 56).  make install now checks the environment at
    every call and installs the lock again when it differs; when it does not, it
    installs nothing."""
    for name in ("Makefile", "pyproject.toml", "requirements.lock"):
        shutil.copy(ROOT / name, tmp_path / name)
    fake = tmp_path / "python3"
    fake.write_text(FAKE_PYTHON)
    fake.chmod(0o755)
    venv = tmp_path / ".venv"
    (venv / "bin").mkdir(parents=True)
    if case != "the interpreter gone":
        shutil.copy(fake, venv / "bin" / "python")
    state, log = tmp_path / "installed", tmp_path / "calls"
    if case == "the environment is the lock":
        state.touch()
    (venv / ".installed-stamp").touch()  # newer than the Makefile's other prerequisites
    done = subprocess.run(
        ["make", "-C", str(tmp_path), "install", f"PYTHON={fake}"],
        capture_output=True,
        text=True,
        env={**os.environ, "FAKE_LOG": str(log), "FAKE_STATE": str(state)},
    )
    assert done.returncode == 0, done.stdout + done.stderr
    calls = log.read_text().splitlines() if log.exists() else []
    installs = [c for c in calls if c.startswith("-m pip install")]
    if case == "the environment is the lock":
        assert calls == ["tools/lock_check.py --installed"]
        return
    assert installs, calls  # the lock installed again
    assert calls[-1] == "tools/lock_check.py --installed"  # and checked after
    assert (venv / "bin" / "python").exists()
    assert "make install: installing the lock again" in done.stdout


@pytest.mark.process
def test_the_check_of_the_environment_names_what_differs(tmp_path):
    """tools/lock_check.py --installed: 0 for this environment (the lock), 1 and one line
    naming the distribution for a lock it is not."""
    tool = [sys.executable, str(ROOT / "tools" / "lock_check.py"), "--installed"]
    assert subprocess.run(tool, capture_output=True).returncode == 0
    (tmp_path / "requirements.lock").write_text(
        LOCK.read_text().replace("\nnumpy==", "\nnumpy==0.0.1+x\n    # was ", 1)
    )
    done = subprocess.run([*tool, "--root", str(tmp_path)], capture_output=True, text=True)
    assert done.returncode == 1
    assert done.stderr.count("\n") == 1 and "numpy" in done.stderr and "0.0.1+x" in done.stderr
