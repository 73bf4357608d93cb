"""Figs. 2-3: v_out over (theta0, delta0) at the figure's L1 (one chunk of theta0 rows)."""

from tennis_stroke.experiments.grids import axis
from tennis_stroke.experiments.maps import angle_map
from tennis_stroke.pipeline.jobs import Timer, chunk, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    model = {**p.common["model"], "L1": p.L1}
    theta0 = chunk(axis(p.theta0), snakemake.wildcards)
    ds = angle_map(theta0, axis(p.delta0), model, settings(p.common), snakemake.threads)
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
