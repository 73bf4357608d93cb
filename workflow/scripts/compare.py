"""Draw a scenario's figure against the paper's: shared scales and the difference (its
registry entry, the paper's marks and the scenario's changes are params of the job)."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.compare import comparison
from tennis_stroke.replication.registry import Figure

with logged(snakemake.log[0]):
    figure = Figure(**snakemake.params.figure)
    comparison(
        figure,
        snakemake.input.paper,
        snakemake.input.scenario,
        snakemake.output[0],
        snakemake.wildcards.scenario,
        snakemake.params.note,
        snakemake.params.marks,
    )
