"""Every file the replication ends in, for naming them as Snakemake targets.

Snakemake (7.7 and later) does not rebuild an intermediate file deleted by hand while
the files after it are present and up to date (``rm results/claims.csv; snakemake -n
report`` says "Nothing to be done": snakemake/snakemake#1978); a file named as a target is
rebuilt.  ``make report`` therefore names the report and every result, figure and the
claims table: ``python -m tennis_stroke.pipeline.targets`` prints them, one per line.
"""

from __future__ import annotations

from ..experiments.specs import RESULT_FILES
from ..replication.registry import FIGURES

#: The claims table and the report page (written by the claims and report rules).
TABLES = ("results/claims.csv", "report/index.html")


def targets() -> list[str]:
    """The report, the claims table, every result file and every figure."""
    figures = [f"results/figures/{name}.png" for name in sorted(FIGURES)]
    return [*TABLES, *RESULT_FILES.values(), *figures]


if __name__ == "__main__":
    print("\n".join(targets()))
