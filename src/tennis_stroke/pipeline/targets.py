"""Every file the replication ends in, for naming them as Snakemake targets.

Snakemake (7.7 and later) does not rebuild an intermediate file deleted by hand while
the files after it are present and up to date (``rm results/claims.csv; snakemake -n
report`` said "Nothing to be done": snakemake/snakemake#1978): it stops at a job whose
output is up to date.  The target rules ``report`` and ``all`` therefore have no output
and take the page and every result, figure and table as inputs (:func:`targets`), so
``snakemake -j2 report`` plans the job of a missing one; ``python -m
tennis_stroke.pipeline.targets`` prints them, one per line.

A damaged result file (truncated, or garbage) is no better than a missing one, but
Snakemake would take it for up to date: the workflow refuses to run over one, naming it
and the way out (:func:`damaged_results`).  So it does over a whole file at a row's path
that the row's job did not write (:func:`foreign_results`: ``tennis-stroke sweep --out
results/angle_maps/fig2.nc``), which every job reading it would fail on.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..experiments.specs import EXPERIMENTS, RESULT_FILES
from ..io.netcdf import damage
from ..replication.registry import FIGURES

#: The claims table and the report page (written by the claims and report rules).
TABLES = ("results/claims.csv", "report/index.html")
#: The replication's article and its ReScience metadata (rule article).
ARTICLE = ("report/article.pdf", "report/metadata.yaml")


def targets() -> list[str]:
    """The report, the claims table, the article, every result file and every figure."""
    figures = [f"results/figures/{name}.png" for name in sorted(FIGURES)]
    return [*TABLES, *ARTICLE, *RESULT_FILES.values(), *figures]


def damaged_results(results: str | Path = "results") -> list[tuple[str, str]]:
    """The netCDF files under ``results`` (chunks included) that are damaged, with why
    (:func:`tennis_stroke.io.netcdf.damage`): checked before every run, as Snakemake
    would take a truncated file whose inputs are older for up to date."""
    out = []
    if Path(results).exists() and not Path(results).is_dir():
        return [(str(results), "a file where the results folder should be")]
    for path in sorted(Path(results).rglob("*.nc")):
        problem = damage(path)
        if problem is not None:
            out.append((str(path), problem))
    return out


def foreign_results(results: str | Path = "results") -> list[tuple[str, str]]:
    """The result files of the table's rows at their paths under ``results`` that are not
    their row's job's, with why: a file without one of the row's variables
    (:attr:`~tennis_stroke.experiments.specs.Experiment.variables`), or whose provenance
    (the attribute ``config`` every job writes, :func:`tennis_stroke.pipeline.jobs.save`)
    names no experiment or another.  Damaged files are :func:`damaged_results`'; a file
    that cannot be opened is left to the job that reads it.  Reads each file's header
    only."""
    import netCDF4

    out = []
    for key, row in EXPERIMENTS.items():
        path = Path(results) / Path(row.path).relative_to("results")
        if not path.is_file() or damage(path) is not None:
            continue
        try:
            with netCDF4.Dataset(path) as ds:
                names = set(ds.variables)
                config = ds.getncattr("config") if "config" in ds.ncattrs() else None
        except (OSError, RuntimeError):
            continue
        missing = [v for v in row.variables if v not in names]
        try:
            named = json.loads(config)["experiment"]["key"] if config is not None else None
        except (ValueError, TypeError, KeyError):
            named = None
        if missing:
            why = f"it lacks the variables {', '.join(missing)} of experiment {key!r}"
        elif named != key:
            why = (
                f"its provenance names experiment {named!r}, not {key!r}"
                if named is not None
                else "it records no experiment of this workflow (attribute 'config')"
            )
        else:
            continue
        out.append((str(path), why))
    return out


if __name__ == "__main__":
    print("\n".join(targets()))
