"""Fig. 4: omega1(t), omega2(t) of the two strokes."""

from tennis_stroke.experiments.strokes import fig4_strokes
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    model, solver = p.common["model"], settings(p.common)
    ds = fig4_strokes(p.strokes, p.t_end, p.samples, model, solver, p.curves)
    save(ds, snakemake.output[0], p, clock())
