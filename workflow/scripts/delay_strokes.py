"""Figs. 10-12: the strokes with the wrist torque delayed by tau_L and tau_H."""

from tennis_stroke.experiments.strokes import delay_strokes
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    ds = delay_strokes(p.stroke, p.common["model"], settings(p.common), p.curves)
    save(ds, snakemake.output[0], p, clock())
