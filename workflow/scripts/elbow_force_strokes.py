"""Table I and Fig. 14: the tau_H stroke without and with the elbow force of Eq. 14."""

from tennis_stroke.experiments.strokes import elbow_force_strokes
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    ds = elbow_force_strokes(p.force, p.stroke, p.common["model"], settings(p.common), p.curves)
    save(ds, snakemake.output[0], p, clock())
