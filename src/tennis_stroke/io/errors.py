"""The error of an output that cannot be written, apart from the netCDF writer so that
the command line can catch it without importing xarray (a ``strike`` writes no file)."""

from __future__ import annotations


class OutputError(OSError):
    """The output file cannot be written (message is one line)."""
