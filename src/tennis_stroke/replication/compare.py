"""A scenario's figure read against the paper's on one scale: the paper's configuration,
the scenario and their difference, side by side in one PNG.

Side by side, two figures drawn each on its own colour scale and axes could differ by
7 km/h and look the same.  :func:`comparison` draws the figure from the paper's files
and from the scenario's with the same drawing function, then gives every pair of axes
the union of their limits and every pair of colour maps the union of their ranges
(:func:`share_scales`), and adds a difference panel (:func:`difference_figure`: scenario
minus paper of the figure's :attr:`~tennis_stroke.replication.registry.Figure.compare`
variables, on diverging colours centred on 0 for a map, as curves for a curve, with the
variable's units in its label).  The three are composed into one image.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..inference.measures import valid_values
from ..io.compare import same_grid
from ..io.netcdf import load_result
from .drawing.axes import axis_label
from .figures import drawn
from .registry import Figure

#: Colours of a difference map: diverging, white at 0.
DIVERGING = "RdBu_r"


def _mappables(ax) -> list:
    """The colour-mapped artists of ``ax`` (images, meshes, scatter with values)."""
    return [a for a in (*ax.images, *ax.collections) if a.get_array() is not None]


def share_scales(first: plt.Figure, second: plt.Figure) -> None:
    """Give each pair of axes of two drawings of one figure the union of their x and y
    limits, and each pair of colour-mapped artists the union of their colour ranges."""
    for a, b in zip(first.axes, second.axes, strict=False):
        pairs = list(zip(_mappables(a), _mappables(b), strict=False))
        for m, n in pairs:
            low = np.nanmin([m.norm.vmin, n.norm.vmin])
            high = np.nanmax([m.norm.vmax, n.norm.vmax])
            m.set_clim(low, high)
            n.set_clim(low, high)
        if a.get_label() == "<colorbar>" or b.get_label() == "<colorbar>":
            continue
        for get, put in (("get_xlim", "set_xlim"), ("get_ylim", "set_ylim")):
            (a0, a1), (b0, b1) = getattr(a, get)(), getattr(b, get)()
            flipped = a0 > a1
            low, high = min(a0, a1, b0, b1), max(a0, a1, b0, b1)
            limits = (high, low) if flipped else (low, high)
            getattr(a, put)(*limits)
            getattr(b, put)(*limits)


def _curve_dim(da: xr.DataArray) -> str | None:
    """The dimension a 1-D (or stroke x time) variable is drawn along."""
    longer = [d for d in da.dims if da.sizes[d] > 1]
    if len(longer) == 1:
        return longer[0]
    if "t" in da.dims and da.ndim == 2:
        return "t"
    return None


def difference_figure(
    paper: xr.Dataset, scenario: xr.Dataset, variables: Sequence[str], title: str
) -> plt.Figure:
    """Scenario minus paper of ``variables`` (one panel each; failed strokes blank, as
    :func:`~tennis_stroke.inference.measures.valid_values` shows them): a map on
    diverging colours centred on 0 where the variable has two dimensions of more than one
    point, else curves (one per stroke) along its dimension.  A panel whose grids differ
    between the two says so instead of interpolating; one whose values are the same says
    that instead of drawing zeros."""
    fig, axes = plt.subplots(1, len(variables), figsize=(0.4 + 5.6 * len(variables), 4.8))
    axes = np.atleast_1d(axes)
    for ax, name in zip(axes, variables, strict=True):
        a, b = valid_values(paper, name), valid_values(scenario, name)
        units = a.attrs.get("units", "")
        label = f"scenario \u2212 paper's configuration ({units})"
        ax.set_title(f"{name}: {a.attrs.get('long_name', name)}", fontsize=8)
        if not same_grid(a, b):
            ax.text(0.5, 0.5, f"{name}: the grids differ\n(no difference drawn)", ha="center")
            ax.set_axis_off()
            continue
        diff = (b - a).squeeze()
        diff.attrs = a.attrs
        same = np.array_equal(np.isnan(a.values), np.isnan(b.values))  # failures too
        if same and np.isfinite(diff).any() and not np.nanmax(np.abs(diff.values)):
            ax.text(  # a flat zero panel would look like a drawing of a change
                0.5,
                0.5,
                f"{name}: the same under both\nconfigurations (the difference is 0)",
                ha="center",
                va="center",
                transform=ax.transAxes,
            )
            ax.set_axis_off()
            continue
        dim = _curve_dim(diff)
        if diff.ndim == 2 and all(diff.sizes[d] > 1 for d in diff.dims) and dim != "t":
            x, y = diff.dims[0], diff.dims[1]
            reach = float(np.nanmax(np.abs(diff.values))) if np.isfinite(diff).any() else 0.0
            reach = reach or 1.0
            mesh = ax.pcolormesh(
                diff[x],
                diff[y],
                diff.transpose(y, x),
                shading="auto",
                cmap=DIVERGING,
                vmin=-reach,
                vmax=reach,
            )
            ax.set_xlabel(axis_label(diff[x]), fontsize=8)
            ax.set_ylabel(axis_label(diff[y]), fontsize=8)
            plt.colorbar(mesh, ax=ax, label=label)
        elif dim is not None:
            others = [d for d in diff.dims if d != dim]
            lines = diff.transpose(*others, dim).values.reshape(-1, diff.sizes[dim])
            names = diff[others[0]].values if others and others[0] in diff.coords else []
            labels = diff["label"].values if "label" in diff.coords else names
            for i, line in enumerate(lines):
                text = str(labels[i]) if i < len(labels) else None
                ax.plot(diff[dim], line, lw=1.2, label=text)
            ax.axhline(0.0, color="0.5", lw=0.8)
            ax.set_xlabel(axis_label(diff[dim]), fontsize=8)
            ax.set_ylabel(label, fontsize=8)
            if len(lines) > 1:
                ax.legend(fontsize=7, loc="best", framealpha=0.7)
        else:  # a number
            ax.bar([0], [float(diff.values)], color="C0")
            ax.set_ylabel(label, fontsize=8)
            ax.set_xticks([])
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def _pixels(fig: plt.Figure, dpi: int) -> np.ndarray:
    fig.set_dpi(dpi)
    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    plt.close(fig)
    return image


def _side_by_side(images: Sequence[np.ndarray], gap: int = 12) -> np.ndarray:
    """The images next to each other on white, top-aligned."""
    height = max(i.shape[0] for i in images)
    width = sum(i.shape[1] for i in images) + gap * (len(images) - 1)
    out = np.full((height, width, 3), 255, dtype=np.uint8)
    x = 0
    for image in images:
        out[: image.shape[0], x : x + image.shape[1]] = image
        x += image.shape[1] + gap
    return out


def comparison(
    figure: Figure,
    paper_inputs: Sequence[str | Path],
    scenario_inputs: Sequence[str | Path],
    output: str | Path,
    scenario: str,
    note: str = "",
    marks: Sequence[Mapping] = (),
) -> None:
    """Write to ``output`` (PNG) ``figure`` drawn from the paper's files and from scenario
    ``scenario``'s on shared scales (:func:`share_scales`), and their difference
    (:func:`difference_figure`), side by side."""
    paper = drawn(figure, paper_inputs, "the paper's configuration", marks)
    ours = drawn(figure, scenario_inputs, note or f"scenario {scenario}", marks)
    share_scales(paper, ours)
    first, second = load_result(paper_inputs[0]), load_result(scenario_inputs[0])
    difference = difference_figure(
        first, second, figure.compare, f"scenario {scenario} \u2212 the paper's configuration"
    )
    image = _side_by_side([_pixels(f, figure.dpi) for f in (paper, ours, difference)])
    plt.imsave(output, image)
