"""Build report/index.html from the figures, claims, ledger and run metadata."""

from tennis_stroke.pipeline import logged
from tennis_stroke.report import build_report

with logged(snakemake.log[0]):  # noqa: F821
    build_report(  # noqa: F821
        figures=list(snakemake.input.figures),  # noqa: F821
        claims_csv=snakemake.input.claims,  # noqa: F821
        readings_csv=snakemake.input.readings,  # noqa: F821
        results=list(snakemake.input.results),  # noqa: F821
        config=snakemake.params.config,  # noqa: F821
        benchmarks_dir=snakemake.params.benchmarks,  # noqa: F821
        output=snakemake.output[0],  # noqa: F821
    )
