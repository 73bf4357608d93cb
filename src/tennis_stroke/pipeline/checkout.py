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
"""

from __future__ import annotations

import shlex
from pathlib import Path


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
