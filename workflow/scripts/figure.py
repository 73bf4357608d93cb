"""Draw one figure from its result files."""

from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.figures import draw

with logged(snakemake.log[0]):
    data = [p for p in snakemake.input if p.endswith(".nc")]
    draw(snakemake.wildcards.name, data, snakemake.output[0])
