"""A scenario's figure read against the paper's (tennis_stroke.replication.compare): one
scale for both, and a difference that is scenario minus paper, centred on 0."""

import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from tennis_stroke.io.netcdf import write_netcdf  # noqa: E402
from tennis_stroke.replication.compare import (  # noqa: E402
    comparison,
    difference_figure,
    share_scales,
)
from tennis_stroke.replication.registry import FIGURES  # noqa: E402


def _map(values, theta0=(60.0, 90.0, 120.0), delta0=(0.0, 50.0)):
    v = xr.DataArray(
        np.asarray(values, float),
        dims=("theta0", "delta0"),
        coords={
            "theta0": ("theta0", list(theta0), {"units": "degree", "long_name": "theta0"}),
            "delta0": ("delta0", list(delta0), {"units": "degree", "long_name": "delta0"}),
        },
        attrs={"units": "km/h", "long_name": "rebound speed"},
    )
    return xr.Dataset({"v_out": v})


def _drawing(low, high):
    fig, ax = plt.subplots()
    mesh = ax.pcolormesh(np.array([[low, high]]))
    fig.colorbar(mesh, ax=ax)
    ax.set_xlim(0, 1 + high / 100)
    return fig, mesh


def test_both_drawings_get_one_colour_scale_and_one_pair_of_axes():
    """Fig. 2 at M2 = 0.35 kg spans 105-155 km/h against the paper's 105-162: on their
    own scales the two looked alike; now both use 105-162 and the wider axes."""
    (a, ma), (b, mb) = _drawing(105.0, 162.0), _drawing(105.0, 155.0)
    share_scales(a, b)
    assert ma.get_clim() == mb.get_clim() == (105.0, 162.0)
    assert a.axes[0].get_xlim() == b.axes[0].get_xlim() == (0.0, 2.62)
    plt.close(a), plt.close(b)


def test_the_difference_is_scenario_minus_paper_on_colours_centred_on_zero():
    paper = _map([[100, 110], [120, 130], [140, 150]])
    scenario = _map([[101, 110], [120, 127], [140, 150]])
    fig = difference_figure(paper, scenario, ["v_out"], "s - paper")
    mesh = fig.axes[0].collections[0]
    np.testing.assert_array_equal(
        np.asarray(mesh.get_array()).reshape(2, 3), [[1, 0, 0], [0, -3, 0]]
    )
    assert mesh.get_clim() == (-3.0, 3.0)  # symmetric: white is no change
    assert fig.axes[1].get_ylabel() == "scenario \u2212 paper's configuration (km/h)"
    plt.close(fig)


def test_a_variable_the_scenario_does_not_move_is_said_not_drawn_as_zeros():
    """Fig. 14's elbow path is prescribed: a flat zero panel looked like a change."""
    paper = _map([[100, 110], [120, 130], [140, 150]])
    fig = difference_figure(paper, paper.copy(deep=True), ["v_out"], "t")
    (text,) = fig.axes[0].texts
    assert "the same under both" in text.get_text() and not fig.axes[0].collections
    plt.close(fig)
    # a value missing on one side only (a failed stroke) is not "the same"
    scenario = paper.copy(deep=True)
    scenario["v_out"][0, 0] = np.nan
    fig = difference_figure(paper, scenario, ["v_out"], "t")
    assert not fig.axes[0].texts and fig.axes[0].collections
    plt.close(fig)


def test_grids_that_differ_are_said_not_interpolated():
    paper = _map([[100, 110], [120, 130], [140, 150]])
    scenario = _map([[100, 110], [120, 130]], theta0=(60.0, 120.0))
    fig = difference_figure(paper, scenario, ["v_out"], "t")
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert texts == ["v_out: the grids differ\n(no difference drawn)"]
    plt.close(fig)


def _angle_map(values):
    job = {"args": {"L1": 0.3}}  # what the job records of its arguments (Fig. 2's title)
    ds = _map(values).assign_attrs(param_L1=0.3, config=json.dumps(job))
    ds["status"] = xr.zeros_like(ds["v_out"], dtype=np.int64)
    ds["best_delta0"] = ds["theta0"] * 0.0 + 20.0
    return ds


def test_a_comparison_is_one_image_of_three_panels(tmp_path):
    paper, scenario = tmp_path / "p.nc", tmp_path / "s.nc"
    write_netcdf(_angle_map([[100, 110], [120, 130], [140, 150]]), paper)
    write_netcdf(_angle_map([[101, 111], [121, 131], [141, 151]]), scenario)
    out = tmp_path / "c.png"
    comparison(FIGURES["fig02_angle_map"], [paper], [scenario], out, "s")
    image = plt.imread(out)
    assert image.shape[1] > 2.5 * image.shape[0]  # three drawings side by side
