"""What the Snakemake workflow runs besides the science: the config checks before any
job, the memory estimates, the thin scripts' helpers (settings, logging, provenance),
and the chunks of a map gathered again.  The top of the package, with the CLI.
"""
