"""Is requirements.lock the lock of pyproject.toml's dependencies?

Usage::

    python3 tools/lock_check.py            # make install runs it first: exit 2 if not
    python3 tools/lock_check.py --write    # make lock runs it after uv: record the hash

The lock records the SHA-256 of the dependencies pyproject.toml declared when it was made
(``project.dependencies`` and every extra of ``project.optional-dependencies``, as sorted
JSON) in one comment line.  An edit of those (a new dependency, another range) without
``make lock`` then stops ``make install`` in one line, before anything installs; an
edit anywhere else in pyproject.toml (a comment, the description) does not.  Standard
library only: it runs before the virtual environment exists.
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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="record the hash (make lock)")
    parser.add_argument("--root", type=Path, default=ROOT, help="the project's folder")
    args = parser.parse_args(argv)
    pyproject, lock = args.root / "pyproject.toml", args.root / "requirements.lock"
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
