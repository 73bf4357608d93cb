"""Figs. 10-12: the strokes with the wrist torque delayed by tau_L and tau_H."""

import numpy as np

from tennis_stroke.experiments.maps import trajectories
from tennis_stroke.pipeline import Timer, logged, save, settings

p = snakemake.params
s = p.stroke
with logged(snakemake.log[0]):
    clock = Timer()
    extra = {"L1": s["L1"], "C2": s["C2"]}
    strokes = [(s["theta0"], s["delta0"], {**extra, "tau": s[k]}) for k in ("tau_L", "tau_H")]
    times = np.linspace(0.0, s["t_end"], s["samples"])
    ds = trajectories(
        strokes, ["tau_L", "tau_H"], times, p.common["model"], settings(p.common), p.curves
    )
    ds["tau"] = ("stroke", [s["tau_L"], s["tau_H"]], {"units": "s", "long_name": "delay of C2"})
    save(ds, snakemake.output[0], p, clock())
