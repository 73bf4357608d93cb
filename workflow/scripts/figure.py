"""Draw one figure from its result files (its registry entry and the paper's values of
the claims it marks are params of the job)."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.figures import draw
from tennis_stroke.replication.registry import Figure

with logged(snakemake.log[0]):
    data = [p for p in snakemake.input if p.endswith(".nc")]
    figure = Figure(**snakemake.params.figure)
    draw(figure, data, snakemake.output[0], snakemake.params.note, snakemake.params.marks)
