"""Evaluate config/claims.yaml against the results into results/claims.csv."""

from tennis_stroke.experiments.reading_space import load_reading_space
from tennis_stroke.pipeline import logged
from tennis_stroke.replication.claims import evaluate, load_claims

with logged(snakemake.log[0]):
    claims = load_claims(snakemake.input.claims)
    space = load_reading_space(snakemake.input.readings, [c["id"] for c in claims])
    table = evaluate(claims, snakemake.params.files, space.fit_of_claim())
    table.to_csv(snakemake.output[0], index=False)
    print(table[["id", "paper_value", "reproduced_value", "tolerance", "status"]].to_string())
