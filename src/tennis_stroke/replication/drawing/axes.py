"""Helpers the drawing functions share: axis labels from the files' attributes, a colour
map with its colour bar."""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import xarray as xr

#: Longest axis label on one line (characters): a longer one is set on two balanced lines,
#: so that it never runs past its axes and off the figure (Fig. 2's delta0 label did).
LABEL_WIDTH = 44


def axis_label(da: xr.DataArray) -> str:
    """``long_name (units)`` of ``da`` (its name without a long name), on two lines when
    longer than :data:`LABEL_WIDTH`."""
    label = f"{da.attrs.get('long_name', da.name)} ({da.attrs.get('units', '')})"
    if len(label) <= LABEL_WIDTH:
        return label
    return "\n".join(textwrap.wrap(label, len(label) // 2 + 8, break_long_words=False))


def colour_map(ax, da: xr.DataArray, x: str, y: str, cmap="viridis"):
    """Colour map of ``da`` with ``x`` horizontal and ``y`` vertical, and its colour bar."""
    mesh = ax.pcolormesh(da[x], da[y], da.transpose(y, x), shading="auto", cmap=cmap)
    ax.set_xlabel(axis_label(da[x]))
    ax.set_ylabel(axis_label(da[y]))
    plt.colorbar(mesh, ax=ax, label=axis_label(da))
    return mesh
