# Replication of Youn, "Double pendulum model for tennis stroke including a collision
# process".  Run:  snakemake -j2 report   (see README.md).
from snakemake.utils import min_version

min_version("9.15")


include: "workflow/rules/config_file.smk"


configfile: "config/config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/experiments.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/report.smk"


# The report and every result, figure and table, named as inputs of a rule without
# output: Snakemake then rebuilds any of them lost while the files after it are present,
# which it does not for the inputs of a rule with output (snakemake/snakemake#1978;
# docs/workflow.md).  `snakemake -j2 report` and `make report` run the same jobs.
rule all:
    input:
        targets(),
