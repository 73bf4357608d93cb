"""Where the cold compilation of the solver goes: each compiled function timed on its
first call in a fresh process with an empty numba cache, leaves first (a caller's time
excludes the callees already compiled).

Run: ``.venv/bin/python benchmarks/compile_time.py`` (about a minute: it compiles
everything once, in place, in a temporary cache).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

PROBE = """
import time
import numpy as np
from tennis_stroke.model.dynamics import coefficients, rhs_trig
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver import _kernels as K
from tennis_stroke.solver import stroke as S
from tennis_stroke.solver.integrate import HISTORY_COLS, N_STATS
from tennis_stroke.solver.settings import METHOD_IDS, SolverSettings

def timed(label, call, *args):
    t = time.perf_counter()
    out = call(*args)
    print(f"{label:36s} {time.perf_counter() - t:6.1f} s", flush=True)
    return out

rows = coefficients(resolve_params({}), np.array([90.0]), np.array([45.0]))
cf = timed("coefficient_tuple", K.coefficient_tuple, rows[0])
y = (1.0, 0.0, 0.7, 0.7, 0.0, 0.0, 1.5, 0.8, 0.0, 0.0)
f = timed("rhs_trig", rhs_trig, 0.0, y, cf, 0.0, False)
for method in ("dp54", "dop853"):
    for phase in ("swing", "contact"):
        step = getattr(K, f"step_{method}_{phase}")
        y1, f1, _ = timed(f"step_{method}_{phase}", step, 0.0, y, f, 1e-3, cf, 0.0, 1e-8, 1e-8)
        dense = getattr(K, f"dense_{method}")
        timed(f"dense_{method} ({phase})", dense, 0.0, y, f, 1e-3, cf, 0.0, y1, f1,
              phase == "contact")
st = SolverSettings().as_array()
out, history, stats = np.empty(S.N_OUT), np.zeros((513, HISTORY_COLS)), np.zeros(N_STATS)
timed("solve_stroke (the rest below it)", S.solve_stroke, METHOD_IDS["DOP853"], rows[0], st,
      out, history, stats)
timed("solve_rows (the range driver)", S.solve_rows, METHOD_IDS["DOP853"], rows, st,
      np.empty((1, S.N_OUT)), 0, 1, 512)
"""


def main() -> None:
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "TENNIS_STROKE_WARMUP": "0"}
        subprocess.run([sys.executable, "-c", PROBE], env=env, check=True)


if __name__ == "__main__":
    main()
