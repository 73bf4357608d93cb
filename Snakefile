# The workflow is workflow/Snakefile (Snakemake's standardized layout); this file lets
# `snakemake -s Snakefile` and tools that look for a root Snakefile find it.
include: "workflow/Snakefile"
