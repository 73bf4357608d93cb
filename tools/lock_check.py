"""Is requirements.lock the lock of pyproject.toml's dependencies?

Usage::

    python3 tools/lock_check.py            # make install runs it first: exit 2 if not
    python3 tools/lock_check.py --write    # make lock runs it after uv: record the hash
    .venv/bin/python tools/lock_check.py --installed   # is .venv the lock? exit 1 if not

The lock records the SHA-256 of the dependencies pyproject.toml declared when it was made
(``project.dependencies`` and every extra of ``project.optional-dependencies``, as sorted
JSON) in one comment line.  An edit of those (a new dependency, another range) without
``make lock`` then stops ``make install`` in one line, before anything installs; an
edit anywhere else in pyproject.toml (a comment, the description) does not.  Standard
library only: it runs before the virtual environment exists.

``--installed`` (run by the environment's interpreter, at every ``make install``) checks
the environment instead of trusting the stamp: every distribution of the lock installed
at its version and the project itself importable, else one line naming the first
differences and exit 1 (``make install`` then installs the lock again).  Distributions
installed beside the lock are left alone (installing the lock would not remove them).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The comment line of the lock that holds the hash.
PREFIX = "# pyproject.toml dependencies sha256: "


def declared_hash(pyproject: Path) -> str:
    """SHA-256 of the dependencies ``pyproject`` declares (sorted JSON)."""
    project = tomllib.loads(pyproject.read_text())["project"]
    declared = {
        "dependencies": sorted(project.get("dependencies", [])),
        "optional-dependencies": {
            extra: sorted(reqs) for extra, reqs in project.get("optional-dependencies", {}).items()
        },
    }
    return hashlib.sha256(json.dumps(declared, sort_keys=True).encode()).hexdigest()


def recorded_hash(lock: Path) -> str | None:
    """The hash the lock records (None: it records none)."""
    for line in lock.read_text().splitlines():
        if line.startswith(PREFIX):
            return line[len(PREFIX) :].strip()
    return None


def write(pyproject: Path, lock: Path) -> None:
    """Record ``pyproject``'s hash in ``lock`` (after its header comment)."""
    lines = [line for line in lock.read_text().splitlines() if not line.startswith(PREFIX)]
    at = next((i for i, line in enumerate(lines) if not line.startswith("#")), len(lines))
    lines.insert(at, PREFIX + declared_hash(pyproject))
    lock.write_text("\n".join(lines) + "\n")


def installed_differences(lock: Path) -> list[str]:
    """How the running environment differs from ``lock``: distributions of the lock
    missing or at another version, and the project not installed (importable)."""
    try:
        from tennis_stroke.io.environment import installed, lock_differences
    except ImportError as exc:
        return [f"the project is not importable ({exc}): pip install -e . missing"]
    out = list(lock_differences(lock, unlocked=False))
    if "tennis-stroke" not in installed():
        out.append("the project itself is not installed")
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="record the hash (make lock)")
    parser.add_argument(
        "--installed", action="store_true", help="is the running environment the lock?"
    )
    parser.add_argument("--root", type=Path, default=ROOT, help="the project's folder")
    args = parser.parse_args(argv)
    pyproject, lock = args.root / "pyproject.toml", args.root / "requirements.lock"
    if args.installed:
        differ = installed_differences(lock)
        if differ:
            more = f" and {len(differ) - 3} more" if len(differ) > 3 else ""
            sys.stderr.write(
                f"lock_check: {sys.prefix} is not {lock.name}: {'; '.join(differ[:3])}{more}\n"
            )
            return 1
        return 0
    try:
        if args.write:
            write(pyproject, lock)
            return 0
        if recorded_hash(lock) != declared_hash(pyproject):
            sys.stderr.write(
                f"lock_check: {lock.name} is not the lock of the dependencies {pyproject.name} "
                "declares (they were edited after the lock): run make lock, or undo the edit\n"
            )
            return 2
    except (OSError, KeyError, tomllib.TOMLDecodeError) as exc:
        sys.stderr.write(f"lock_check: cannot read {pyproject.name} or {lock.name}: {exc}\n")
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
