"""The errors of result files that cannot be written or read, apart from the netCDF
module so that the command line can catch them without importing xarray (a ``strike``
writes no file)."""

from __future__ import annotations


class OutputError(OSError):
    """The output file cannot be written (message is one line)."""


class ResultError(OSError):
    """A result file cannot be read: missing, damaged or not a result (message is one
    line and names the file)."""


class ProvenanceError(OutputError):
    """A result would not record where it comes from (the checkout's commit), so it is
    not written (message is one line)."""
