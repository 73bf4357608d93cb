"""The checkout the workflow runs from: the interpreter's path in a shell command, and the
package a job imports against the checkout's sources.

Snakemake (9.15) runs a ``script:`` job as the shell command ``{sys.executable} {script:q}``:
the interpreter's path is not quoted, so a checkout under a folder whose name has a space
(``~/my dir/tennis/.venv/bin/python``) runs no job (``bash: .../my: No such file or
directory``, exit status 127).  :func:`shell_safe` gives the path as one shell word, which
the Snakefile puts in ``sys.executable`` before any job (docs/workflow.md).

A non-editable install (``pip install .``) makes every job import the copy in
site-packages, not the checkout's ``src/tennis_stroke``: an edit of the checkout would
rerun jobs (their code inputs are the checkout's files) that then run the unedited copy.
:func:`installed_difference` names the first module in which the two differ.

The planned jobs must be able to write where their files go: a folder that is not
writable, or a file where a folder goes, is one line before any job
(:func:`unwritable_folders`, from the Snakefile's ``onstart``), not a job's traceback.

One run at a time in a working folder (:func:`hold_folder`), by an ``flock`` the kernel
lets go when the run ends: Snakemake's lock files name the files a run uses, not the run,
so it cannot tell a live run from a dead one and tells both to ``--unlock``
(``snakemake/exceptions.py``, ``LockException``; no upstream issue found).
"""

from __future__ import annotations

import fcntl
import os
import shlex
import sys
from pathlib import Path

# The caches' rule for a folder that can be written, used as it is: _cache is a code
# input of every job, so a public name there would rerun them all.
from .._cache import _unusable


def planned_files(persistence) -> list[str]:
    """Every file the jobs Snakemake is about to run write (``persistence``: the
    workflow's): their outputs, benchmark files and logs."""
    return [str(f) for job in persistence.dag.needrun_jobs() for f in job.products()]


def unwritable_folders(paths) -> str | None:
    """The one line naming every folder of ``paths`` (files to be written, relative to
    the working folder) that cannot take them, or None: the nearest existing of the
    folder and its parents must be a writable folder (the rule of the caches' folders,
    ``tennis_stroke._cache``), and each folder is checked once however many files go
    there."""
    by_folder: dict[str, list[str]] = {}
    for path in map(str, paths):
        by_folder.setdefault(os.path.dirname(path) or ".", []).append(path)
    problems: dict[str, list[str]] = {}
    for folder, files in sorted(by_folder.items()):
        why = _unusable(Path(folder))
        if why:
            problems.setdefault(why, []).extend(files)
    if not problems:
        return None
    said = "; ".join(
        f"{why}: the planned jobs write {len(files)} file(s) there ({', '.join(files[:3])}"
        + (", ..." if len(files) > 3 else "")
        + ")"
        for why, files in problems.items()
    )
    return f"{said}: make it a writable folder, then run again (no job has run)"


def shell_safe(path: str) -> str:
    """``path`` as one word of a POSIX shell command (unchanged when it needs no quotes)."""
    return shlex.quote(path)


def _modules(package: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(package)): p.read_bytes()
        for p in package.rglob("*")
        if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"
    }


def installed_difference(installed: str | Path, checkout: str | Path) -> str | None:
    """None when the package a job imports (``installed``) is the checkout's
    (``checkout``, the folder ``src/tennis_stroke``), or has the same files; else the
    first file (relative path) missing from one or differing."""
    installed, checkout = Path(installed).resolve(), Path(checkout).resolve()
    if installed == checkout:
        return None
    ours, theirs = _modules(checkout), _modules(installed)
    for name in sorted(set(ours) | set(theirs)):
        if ours.get(name) != theirs.get(name):
            return name
    return None


def runs_no_code(argv: list[str]) -> bool:
    """Whether a Snakemake command line (``sys.argv[1:]``) is a dry run or ``--touch``,
    which run no job's code.  (Snakemake knows only after the Snakefile is read.)"""
    for arg in argv:
        if arg in ("--dry-run", "--dryrun", "--touch"):
            return True
        short = arg[1:] if arg.startswith("-") and not arg.startswith("--") else ""
        if short.isalpha() and set(short) & {"n", "t"}:  # -n, -t, or joined flags (-pn)
            return True
    return False


#: Snakemake's folder in the working folder: its locks, its record of incomplete files.
SNAKEMAKE_FOLDER = Path(".snakemake")
#: Options of a Snakemake command line that only read the folder (besides a dry run).
READING_OPTIONS = frozenset(
    "--list-rules --list --list-target-rules --lt -l --lint --summary -S "
    "--detailed-summary -D --dag --rulegraph --filegraph --d3dag --report "
    "--list-changes --lc --list-input-changes --li --list-params-changes --lp "
    "--list-code-changes --version -v --help -h --print-compilation".split()
)
#: The open folder whose ``flock`` this process holds until it ends (the kernel lets it
#: go then, also after ``kill -9``).
_HELD: list[int] = []


def changes_folder(argv: list[str]) -> bool:
    """Whether a Snakemake command line (``sys.argv[1:]``) is a run's that runs jobs or
    otherwise writes the working folder (``--touch``, ``--unlock``, ...): not a dry run,
    not a listing, not a job's own Snakemake (``--mode subprocess`` or ``remote``: its
    run's process holds the folder)."""
    for i, arg in enumerate(argv):
        mode = argv[i + 1] if arg == "--mode" and i + 1 < len(argv) else arg[7:]
        if arg.startswith("--mode") and mode != "default":
            return False
        if arg in ("--dry-run", "--dryrun") or arg.split("=")[0] in READING_OPTIONS:
            return False
        short = arg[1:] if arg.startswith("-") and not arg.startswith("--") else ""
        if short.isalpha() and "n" in short:  # -n, or joined flags (-pn)
            return False
    return True


def _holder(fd: int) -> int | None:
    """The process holding the ``flock`` on open file ``fd``, or None: ``/proc/locks``
    names each lock's holder and ``MAJOR:MINOR:INODE`` (by the inode only: an overlay
    file system's device number there is not the one ``stat`` gives)."""
    inode = str(os.fstat(fd).st_ino)
    try:
        lines = Path("/proc/locks").read_text().splitlines()
    except OSError:
        return None
    for fields in (line.split() for line in lines):
        if len(fields) > 5 and fields[1] == "FLOCK" and fields[5].rsplit(":", 1)[-1] == inode:
            return int(fields[4]) if fields[4].isdigit() else None
    return None


def hold_folder(argv: list[str]) -> str | None:
    """Make this Snakemake process (the run's, not a job's) the only one that writes the
    working folder while it lives: it holds an exclusive ``flock`` on ``.snakemake``
    (not inherited by its jobs; let go by the kernel when it ends, however it ends).
    Another live run holding it: returns the line that says so (the caller refuses to
    run).  None: Snakemake's locks left in the folder are those of a run that ended
    without removing them (``kill -9``, a power cut), and are removed, as ``snakemake
    --unlock`` would (one line says so).  A dry run or a listing
    (:func:`changes_folder`) writes nothing and holds nothing; a file system without
    ``flock`` leaves it all to Snakemake."""
    if _HELD or not changes_folder(argv):  # held already (the Snakefile read again)
        return None
    SNAKEMAKE_FOLDER.mkdir(exist_ok=True)
    fd = os.open(SNAKEMAKE_FOLDER, os.O_RDONLY)  # not inherited by the jobs (PEP 446)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        pid = _holder(fd)
        os.close(fd)
        who = f" (Snakemake, pid {pid})" if pid else ""
        stop = f"kill -INT {pid}" if pid else "Ctrl-C in its terminal"
        return f"another run is active in this folder{who}: wait for it to end, or stop it ({stop})"
    except OSError:
        os.close(fd)
        return None
    _HELD.append(fd)
    stale = sorted((SNAKEMAKE_FOLDER / "locks").glob("*.lock"))
    for path in stale:
        path.unlink(missing_ok=True)
    if stale:
        sys.stderr.write(
            "tennis-stroke: removed the locks of an earlier run that ended without removing "
            "them (no other run is active in this folder)\n"
        )
    return None
