"""Figs. 7-9: v_out over the wrist-torque delay and C2 (Fig. 7) or delta0 (Figs. 8-9),
one chunk of rows of C2 or delta0."""

import numpy as np

from tennis_stroke.experiments.maps import delay_map
from tennis_stroke.pipeline import Timer, axis, chunk, logged, save, settings

p = snakemake.params
s = p.section
with logged(snakemake.log[0]):
    clock = Timer()
    model = {**p.common["model"], "L1": s["L1"]}
    tau = axis(s["tau"])
    if isinstance(s["C2"], dict):  # Fig. 7: (C2, tau) at fixed delta0
        ds = delay_map(
            "C2",
            chunk(axis(s["C2"]), snakemake.wildcards),
            ("N m", "wrist torque C2"),
            tau,
            s["theta0"],
            s["delta0"],
            model,
            settings(p.common),
            snakemake.threads,
        )
    else:  # Figs. 8-9: (delta0, tau) at fixed C2
        delta0 = (
            axis(s["delta0"]) if isinstance(s["delta0"], dict) else np.array([float(s["delta0"])])
        )
        ds = delay_map(
            "delta0",
            chunk(delta0, snakemake.wildcards),
            ("degree", "initial angle between the rods"),
            tau,
            s["theta0"],
            None,
            {**model, "C2": s["C2"]},
            settings(p.common),
            snakemake.threads,
        )
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
