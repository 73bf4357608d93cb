"""The targeted evaluation of the claims checked against the full maps on kept readings
(config/readings.yaml, multiverse.validation), for one group of searched files."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.inference.validation import validate
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    kept = load_result(snakemake.input.kept)
    config = {**p.experiments, "model": p.common["model"]}
    group = snakemake.wildcards.group
    ds = validate(claims, space, kept, config, settings(p.common), snakemake.threads, group)
    worst = ds["difference"].where(ds["tolerance"] > 0).max("reading")
    print(worst.to_series().sort_values(ascending=False).head(10).to_string())
    save(ds, snakemake.output[0], p, clock())
