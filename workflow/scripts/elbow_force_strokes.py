"""Table I and Fig. 14: the tau_H stroke without and with the elbow force of Eq. 14."""

import numpy as np

from tennis_stroke.experiments import trajectories
from tennis_stroke.pipeline import Timer, logged, save, settings

p = snakemake.params
f, d = p.force, p.delay
with logged(snakemake.log[0]):
    clock = Timer()
    tau_h = d["strokes"]["tau_H"]
    base = {"L1": d["L1"], "C2": d["fig9"]["C2"], "tau": tau_h, "t_d": f["t_d"], "t_F": tau_h}
    cases = [{**base, "F0": f["F0"], "psi_F_deg": psi} for psi in f["table1_psi"]]
    cases.append({**base, "F0": 0.0})
    labels = [f"F0={f['F0']:g} N, psi={psi:g} deg" for psi in f["table1_psi"]] + ["no force"]
    strokes = [(d["theta0"], d["fig9"]["delta0"], case) for case in cases]
    times = np.linspace(0.0, d["strokes"]["t_end"], d["strokes"]["samples"])
    ds = trajectories(strokes, labels, times, p.common["model"], settings(p.common), p.curves)
    ds["psi_F"] = (
        "stroke",
        [*f["table1_psi"], np.nan],
        {"units": "degree", "long_name": "force direction"},
    )
    ds["F0"] = (
        "stroke",
        [f["F0"]] * len(f["table1_psi"]) + [0.0],
        {"units": "N", "long_name": "force amplitude"},
    )
    save(ds, snakemake.output[0], p, clock())
