"""Write report/article.pdf and report/metadata.yaml from the results."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from pathlib import Path

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.article import build_article, job_seconds

with logged(snakemake.log[0]):
    build_article(
        claims_csv=snakemake.input.claims,
        claims_yaml=snakemake.input.statements,
        figures=list(snakemake.input.figures),
        results=list(snakemake.input.results),
        output_pdf=snakemake.output.pdf,
        output_metadata=snakemake.output.metadata,
        job_seconds=job_seconds(Path(snakemake.params.benchmarks)),
        lock=snakemake.input.lock,
        pyproject=snakemake.input.pyproject,
        work_precision=snakemake.input.work_precision,
        citation=snakemake.input.citation,
    )
