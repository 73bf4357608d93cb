"""The lock (requirements.lock) against pyproject.toml and the installed environment:
`make install` installs exactly the lock, and the lock holds every declared dependency
at a version the declared range admits."""

import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

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
