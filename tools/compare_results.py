"""Compare two ``results/`` folders file by file: are they the same results?

Usage: ``python tools/compare_results.py OLD_RESULTS NEW_RESULTS [--also-differ ATTR ...]``

netCDF files: every data variable and coordinate bit for bit (values, dtype, dimensions,
attributes), except wall-clock measurements (variables with a ``timing`` attribute), and
every global attribute except those that differ between two runs of one job
(:data:`tennis_stroke.io.netcdf.RUN_ATTRS`) and ``--also-differ`` (e.g. ``git_commit`` across
commits).  CSV files: equal cell for cell.  When the two folders' files record different
software environments (the lock's hash, whether the environment was the lock), says so.
PNG figures are not compared (matplotlib output is not a result).  Prints one line per
file and exits 1 if any differs or is missing on one side.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from tennis_stroke.io.compare import result_differences
from tennis_stroke.io.errors import ResultError
from tennis_stroke.io.netcdf import load_result


def compare(old: Path, new: Path, also_differ: list[str]) -> int:
    names = sorted(
        {str(p.relative_to(root)) for root in (old, new) for p in root.rglob("*") if p.is_file()}
    )
    bad = 0
    for name in names:
        if name.endswith(".png"):
            continue
        a, b = old / name, new / name
        if not (a.exists() and b.exists()):
            print(f"MISSING {name}: only in {'old' if a.exists() else 'new'}")
            bad += 1
            continue
        if name.endswith(".nc"):
            try:
                problems = result_differences(a, b, also_differ)
            except ResultError as exc:  # a damaged file differs from anything
                problems = [str(exc)]
        elif name.endswith(".csv"):
            same = pd.read_csv(a, keep_default_na=False).equals(
                pd.read_csv(b, keep_default_na=False)
            )
            problems = [] if same else ["tables differ"]
        else:
            problems = [] if a.read_bytes() == b.read_bytes() else ["bytes differ"]
        print(f"{'same' if not problems else 'DIFFERS'} {name}")
        for problem in problems:
            print(f"    {problem}")
        bad += bool(problems)
    print(f"{bad} of {len([n for n in names if not n.endswith('.png')])} files differ")
    envs = {side: environments(root) for side, root in (("old", old), ("new", new))}
    if envs["old"] != envs["new"]:
        print("ENVIRONMENTS differ: the folders were made by different software environments")
        for side, found in envs.items():
            print(f"    {side}: {'; '.join(sorted(found)) or 'none recorded'}")
    return 1 if bad else 0


def environments(root: Path) -> set[str]:
    """The environments the netCDF files below ``root`` record: the lock's hash and
    whether the writing environment was the lock (tennis_stroke.io.environment)."""
    out = set()
    for path in sorted(root.rglob("*.nc")):
        try:
            attrs = load_result(path).attrs
        except ResultError:
            continue
        lock = attrs.get("environment_lock_sha256_16", "not recorded")
        out.add(f"lock {lock}, environment is the lock: {attrs.get('environment_is_lock', '?')}")
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--also-differ", nargs="*", default=[], metavar="ATTR")
    args = parser.parse_args()
    return compare(args.old, args.new, args.also_differ)


if __name__ == "__main__":
    sys.exit(main())
