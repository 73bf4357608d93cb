"""The robustness analysis, step 1: the declared Sobol candidates screened against both
fit sets, and the consistent readings kept (config/readings.yaml, multiverse)."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.multiverse import best_fits, readings_dataset, screen
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline.jobs import Timer, logged, save, settings

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    fits = {n: load_result(snakemake.input[f"{n}_fits"]) for n in space.fits}
    screened = screen(
        space,
        claims,
        p.fig4_strokes,
        p.force,
        p.stroke,
        p.common["model"],
        best_fits(fits),
        settings(p.common),
        snakemake.threads,
    )
    kept = readings_dataset(space, screened)
    print(f"consistent: {int(screened['consistent'].sum())}; kept: {kept.sizes['reading']}")
    seconds = clock()
    save(screened, snakemake.output.screen, p, seconds)
    save(kept, snakemake.output.readings, p, seconds)
