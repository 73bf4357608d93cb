"""Fig. 13: v_out over the direction and delay of the extra elbow force (Eq. 14)."""

from tennis_stroke.experiments import elbow_force_map
from tennis_stroke.pipeline import Timer, axis, logged, save, settings

p = snakemake.params
f, d = p.force, p.delay
with logged(snakemake.log[0]):
    clock = Timer()
    tau_h = d["strokes"]["tau_H"]
    model = {
        **p.common["model"],
        "L1": d["L1"],
        "C2": d["fig9"]["C2"],
        "tau": tau_h,
        "F0": f["F0"],
        "t_d": f["t_d"],
    }
    ds = elbow_force_map(
        axis(p.psi_F),
        axis(p.tau_F),
        tau_h,
        d["theta0"],
        d["fig9"]["delta0"],
        model,
        settings(p.common),
        snakemake.threads,
    )
    save(ds, snakemake.output[0], p, clock())
