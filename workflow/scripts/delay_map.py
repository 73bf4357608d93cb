"""Figs. 7-9: v_out over the wrist-torque delay and C2 (Fig. 7) or delta0 (Figs. 8-9),
one chunk of rows of C2 or delta0."""

from tennis_stroke.experiments.maps import torque_delay_map
from tennis_stroke.pipeline.jobs import Timer, chunk_position, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    rows = chunk_position(snakemake.wildcards)
    ds = torque_delay_map(p.section, p.common["model"], settings(p.common), rows, snakemake.threads)
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
