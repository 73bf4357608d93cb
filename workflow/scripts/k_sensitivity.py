"""Sec. II: v_out of the Fig. 4 strokes over the paper's range of the spring constant."""

from tennis_stroke.experiments.maps import k_sensitivity_map
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    model, solver = p.common["model"], settings(p.common)
    ds = k_sensitivity_map(p.strokes, p.k_contact, p.points, model, solver, snakemake.threads)
    save(ds, snakemake.output[0], p, clock())
