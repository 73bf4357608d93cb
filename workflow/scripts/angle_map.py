"""Figs. 2-3: v_out over (theta0, delta0) for one L1."""

from tennis_stroke.experiments import angle_map
from tennis_stroke.pipeline import Timer, axis, logged, save, settings

p = snakemake.params  # noqa: F821
with logged(snakemake.log[0]):  # noqa: F821
    clock = Timer()
    model = {**p.common["model"], "L1": float(snakemake.wildcards.L1)}  # noqa: F821
    ds = angle_map(axis(p.theta0), axis(p.delta0), model, settings(p.common),
                   snakemake.threads)  # noqa: F821
    save(ds, snakemake.output[0], p.common, clock())  # noqa: F821
