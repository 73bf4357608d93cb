"""The report job's work alone: ``build_report`` as ``workflow/scripts/report.py`` calls it,
on the results of a finished ``make report`` in the current directory, the page written to
a temporary file (``report/index.html`` is left alone).  Time the whole process, e.g. in
a checkout of two commits in turn (the results copied into each)::

    /usr/bin/time -f "%U user %S sys" python benchmarks/report_job.py
"""

import tempfile
from pathlib import Path

import yaml

from tennis_stroke.experiments.specs import INFERENCE_RESULTS, PAPER_RESULTS, RESULT_FILES
from tennis_stroke.replication.registry import FIGURES
from tennis_stroke.replication.report import build_report

with tempfile.TemporaryDirectory() as tmp:
    build_report(
        figures=[f"results/figures/{name}.png" for name in sorted(FIGURES)],
        claims_csv="results/claims.csv",
        inference=INFERENCE_RESULTS,
        results=list(PAPER_RESULTS.values()),
        config=yaml.safe_load(Path("config/config.yaml").read_text()),
        benchmarks_dir="logs/benchmarks",
        output=str(Path(tmp) / "index.html"),
        assumptions_md="docs/assumptions.md",
        studies=[RESULT_FILES[k] for k in ("ladder", "optimum_cost", "stability")],
        statements_yaml="config/claims.yaml",
    )
