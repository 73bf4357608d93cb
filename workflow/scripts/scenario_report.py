"""Build a scenario's page: its overrides, the figures it changes beside the paper
configuration's, every claim under both configurations."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.scenario_report import build_scenario_report

with logged(snakemake.log[0]):
    build_scenario_report(
        scenario=snakemake.params.scenario,
        figures=snakemake.params.figures,
        claims_csv=snakemake.input.claims,
        claims_yaml=snakemake.input.statements,
        output=snakemake.output[0],
    )
