"""Shared fixtures: the paper's default parameters and handy coefficient rows."""

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
