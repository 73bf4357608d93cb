"""Where numba caches the compiled solver.

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
