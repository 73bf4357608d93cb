"""Where the compiled solver's time goes, function by function, with ``perf``.

Solves the 241 x 181 bench grid (Fig. 2's angles, default settings, one thread) 15
times, after writing ``/tmp/perf-<pid>.map``: the address and name of every function of
the compiled stroke batch, so that ``perf report`` names numba's machine code instead of
printing bare addresses (sizes are the gaps between the addresses, so a share may
include padding).  The solver must compile in this process (numba keeps the code's
names only then), hence the fresh cache and no warm-up subprocess::

    TENNIS_STROKE_WARMUP=0 NUMBA_CACHE_DIR=$(mktemp -d) \\
        perf record -o /tmp/perf.data .venv/bin/python benchmarks/profile_solver.py
    perf report -i /tmp/perf.data --sort dso,symbol | grep -E 'JIT|libm'

The shares are of the whole process, compilation included; compare the compiled
functions with each other.  Not a test; ``perf`` comes with the Debian package
``linux-perf``.
"""

from __future__ import annotations

import os

import numpy as np

from tennis_stroke import SolverSettings, strike_batch
from tennis_stroke.solver import stroke

THETA0 = np.linspace(60.0, 120.0, 241)[:, None]
DELTA0 = np.linspace(0.0, 90.0, 181)[None, :]


def function_addresses() -> list[tuple[int, str]]:
    """``(address, name)`` of every function defined in the stroke batch's compiled
    libraries (the ones it links included)."""
    found, seen = set(), set()

    def walk(library):
        if id(library) in seen:
            return
        seen.add(id(library))
        for fn in library._final_module.functions:
            if not fn.is_declaration:
                address = library._codegen._engine.get_function_address(fn.name)
                if address:
                    found.add((address, fn.name))
        for linked in getattr(library, "_linking_libraries", ()):
            walk(linked)

    for overload in stroke.solve_rows.overloads.values():
        walk(overload.library)
    return sorted(found)


def main() -> None:
    settings = SolverSettings()
    strike_batch(THETA0[:2], DELTA0, settings=settings, threads=1)  # compiles
    entries = function_addresses()
    if not entries:
        raise SystemExit("no compiled functions found: run with TENNIS_STROKE_WARMUP=0")
    with open(f"/tmp/perf-{os.getpid()}.map", "w") as out:
        for i, (address, name) in enumerate(entries):
            size = entries[i + 1][0] - address if i + 1 < len(entries) else 4096
            out.write(f"{address:x} {size:x} {name}\n")
    for _ in range(15):
        strike_batch(THETA0, DELTA0, settings=settings, threads=1)
    print(f"{len(entries)} functions mapped in /tmp/perf-{os.getpid()}.map")


if __name__ == "__main__":
    main()
