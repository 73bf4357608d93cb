"""The replication: the paper's claims against the results, the figures, the report.

The top of the package: reads result files, never simulates.
"""
