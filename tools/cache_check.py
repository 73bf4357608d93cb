"""Can Snakemake and numba use the cache folders the environment names?

Usage::

    .venv/bin/python tools/cache_check.py     # make report runs it first

Exit 2 with one line naming the variable (``HOME``, ``XDG_CACHE_HOME``,
``NUMBA_CACHE_DIR``) when one names a file or a folder that cannot be written: Snakemake
would stop on it with a long traceback before reading the Snakefile
(``tennis_stroke._cache.cache_problem``).  ``tennis-stroke whatif`` asks the same.
"""

from __future__ import annotations

import sys

from tennis_stroke._cache import cache_problem

if __name__ == "__main__":
    problem = cache_problem()
    if problem:
        sys.stderr.write(f"tennis-stroke: error: {problem}\n")
        sys.exit(2)
