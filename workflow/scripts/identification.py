"""Assumption ledger: score every candidate reading against the Fig. 4 claims."""

from tennis_stroke.experiments.identification import score_readings
from tennis_stroke.pipeline import logged, settings

with logged(snakemake.log[0]):
    table = score_readings(snakemake.params.targets, settings(snakemake.params.common))
    table.to_csv(snakemake.output[0], index=False)
    print(table.head(10).to_string())
