"""Evaluate config/claims.yaml against the results into results/claims.csv."""

from tennis_stroke.pipeline import logged
from tennis_stroke.replication.claims import evaluate, load_claims

with logged(snakemake.log[0]):
    table = evaluate(load_claims(snakemake.input.claims), snakemake.params.files)
    table.to_csv(snakemake.output[0], index=False)
    print(table[["id", "paper_value", "reproduced_value", "tolerance", "status"]].to_string())
