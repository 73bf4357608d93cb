"""What the Snakemake workflow runs besides the science: the config checks before any
job, the memory estimates, the thin scripts' helpers (settings, logging, provenance),
the chunks of a map gathered again, the scenarios, and a what-if's plan (its targets and
Snakemake's command line, :mod:`.whatif`).  The top of the package, with the CLI.
"""
