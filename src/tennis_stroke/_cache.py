"""Where numba caches the compiled solver.

numba's on-disk cache checks only the source file of each compiled function, not the
modules it calls, so a change in ``model/dynamics.py`` would not recompile
``solver/stroke.py``.  The cache directory is therefore keyed by a hash of the layers with
compiled code, ``model/`` and ``solver/``: a change in any of their modules starts a fresh
cache, and an unchanged package reloads in a new process without compiling.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

#: The layers that hold compiled (numba) code; a change in any of their modules
#: recompiles all.
COMPILED_LAYERS = ("model", "solver")


def compiled_sources() -> list[Path]:
    """The source files of :data:`COMPILED_LAYERS`, in a fixed order."""
    package = Path(__file__).parent
    return sorted(p for layer in COMPILED_LAYERS for p in (package / layer).glob("*.py"))


def source_hash() -> str:
    """SHA-256 (first 16 hex digits) of the modules of the compiled layers."""
    package = Path(__file__).parent
    digest = hashlib.sha256()
    for path in compiled_sources():
        digest.update(str(path.relative_to(package)).encode())
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
