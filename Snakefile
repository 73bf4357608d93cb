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


rule all:
    input:
        "report/index.html",
