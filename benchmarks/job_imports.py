"""What each workflow job pays for its imports before it works: every script's top-level
imports run in a fresh interpreter (as Snakemake starts each job), ``--runs`` times;
prints each script's median seconds and the heavy modules it loaded
(``tests/workflow/test_job_imports.py`` asserts which may not be).

``--checkout DIR`` measures another checkout's scripts and package (``DIR/src`` first on
the path): a ``git worktree`` of an older commit, side by side with this one.

Usage::

    python benchmarks/job_imports.py [--runs 3] [--checkout DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from scripts import top_level_imports  # noqa: E402

HEAVY = ("numba", "scipy.optimize", "scipy.integrate", "matplotlib", "bokeh", "xarray")
PROBE = """
import time
start = time.perf_counter()
{imports}
import json, sys
print(json.dumps([time.perf_counter() - start, [m for m in {heavy!r} if m in sys.modules]]))
"""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--checkout", type=Path, default=ROOT)
    args = parser.parse_args(argv)
    env = {**os.environ, "PYTHONPATH": str(args.checkout.resolve() / "src")}
    for script in sorted((args.checkout / "workflow" / "scripts").glob("*.py")):
        code = PROBE.format(imports=top_level_imports(script), heavy=list(HEAVY))
        times = []
        for _ in range(args.runs):
            done = subprocess.run(
                [sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env
            )
            seconds, loaded = json.loads(done.stdout.strip().splitlines()[-1])
            times.append(seconds)
        shown = " ".join(loaded) or "-"
        print(f"{script.name:24s} {statistics.median(times):5.2f} s  {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
