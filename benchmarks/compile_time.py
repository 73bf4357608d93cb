"""Where the cold compilation of the solver goes: the stroke batch of one method compiled
in a fresh process with an empty numba cache, each compiled function's own time
(exclusive of the functions it calls, from numba's ``numba:compile`` events), largest
first, and the total.

Run: ``.venv/bin/python benchmarks/compile_time.py [--method DOP853|DP54]`` (about half a
minute: it compiles once, in a temporary cache).  Timings vary with the machine's load:
compare runs side by side.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile

PROBE = """
import sys
import time
from collections import defaultdict

import numpy as np
from numba.core import event

from tennis_stroke.model.dynamics import coefficients
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver import stroke as S
from tennis_stroke.solver.settings import METHOD_IDS, SolverSettings

own = defaultdict(float)
stack = []


class Listener(event.Listener):
    def on_start(self, ev):
        stack.append([ev.data["dispatcher"].py_func.__qualname__, time.perf_counter(), 0.0])

    def on_end(self, ev):
        name, start, inner = stack.pop()
        spent = time.perf_counter() - start
        own[name] += spent - inner
        if stack:
            stack[-1][2] += spent


event.register("numba:compile", Listener())
method = sys.argv[1]
rows = coefficients(resolve_params({}), np.array([90.0]), np.array([45.0]))
start = time.perf_counter()
S.solve_rows(METHOD_IDS[method], rows, SolverSettings(method=method).as_array(),
             np.empty((1, S.N_OUT)), 0, 1, 512)
total = time.perf_counter() - start
for name, spent in sorted(own.items(), key=lambda kv: -kv[1])[:15]:
    print(f"{name:44s} {spent:6.2f} s")
print(f"{'total (' + str(len(own)) + ' functions)':44s} {total:6.2f} s")
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--method", default="DOP853", choices=("DOP853", "DP54"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "TENNIS_STROKE_WARMUP": "0"}
        subprocess.run([sys.executable, "-c", PROBE, args.method], env=env, check=True)


if __name__ == "__main__":
    main()
