"""The robustness analysis, step 2: every claim under one chunk of the kept readings."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.inference.robustness import evaluate_readings
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline.jobs import Timer, chunk_position, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    kept = load_result(snakemake.input.kept)
    config = {**p.experiments, "model": p.common["model"]}
    rows = chunk_position(snakemake.wildcards)
    ds = evaluate_readings(claims, space, kept, config, settings(p.common), rows, snakemake.threads)
    save(ds, snakemake.output[0], p, clock(), chunk_of=snakemake.wildcards)
