"""The lock (requirements.lock) against pyproject.toml and the installed environment:
`make install` installs exactly the lock, and the lock holds every declared dependency
at a version the declared range admits."""

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
