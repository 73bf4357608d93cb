"""The software environment that computes the results: the lock, what is installed, the
CPU and the compile target.

``requirements.lock`` (``make lock``) pins every distribution the project installs, with
hashes; ``make install`` installs exactly it.  Each result file records the lock's hash
and whether the running environment is the lock (:func:`environment_attrs`); the report
lists every installed distribution, the CPU model and numba's compile target
(:func:`environment_table`); ``tools/compare_results.py`` says when two result folders
were made by different environments.
"""

from __future__ import annotations

import hashlib
import re
from functools import cache
from importlib import metadata
from pathlib import Path

#: The lock of a source checkout (beside ``src/``).
LOCK = Path(__file__).resolve().parents[3] / "requirements.lock"
#: Installed but never locked: the project itself and the venv's own pip.
UNLOCKED = {"tennis-stroke", "pip"}


def canonical(name: str) -> str:
    """A distribution's name as PEP 503 compares it."""
    return re.sub(r"[-_.]+", "-", name).lower()


def locked(path: str | Path = LOCK) -> dict[str, tuple[str, list[str]]]:
    """Each distribution of a lock with its version and sha256 hashes, by canonical name."""
    out = {}
    for entry in re.split(r"\n(?=[A-Za-z0-9])", Path(path).read_text()):
        match = re.match(r"([A-Za-z0-9_.\-]+)==([^\s\\;]+)", entry)
        if match:
            hashes = re.findall(r"--hash=sha256:([0-9a-f]{64})", entry)
            out[canonical(match.group(1))] = (match.group(2), hashes)
    return out


def installed() -> dict[str, str]:
    """Every installed distribution's version, by canonical name."""
    return {canonical(d.metadata["Name"]): d.version for d in metadata.distributions()}


@cache
def lock_hash(path: str | Path = LOCK) -> str:
    """SHA-256 (16 hex digits) of the lock, or ``"no lock"`` outside a checkout."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    except OSError:
        return "no lock"


@cache
def lock_differences(path: str | Path = LOCK, unlocked: bool = True) -> tuple[str, ...]:
    """How the running environment differs from the lock (empty: it is the lock): each
    distribution installed at another version, missing, or (``unlocked``) installed but
    not locked."""
    try:
        lock = locked(path)
    except OSError:
        return ("no lock",)
    have = installed()
    out = [
        f"{name} {have.get(name, 'missing')} (locked {version})"
        for name, (version, _) in sorted(lock.items())
        if have.get(name) != version
    ]
    if unlocked:
        extra = sorted(set(have) - set(lock) - UNLOCKED)
        out += [f"{name} {have[name]} (not locked)" for name in extra]
    return tuple(out)


def environment_attrs() -> dict[str, str]:
    """The global attributes of every result file: the lock's hash and whether the
    environment that wrote the file is the lock."""
    differ = lock_differences()
    return {
        "environment_lock_sha256_16": lock_hash(),
        "environment_is_lock": "yes"
        if not differ
        else f"no: {'; '.join(differ[:5])}"
        + (f" and {len(differ) - 5} more" if len(differ) > 5 else ""),
    }


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo``), or ``"unknown"``."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def compile_target() -> str:
    """The CPU numba compiles for (LLVM's host CPU name and its features' count)."""
    try:
        from llvmlite import binding

        features = binding.get_host_cpu_features().flatten().split(",")
        return (
            f"{binding.get_host_cpu_name()} ({sum(f.startswith('+') for f in features)} features)"
        )
    except Exception:  # noqa: BLE001 - any failure: say it is unknown, never fail a report
        return "unknown"


def environment_table() -> dict[str, object]:
    """What the report's provenance shows of the environment: the lock's hash, whether
    the environment is the lock, the CPU and compile target, every distribution."""
    differ = lock_differences()
    return {
        "lock": lock_hash(),
        "is_lock": not differ,
        "differences": list(differ),
        "cpu": cpu_model(),
        "compile_target": compile_target(),
        "distributions": sorted(installed().items()),
    }
