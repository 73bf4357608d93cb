"""Model ladder (spring contact vs instantaneous impact) and the optimum-search cost."""

from tennis_stroke.pipeline.jobs import Timer, logged, save
from tennis_stroke.studies.ladder import ladder
from tennis_stroke.studies.optimum_cost import optimum_cost
from tennis_stroke.studies.sampling import sample_strokes

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    save(ladder(sample_strokes(p.strokes, p.seed)), snakemake.output.ladder, p, clock())
    o = p.optimum
    ds = optimum_cost(o["M2"], o["L1"], [tuple(s) for s in o["steps"]], o["reference_step"])
    save(ds, snakemake.output.optimum, p, clock())
