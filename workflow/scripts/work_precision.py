"""Speed against accuracy: the work-precision table of every integrator."""

from tennis_stroke.pipeline.jobs import Timer, logged, save
from tennis_stroke.studies.sampling import sample_strokes
from tennis_stroke.studies.work_precision import work_precision

p = snakemake.params
s = p.study
with logged(snakemake.log[0]):
    clock = Timer()
    strokes = sample_strokes(s["strokes"], s["seed"])
    ds = work_precision(
        strokes,
        s["compiled_tolerances"],
        s["scipy_tolerances"],
        s["rk4_steps"],
        repeats=s["repeats"],
    )
    save(ds, snakemake.output[0], p, clock())
