"""Fig. 13: v_out over the direction and delay of the extra elbow force (Eq. 14),
one chunk of psi_F rows."""

from tennis_stroke.experiments.maps import elbow_force_section_map
from tennis_stroke.pipeline.jobs import Timer, chunk_position, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    solver, rows = settings(p.common), chunk_position(snakemake.wildcards)
    ds = elbow_force_section_map(
        p.force, p.psi_F, p.tau_F, p.stroke, p.common["model"], solver, rows, snakemake.threads
    )
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
