"""Build report/index.html from the figures, claims, ledger and run metadata."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.experiments.specs import INFERENCE_RESULTS, STUDY_RESULTS
from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.report import build_report

with logged(snakemake.log[0]):
    build_report(
        figures=list(snakemake.input.figures),
        claims_csv=snakemake.input.claims,
        inference=INFERENCE_RESULTS,
        results=list(snakemake.input.results),
        config=snakemake.params.config,
        benchmarks_dir=snakemake.params.benchmarks,
        output=snakemake.output[0],
        assumptions_md=snakemake.input.assumptions,
        studies=STUDY_RESULTS,
        statements_yaml=snakemake.input.statements,
    )
