"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

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


def run_snakemake(target, workdir, *options, timeout=300):
    """Run this project's Snakefile on ``target`` in ``workdir`` (target first: options
    that take several values would swallow it); returns the completed process."""
    snakemake = Path(sys.executable).with_name("snakemake")
    command = [
        str(snakemake),
        target,
        "-s",
        str(ROOT / "Snakefile"),
        "--directory",
        str(workdir),
        *options,
    ]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)
