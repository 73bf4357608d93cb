"""Files: result files (netCDF with CF attributes and provenance, written atomically),
the YAML files the package reads, failed-stroke counts, and comparing results.

Imports the model and the solver's settings and result fields; no compiled code.
"""
