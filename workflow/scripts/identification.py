"""Identification as a fit (config/readings.yaml): fits, profiles and leave-one-out of
both declared fit sets, one netCDF file each."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.identification import run_identification, summary, to_datasets
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    solver = settings(p.common)
    results = run_identification(
        space, claims, p.fig4_strokes, p.force, p.stroke, p.common["model"], solver
    )
    print(summary(results))
    seconds = clock()
    for name, result in results.items():
        for kind, ds in to_datasets(result, solver).items():
            save(ds, snakemake.output[f"{name}_{kind}"], p, seconds)
