"""Figs. 5-6: the fastest rebound over the initial angles at every (M2, L1), one chunk
of M2 rows."""

from tennis_stroke.experiments.grids import axis
from tennis_stroke.experiments.maps import mass_length_map
from tennis_stroke.pipeline.jobs import Timer, chunk, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    ds = mass_length_map(
        chunk(axis(p.M2), snakemake.wildcards),
        axis(p.L1),
        p.coarse_step,
        p.fine_step,
        tuple(p.theta0_range),
        tuple(p.delta0_range),
        p.common["model"],
        settings(p.common),
        snakemake.threads,
    )
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
