"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tennis_stroke._kernels import coefficient_tuple
from tennis_stroke.dynamics import coefficients
from tennis_stroke.params import resolve_params

#: The two strokes of the paper's Fig. 4: (theta0, delta0) in degrees.
FIG4_A = (120.0, 81.5)
FIG4_B = (75.0, 39.0)


@pytest.fixture(autouse=True)
def _raise_on_float_errors():
    """Floating-point warnings are errors in tests."""
    with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
        yield


def coefficient_row(theta0=90.0, delta0=30.0, **overrides):
    """One coefficient row (array) for the given angles and parameter overrides."""
    return coefficients(resolve_params(overrides), theta0, delta0)[0]


def coefficient_tup(theta0=90.0, delta0=30.0, **overrides):
    """The same as a tuple, as the compiled kernels take it."""
    return coefficient_tuple(coefficient_row(theta0, delta0, **overrides))


ROOT = Path(__file__).resolve().parents[1]


def snakemake_command(targets, workdir, *options) -> list[str]:
    """Command line running this project's Snakefile on ``targets`` (a path or a list) in
    ``workdir``; targets come first, as options that take several values would swallow
    them."""
    targets = [targets] if isinstance(targets, str) else list(targets)
    snakemake = Path(sys.executable).with_name("snakemake")
    return [
        str(snakemake),
        *targets,
        "-s",
        str(ROOT / "Snakefile"),
        "--directory",
        str(workdir),
        *options,
    ]


def run_snakemake(targets, workdir, *options, timeout=300):
    """Run :func:`snakemake_command`; returns the completed process."""
    command = snakemake_command(targets, workdir, *options)
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)


def assert_same_numbers(path_a, path_b):
    """Two result files hold the same numbers, bit for bit, in every data variable and
    coordinate, from the same job configuration; only wall-clock measurements (variables
    with a ``timing`` attribute) and timestamps may differ."""
    with xr.open_dataset(path_a) as a, xr.open_dataset(path_b) as b:
        assert set(a.data_vars) == set(b.data_vars), path_a
        assert set(a.coords) == set(b.coords), path_a
        for name in [*a.data_vars, *a.coords]:
            if "timing" in a[name].attrs:
                continue
            np.testing.assert_array_equal(
                a[name].values, b[name].values, err_msg=f"{path_a}: {name}", strict=True
            )
        assert a.attrs["config_sha256_16"] == b.attrs["config_sha256_16"], path_a
