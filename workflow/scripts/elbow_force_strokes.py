"""Table I and Fig. 14: the tau_H stroke without and with the elbow force of Eq. 14."""

import numpy as np

from tennis_stroke.experiments.maps import trajectories
from tennis_stroke.pipeline import Timer, logged, save, settings

p = snakemake.params
f, s = p.force, p.stroke
with logged(snakemake.log[0]):
    clock = Timer()
    base = {"L1": s["L1"], "C2": s["C2"], "tau": s["tau_H"], "t_d": f["t_d"], "t_F": s["tau_H"]}
    cases = [{**base, "F0": f["F0"], "psi_F_deg": psi} for psi in f["table1_psi"]]
    cases.append({**base, "F0": 0.0})
    labels = [f"F0={f['F0']:g} N, psi={psi:g} deg" for psi in f["table1_psi"]] + ["no force"]
    strokes = [(s["theta0"], s["delta0"], case) for case in cases]
    times = np.linspace(0.0, s["t_end"], s["samples"])
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
