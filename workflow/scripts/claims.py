"""Evaluate config/claims.yaml into a claims table: each claim measured on the targeted
evaluation of the default reading (its optima and threshold by a search), on the
workflow's maps as map_value; for the paper's configuration with its robustness across
the consistent readings and each deviation's evidence.  Beside the table, the record of
the configuration it was computed under (a scenario's, or where it departs from the
paper's)."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.inference.paper_config import (
    configuration_record,
    load_paper_inputs,
    write_record,
)
from tennis_stroke.inference.reading_space import claims_and_readings
from tennis_stroke.inference.targeted import searched_files
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.pipeline.jobs import logged, settings
from tennis_stroke.replication.claims import evaluate
from tennis_stroke.replication.robustness import annotate

p = snakemake.params
with logged(snakemake.log[0]):
    claims, space = claims_and_readings(snakemake.input.claims, snakemake.input.readings)
    maps = {k: load_result(v) for k, v in p.files.items()}
    config = {**p.experiments, "model": p.common["model"]}
    found = searched_files(config, p.common["model"], settings(p.common), None, snakemake.threads)
    flat_gap = space.raw["evidence"]["flat_gap"]
    table = evaluate(claims, {**maps, **found}, space.fit_of_claim(), maps, flat_gap)
    if "robustness" in snakemake.input.keys():
        robustness = load_result(snakemake.input.robustness)
        table = annotate(table, robustness, space, claims)
    table.to_csv(snakemake.output.claims, index=False)
    inputs = load_paper_inputs(snakemake.input.claims)
    write_record(configuration_record(config, inputs, p.scenario), snakemake.output.configuration)
    print(table[["id", "reproduced_value", "map_value", "status"]].to_string())
