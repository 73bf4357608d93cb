"""A claim's value and its verdict (tennis_stroke.inference.claims): :func:`measure`
reads the value from the result files, :func:`within` compares it with the paper's.
(Not test_claims.py: tests/replication has one, and pytest needs unique basenames.)"""

import numpy as np
import pytest
import xarray as xr

from tennis_stroke.inference.claims import measure, within


@pytest.mark.parametrize(
    "value, paper, tolerance, expected",
    [
        (1.05, 1.0, 0.1, True),
        (0.95, 1.0, 0.1, True),  # below the paper's value as above it
        (1.15, 1.0, 0.1, False),  # 1.5 tolerances above
        (0.85, 1.0, 0.1, False),  # 1.5 tolerances below
        (-5.0, 1.0, 0.1, False),  # far below: the difference's size counts, not its sign
        (1.0, 1.0, 0.0, True),  # a qualitative claim: the same answer
        (0.0, 1.0, 0.0, False),
        (1e-12, 0.0, 0.0, True),  # the rounding margin of 1e-12 belongs to the bound
        (3e-12, 0.0, 0.0, False),
        (np.nan, 1.0, 0.1, False),
        (np.inf, np.inf, 1.0, False),
    ],
)
def test_within_is_the_closed_band_of_the_tolerance_around_the_paper(
    value, paper, tolerance, expected
):
    assert bool(within(value, paper, tolerance)) is expected


def test_within_compares_element_by_element():
    """The robustness analysis compares readings by claims in one call."""
    values = np.array([[1.05, 2.0], [0.0, 2.05]])
    got = within(values, np.array([1.0, 2.0]), np.array([0.1, 0.01]))
    assert got.tolist() == [[True, True], [False, False]]


FILES = {
    "f": xr.Dataset(
        {"v": ("tau", [-3.0, -1.0, 2.0]), "w": ("tau", [10.0, 20.0, 30.0])},
        coords={"tau": [0.0, 0.1, 0.2]},
    )
}


@pytest.mark.parametrize(
    "spec, expected",
    [
        ({"var": "w", "sel": {"tau": 1}}, 20.0),
        ({"var": "v", "sel": {"tau": 0}}, -3.0),
        ({"var": "v", "sel": {"tau": 0}, "abs": True}, 3.0),
        ({"var": "v", "sel": {"tau": 0}, "abs": False}, -3.0),
        ({"var": "v", "sel": {"tau": 0.2}, "abs": True}, 2.0),
    ],
)
def test_measure_reads_the_named_variable_at_its_selection(spec, expected):
    assert measure({"file": "f", **spec}, FILES) == expected


def test_a_measure_across_readings_reads_each_reading_s_own_coordinate():
    """Files stacked over readings (the robustness chunk's way): a decimal ``sel`` finds
    its value on each reading's own axis, a named measurement gives one value per
    reading, and called with a dataset it gives that one reading's float."""
    from tennis_stroke.inference.claims import ClaimError, measure_stacks
    from tennis_stroke.inference.measures import Stack, measure_optimum

    one = xr.Dataset(
        {
            "w": ("tau", [10.0, 20.0, 30.0]),
            "v_out": ("tau", [1.0, 3.0, 2.0]),
            "status": ("tau", [0, 0, 0]),
        },
        coords={"tau": [0.0, 0.1, 0.2]},
    )
    other = one.assign_coords(tau=[0.1, 0.2, 0.3])  # the same values, another axis
    files = {"f": Stack([one, other])}
    got = measure_stacks({"file": "f", "var": "w", "sel": {"tau": 0.1}}, files)
    assert got.tolist() == [20.0, 10.0]
    assert measure_stacks({"file": "f", "function": "optimum", "coord": "tau"}, files).tolist() == [
        0.1,
        0.2,
    ]
    assert measure_optimum(other, "tau") == 0.2  # a dataset: one reading, a float
    with pytest.raises(ClaimError, match=r"f: no tau = 0 on its axis \(nearest 0.1\)"):
        measure_stacks({"file": "f", "var": "w", "sel": {"tau": 0.0}}, files)


ARM = xr.Dataset(
    {"best_delta0": ("theta0", [40.0, 30.0, 20.0])}, coords={"theta0": [60.0, 90.0, 120.0]}
)


@pytest.mark.parametrize("theta0", [130.0, 500.0, -1000.0])
def test_a_measurement_refuses_a_value_off_its_file_s_axis(theta0):
    """130 and 500 deg were read at 120 deg's row, -1000 at 60 deg's (issue 66, case 1)."""
    from tennis_stroke.inference.measures import OffAxisError, measure_best_delta0

    with pytest.raises(OffAxisError, match=f"theta0 = {theta0:g} lies off the file's theta0 axis"):
        measure_best_delta0(ARM, theta0)


@pytest.mark.parametrize(
    "theta0, expected",
    [(120.0, 20.0), (120.0 + 1e-8, 20.0), (60.0 - 1e-8, 40.0), (100.0, 30.0), (105.0, 20.0)],
)
def test_a_value_on_the_axis_is_read_at_its_nearest_grid_point(theta0, expected):
    """Between grid points the nearer one (a tie: the later); an end within rounding."""
    from tennis_stroke.inference.measures import measure_best_delta0

    assert measure_best_delta0(ARM, theta0) == expected
