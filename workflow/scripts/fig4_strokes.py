"""Fig. 4: omega1(t), omega2(t) of the two strokes."""

import numpy as np

from tennis_stroke.experiments.maps import trajectories
from tennis_stroke.pipeline import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    strokes = [(a, b, {}) for a, b in p.strokes]
    labels = [f"({a:g}, {b:g})" for a, b in p.strokes]
    times = np.linspace(0.0, p.t_end, p.samples)
    ds = trajectories(strokes, labels, times, p.common["model"], settings(p.common), p.curves)
    save(ds, snakemake.output[0], p, clock())
