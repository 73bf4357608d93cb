"""Where numba caches the compiled solver, and whether the caches' folders can be used.

numba's on-disk cache checks only the source file of each compiled function, not the
modules it calls, so a change in ``model/dynamics.py`` would not recompile
``solver/stroke.py``.  The cache directory is therefore keyed by a hash of the modules
that hold compiled functions (those importing numba) and every package module they
import, read from the import graph (:mod:`tennis_stroke._imports`): a change in any of
them starts a fresh cache, an edit anywhere else (a long name in
:mod:`tennis_stroke.io.units`, the inference, the docs) compiles nothing, and an
unchanged package reloads in a new process without compiling.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Mapping
from functools import cache
from pathlib import Path

from ._imports import PACKAGE, closure, compiled_modules


@cache
def compiled_sources() -> tuple[Path, ...]:
    """The modules with compiled functions and everything they import, in a fixed order."""
    return tuple(closure(modules=compiled_modules()))


def source_hash() -> str:
    """SHA-256 (first 16 hex digits) of :func:`compiled_sources`, names and contents."""
    digest = hashlib.sha256()
    for path in compiled_sources():
        digest.update(str(path.relative_to(PACKAGE)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure_numba_cache() -> None:
    """Point ``NUMBA_CACHE_DIR`` at a per-source-hash directory unless the user set one.

    Only effective before numba is first imported (numba reads it at import).
    """
    if "NUMBA_CACHE_DIR" in os.environ:
        return
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
    os.environ["NUMBA_CACHE_DIR"] = str(base / "tennis-stroke" / "numba" / source_hash())


def _unusable(path: Path) -> str | None:
    """Why folder ``path`` cannot hold a cache (None: it is, or can be made, a writable
    folder): the nearest existing of it and its parents must be a writable folder."""
    existing = path
    while not os.path.lexists(existing) and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        return f"{str(existing)!r} is not a folder"
    if not os.access(existing, os.W_OK | os.X_OK):
        return f"{str(existing)!r} is not writable"
    return None


def cache_problem(environ: Mapping[str, str] | None = None) -> str | None:
    """The one line saying why an environment variable that names a cache folder cannot
    be used, or None.  Snakemake keeps its source cache and numba the compiled solver
    under ``XDG_CACHE_HOME``, else ``HOME``'s ``.cache``; numba under ``NUMBA_CACHE_DIR``
    where it is set.  Snakemake fails on a bad one with a long traceback before it reads
    the Snakefile, so what runs it for the user asks first (``tennis-stroke whatif``,
    ``make report``: ``tools/cache_check.py``)."""
    env = os.environ if environ is None else environ
    both = "the caches of Snakemake and numba"
    if env.get("XDG_CACHE_HOME"):
        where = [("XDG_CACHE_HOME", env["XDG_CACHE_HOME"], "", both, "XDG_CACHE_HOME")]
    else:
        home = env.get("HOME") or os.path.expanduser("~")
        where = [("HOME", home, ".cache", both, "XDG_CACHE_HOME or HOME")]
    # (the package sets NUMBA_CACHE_DIR below the folder above where the user did not)
    where.append(("NUMBA_CACHE_DIR", env.get("NUMBA_CACHE_DIR", ""), "", "numba's cache", ""))
    for name, value, below, what, fix in where:
        why = _unusable(Path(value, below)) if value else None
        if why:
            fix = fix or name
            return f"{name}={value!r} cannot hold {what} ({why}): set {fix} to a writable folder"
    return None
