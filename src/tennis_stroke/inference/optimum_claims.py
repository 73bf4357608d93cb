"""The claims that locate an optimum, and the two rules every one of them is judged by.

A claim *locates an optimum* when its value is where ``v_out`` is largest (or smallest)
along a coordinate of a map: the best delta0 of a row of Figs. 2-3, the best delay of
Figs. 8-9, the best and worst direction of Figs. 13-14.  :func:`located` says which
claims do, from their ``measure`` alone (no list of claim ids), and two rules apply to
each of them, whatever its status:

* **edge**: the optimum lies on the edge of its search range when one of its searched
  coordinates lies at an end of the range (within
  :data:`~tennis_stroke.inference.measures.AXIS_TOLERANCE` of the span): the searches
  and the maps' grids clip an optimum beyond the range to its end, so one there is where
  the range stopped it, not where the objective peaks.  The range of a coordinate is its
  axis on the full map (the searches search the map's range).  A direction over a full
  turn has no edge (its search wraps around).
* **flat**: the objective is flat when ``v_out`` at the paper's argument (nearest grid
  point of the full map, the claim's fixed coordinates at their values, the others at
  their best) lies within ``flat_gap`` (km/h; ``config/readings.yaml``: ``evidence``) of
  the optimum: the paper's argument is as good as ours, and the objective cannot tell
  them apart.  A deviation on a flat objective is ``ill_conditioned``
  (:mod:`tennis_stroke.replication.robustness`); a pass on one says that the location
  agrees only as well as the objective can tell.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..io.units import unit_of
from .measures import AXIS_TOLERANCE, measure_minimum, measure_optimum, valid_v_out


@dataclass(frozen=True)
class Located:
    """The optimum a claim's value is the location of: in file ``file``, along ``coord``,
    the largest (``sign`` 1) or smallest (-1) ``v_out``, with ``fixed`` coordinates held
    at a value (the claim's row)."""

    file: str
    coord: str
    sign: float = 1.0
    fixed: Mapping[str, float] = field(default_factory=dict)


def located(spec: Mapping) -> Located | None:
    """The optimum a claim's ``measure`` locates, None if its value is no optimum's
    location (the one table of which measurements locate one)."""
    name, file = spec.get("function"), spec.get("file")
    if name == "best_delta0":
        return Located(file, "delta0", 1.0, {"theta0": float(spec["theta0"])})
    if name in ("optimum", "minimum"):
        return Located(file, spec["coord"], 1.0 if name == "optimum" else -1.0)
    if name == "fig9" and spec.get("what") == "tau_H":
        return Located(file, "tau", 1.0)
    return None


def _objective(where: Located, full_map: xr.Dataset) -> xr.DataArray:
    """``v_out`` of the full map (failed strokes NaN) at the claim's fixed coordinates."""
    v = valid_v_out(full_map)
    return v.sel(dict(where.fixed), method="nearest") if where.fixed else v


def searched(where: Located, full_map: xr.Dataset) -> list[str]:
    """The coordinates the optimum is searched along: the full map's dimensions of
    ``v_out`` but the fixed ones and those of one point."""
    v = _objective(where, full_map)
    return [d for d in v.dims if v.sizes[d] > 1]


def objective_gap(where: Located, argument: float, full_map: xr.Dataset) -> float:
    """How far (km/h) ``v_out`` at ``argument`` of ``where.coord`` lies from the optimum
    (nearest grid point of the full map; the other searched coordinates at their best):
    the rule **flat** compares it with ``flat_gap``."""
    v = _objective(where, full_map)
    at = v.sel({where.coord: argument}, method="nearest")
    if where.sign > 0:
        return float(v.max()) - float(at.max())
    return float(at.min()) - float(v.min())


def _full_turn(coord: str, low: float, high: float) -> bool:
    return unit_of(coord) == "degree" and bool(np.isclose(high - low, 360.0))


def location(where: Located, value: float, measured: xr.Dataset, full_map: xr.Dataset):
    """The optimum's location on every searched coordinate: ``where.coord`` is the
    claim's ``value``; another is read on the file the claim was measured on, at its
    extreme ``v_out`` (``measured``: the targeted search's file or the map)."""
    out = {}
    for coord in searched(where, full_map):
        if coord == where.coord:
            out[coord] = float(value)
        elif "v_out" in measured and coord in measured["v_out"].dims:
            extreme = measure_optimum if where.sign > 0 else measure_minimum
            out[coord] = extreme(measured, coord)
    return out


def edge(where: Located, value: float, measured: xr.Dataset, full_map: xr.Dataset) -> str:
    """The rule **edge**: ``""`` if the optimum lies inside its search range, else where
    it lies on the edge, one part per coordinate: ``delta0 = 0 degree, the lower end of
    the search range [0, 100] degree``."""
    parts = []
    for coord, x in location(where, value, measured, full_map).items():
        axis = full_map[coord].values
        low, high = float(np.min(axis)), float(np.max(axis))
        if not np.isfinite(x) or _full_turn(coord, low, high):
            continue
        slack = AXIS_TOLERANCE * max(high - low, 1.0)
        end = "lower" if abs(x - low) <= slack else "upper" if abs(x - high) <= slack else ""
        if end:
            unit = unit_of(coord)
            parts.append(
                f"{coord} = {x:.4g} {unit}, the {end} end of the search range "
                f"[{low:.4g}, {high:.4g}] {unit}"
            )
    return "; ".join(parts)


def is_full_map(ds: xr.Dataset | None, where: Located | None) -> bool:
    """Whether ``ds`` is a map the rules can read ``where``'s optimum on: ``v_out`` over
    its coordinate, not a targeted search's file (which holds only the points found)."""
    return (
        ds is not None
        and where is not None
        and not ds.attrs.get("targeted")
        and "v_out" in ds
        and where.coord in ds["v_out"].dims
    )


def judged(
    spec: Mapping,
    value: float,
    paper_value: float,
    measured: Mapping[str, xr.Dataset],
    maps: Mapping[str, xr.Dataset],
    flat_gap: float | None,
) -> dict[str, object]:
    """The columns of the two rules for one claim: ``objective_gap`` (km/h, NaN if the
    claim locates no optimum), ``flat`` (``True``/``False``; ``""`` if it locates none
    or no ``flat_gap`` is given) and ``edge`` (:func:`edge`); none of them without the
    claim's full map in ``maps`` (:func:`is_full_map`)."""
    where = located(spec)
    full_map = maps.get(where.file) if where is not None else None
    if not is_full_map(full_map, where):
        return {"objective_gap": float("nan"), "flat": "", "edge": ""}
    gap = objective_gap(where, float(paper_value), full_map)
    flat = "" if flat_gap is None or not np.isfinite(gap) else bool(gap <= float(flat_gap))
    return {
        "objective_gap": gap,
        "flat": flat,
        "edge": edge(where, value, measured[where.file], full_map),
    }


def _flat(row: Mapping) -> bool:
    return str(row.get("flat", "")) in ("True", "true", "1", "1.0")


def _gap(row: Mapping) -> float:
    try:
        return float(row.get("objective_gap", "nan"))
    except (TypeError, ValueError):
        return float("nan")


def note(row: Mapping) -> str:
    """What the two rules found of a claims table's row, in words (the report): ``""``
    for a claim whose optimum lies inside its search range on an objective that is not
    flat, or that locates none."""
    parts = []
    if str(row.get("edge", "") or ""):
        parts.append(f"optimum at the edge of its search range: {row['edge']}")
    if _flat(row):
        parts.append(
            f"flat objective: v_out at the paper's value is {_gap(row):.2g} km/h from the "
            "optimum, within the flat gap"
        )
    return "; ".join(parts)


def short_note(row: Mapping) -> str:
    """:func:`note` in a table cell (the article): ``optimum on the edge of its search
    range [0, 100] degree, flat``."""
    parts = []
    if str(row.get("edge", "") or ""):
        ranges = [p.split("search range ")[-1] for p in str(row["edge"]).split("; ")]
        parts.append(f"optimum on the edge of its search range {', '.join(ranges)}")
    if _flat(row):
        parts.append("flat objective")
    return ", ".join(parts)
