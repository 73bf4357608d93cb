"""Fig. 13: v_out over the direction and delay of the extra elbow force (Eq. 14),
one chunk of psi_F rows."""

from tennis_stroke.experiments.maps import elbow_force_map
from tennis_stroke.pipeline import Timer, axis, chunk, logged, save, settings

p = snakemake.params
f, s = p.force, p.stroke
with logged(snakemake.log[0]):
    clock = Timer()
    model = {
        **p.common["model"],
        "L1": s["L1"],
        "C2": s["C2"],
        "tau": s["tau_H"],
        "F0": f["F0"],
        "t_d": f["t_d"],
    }
    ds = elbow_force_map(
        chunk(axis(p.psi_F), snakemake.wildcards),
        axis(p.tau_F),
        s["tau_H"],
        s["theta0"],
        s["delta0"],
        model,
        settings(p.common),
        snakemake.threads,
    )
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
