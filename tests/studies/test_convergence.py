"""Measured orders: each method's fitted slope of log error against log step is its
theoretical order within MARGIN, on the config's own convergence study.

The margin was stated before the slopes were measured (2026-12-06): half an order."""

from pathlib import Path

import pytest
import yaml

from tennis_stroke.studies.convergence import THEORETICAL_ORDERS, convergence_study

ROOT = Path(__file__).resolve().parents[2]
MARGIN = 0.5


@pytest.fixture(scope="module")
def measured():
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    return convergence_study(**config["solver_study"]["convergence"])


def test_every_method_of_the_shipped_study_is_measured(measured):
    assert set(measured["method"].values) == {
        "tennis_stroke.DP54",
        "tennis_stroke.DOP853",
        "fixed.RK4",
    }
    assert sorted(THEORETICAL_ORDERS.values()) == [4, 5, 8]


@pytest.mark.parametrize("method", ["tennis_stroke.DP54", "tennis_stroke.DOP853", "fixed.RK4"])
def test_each_slope_is_its_order_within_the_margin(measured, method):
    row = measured.sel({"method": method})
    slope, order = float(row["slope"]), int(row["order"])
    assert abs(slope - order) <= MARGIN, (method, slope, order, row["omega_error"].values)


def test_a_torque_switch_inside_the_stretch_is_refused():
    with pytest.raises(ValueError, match="switches inside"):
        convergence_study(100.0, 40.0, 0.6, {"RK4": [10, 20]})
