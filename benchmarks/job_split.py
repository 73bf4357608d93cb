"""Where the jobs of a finished run spent their time, by job kind.

Usage (after a run, from the project's folder)::

    python benchmarks/job_split.py [--logs logs] [--benchmarks logs/benchmarks]

Each job's log ends with the line :func:`tennis_stroke.pipeline.jobs.time_split` writes,
``job time (s): start-up S, imports I, compiled code C, compute X, writing W``: start-up
is the interpreter and Snakemake's preamble until the package's first import, imports
run until the job's block, compiled code is making sure of and loading the compiled
solver.  Each job's benchmark file (``logs/benchmarks``, Snakemake's ``benchmark:``)
gives its wall time ``s`` and CPU time ``cpu_time``.  The table sums both per job kind:
simulation, study, gather, inference, claims, figure, report.  Scenario jobs (below
``scenarios/``) are left out.  Run it on a run from empty results
(``rm -rf results report logs && snakemake -j2 report``): a job that
did not run this time keeps an older log.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import pandas as pd

from tennis_stroke.experiments.specs import EXPERIMENTS
from tennis_stroke.pipeline.jobs import SPLIT_PARTS, SPLIT_PREFIX

#: Rules that are not rows of the table of experiments, by kind.
KINDS = {
    "gather_map": "gather",
    "identification": "inference",
    "robustness_screen": "inference",
    "robustness_chunk": "inference",
    "claims_validation": "inference",
    "model_ladder": "inference",
    "claims": "claims",
    "report": "report",
    "report_page": "report",
}
ORDER = ("simulation", "study", "gather", "inference", "claims", "figure", "report")


def kind(job: str) -> str:
    """The kind of a job from its log or benchmark path below its folder
    (``angle_maps/fig2/0-of-1``, ``angle_maps/fig2_0-of-1``, ``strokes/fig4``,
    ``figure_fig02_angle_map``, ``gather_map/angle_maps/fig2``, ``claims``)."""
    rule = re.split(r"[/]", job)[0]
    if rule.startswith("figure_"):
        return "figure"
    rule = re.sub(r"_\d+-of-\d+$", "", rule)  # a chunk's benchmark: fig2_0-of-1
    for name in sorted(KINDS, key=len, reverse=True):  # claims_validation_fig7
        if rule == name or rule.startswith(f"{name}_"):
            return KINDS[name]
    stem = re.sub(r"[_/]\d+-of-\d+$", "", job)  # a row's job: its file's stem
    family = {e.stem: e.family for e in EXPERIMENTS.values()}.get(stem)
    if family is None:
        raise SystemExit(f"job_split: no kind for job {job!r}")
    return "study" if family == "study" else "simulation"


def _jobs(folder: Path, suffix: str):
    for path in sorted(folder.rglob(f"*{suffix}")):
        job = path.relative_to(folder).with_suffix("").as_posix()
        if not job.startswith("scenarios/"):
            yield job, path


def split_table(logs: Path, benchmarks: Path) -> pd.DataFrame:
    """Seconds per job kind: the jobs' own split (from their logs) and their wall and CPU
    time (from their benchmark files)."""
    rows = []
    pattern = re.compile(re.escape(SPLIT_PREFIX) + r" (.*)$", re.M)
    for job, path in _jobs(logs, ".log"):
        found = pattern.findall(path.read_text(errors="replace"))
        if not found:
            continue
        parts = dict(p.rsplit(" ", 1) for p in found[-1].split(", "))
        rows.append({"kind": kind(job), **{k: float(parts[k]) for k in SPLIT_PARTS}})
    split = pd.DataFrame(rows).groupby("kind").agg(["sum", "count"])
    table = pd.DataFrame({"jobs": split[(SPLIT_PARTS[0], "count")]})
    for part in SPLIT_PARTS:
        table[part] = split[(part, "sum")]
    costs = []
    for job, path in _jobs(benchmarks, ".tsv"):
        record = pd.read_csv(path, sep="\t").iloc[-1]
        costs.append({"kind": kind(job), "wall": record["s"], "cpu": record["cpu_time"]})
    cost = pd.DataFrame(costs).groupby("kind").agg(["sum", "count"])
    table["benchmark files"] = cost[("wall", "count")]
    table["wall"] = cost[("wall", "sum")]
    table["cpu"] = cost[("cpu", "sum")]
    table = table.reindex([k for k in ORDER if k in table.index])
    table.loc["all"] = table.sum()
    split_sum = table[list(SPLIT_PARTS)].sum(axis=1)
    table["start-up share"] = (
        table["start-up"] + table["imports"] + table["compiled code"]
    ) / split_sum
    return table


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--logs", type=Path, default=Path("logs"))
    parser.add_argument("--benchmarks", type=Path, default=Path("logs/benchmarks"))
    args = parser.parse_args(argv)
    for folder in (args.logs, args.benchmarks):
        if not folder.is_dir():
            print(f"job_split: no folder {str(folder)!r}: run the workflow first", file=sys.stderr)
            return 1
    table = split_table(args.logs, args.benchmarks)
    print(table.to_markdown(floatfmt=".2f"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
