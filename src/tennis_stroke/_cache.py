"""Where numba caches the compiled solver.

numba's on-disk cache checks only the source file of each compiled function, not the
modules it calls, so a change in ``dynamics.py`` would not recompile ``stroke.py``.  The
cache directory is therefore keyed by a hash of the modules with compiled code: a change
in any of them starts a fresh cache, and an unchanged package reloads in a new process
without compiling.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

#: The modules that hold compiled (numba) code; a change in any of them recompiles all.
COMPILED_MODULES = ("dynamics.py", "_kernels.py", "integrate.py", "stroke.py")


def source_hash() -> str:
    """SHA-256 (first 16 hex digits) of the modules with compiled code."""
    digest = hashlib.sha256()
    for name in COMPILED_MODULES:
        digest.update(name.encode())
        digest.update((Path(__file__).parent / name).read_bytes())
    return digest.hexdigest()[:16]


def configure_numba_cache() -> None:
    """Point ``NUMBA_CACHE_DIR`` at a per-source-hash directory unless the user set one.

    Only effective before numba is first imported (numba reads it at import).
    """
    if "NUMBA_CACHE_DIR" in os.environ:
        return
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
    os.environ["NUMBA_CACHE_DIR"] = str(base / "tennis-stroke" / "numba" / source_hash())
