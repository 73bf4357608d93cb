"""One row of the table of experiments (``tennis_stroke.experiments.specs``): its function
on the config values the rule passes, for the whole file or one chunk of its first axis."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.experiments.specs import EXPERIMENTS, compute
from tennis_stroke.pipeline.jobs import Timer, chunk_position, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    experiment = EXPERIMENTS[p.experiment["key"]]
    chunk = snakemake.wildcards if experiment.chunks else None
    rows = chunk_position(chunk) if chunk is not None else None
    model = p.common["model"] if experiment.model else None
    solver = settings(p.common) if experiment.model else None
    ds = compute(experiment, p.args, model, solver, rows, snakemake.threads)
    row = {k: v for k, v in p.items() if v is not None}  # a row without the model: no common
    save(ds, snakemake.output[0], row, clock(), chunk_of=chunk)
