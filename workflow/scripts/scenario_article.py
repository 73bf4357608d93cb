"""Write a scenario's article (report/scenarios/NAME/article.pdf) from its results."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.scenario_article import build_scenario_article

with logged(snakemake.log[0]):
    build_scenario_article(
        scenario=snakemake.params.scenario,
        comparisons=list(snakemake.input.comparisons),
        claims_csv=snakemake.input.claims,
        claims_yaml=snakemake.input.statements,
        output_pdf=snakemake.output[0],
    )
