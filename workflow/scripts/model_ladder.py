"""Every claim under each rung of the model ladder (config model_ladder), by the targeted
evaluation at the default reading: results/ladder/claims_by_rung.nc."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.ladder import evaluate_ladder
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.pipeline.jobs import Timer, logged, save

p = snakemake.params
with logged(snakemake.log[0]):
    clock = Timer()
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    config = {
        **p.experiments,
        **p.common,
        "figure_curves": p.figure_curves,
        "model_ladder": p.ladder,
    }
    ds = evaluate_ladder(claims, config, snakemake.threads, space.fit_of_claim())
    print(ds["within"].sum("claim").to_series().to_string())
    save(ds, snakemake.output[0], p, clock())
