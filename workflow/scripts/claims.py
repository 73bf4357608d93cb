"""Evaluate config/claims.yaml against the results into results/claims.csv, with each
claim's robustness across the consistent readings and each deviation's evidence."""

import xarray as xr

from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.reading_space import load_reading_space
from tennis_stroke.pipeline.jobs import logged
from tennis_stroke.replication.claims import evaluate
from tennis_stroke.replication.robustness import annotate

with logged(snakemake.log[0]):
    claims = load_claims(snakemake.input.claims)
    space = load_reading_space(snakemake.input.readings, [c["id"] for c in claims])
    files = {k: xr.load_dataset(v) for k, v in snakemake.params.files.items()}
    table = evaluate(claims, files, space.fit_of_claim())
    robustness = xr.load_dataset(snakemake.input.robustness)
    table = annotate(table, robustness, space, claims, files)
    table.to_csv(snakemake.output[0], index=False)
    print(table[["id", "reproduced_value", "status", "robustness", "evidence"]].to_string())
