"""Every consistent reading in a sortable table and in parallel coordinates
(:func:`multiverse_view`); a reading (and a claim-level variant) picked there shows every
claim's value and verdict under it beside the default reading's; a claim picked in that
table highlights the readings under which it fails.  The values are embedded as they
are (float64: a few kB), in the source ``multiverse-claims``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr
from bokeh.layouts import column
from bokeh.models import ColumnDataSource, CustomJS, Div, NumberFormatter, Select, TableColumn
from bokeh.palettes import Viridis256
from bokeh.plotting import figure as bokeh_figure

from .tables import data_table

_PICK_JS = """
const r = readings.selected.indices.length ? readings.selected.indices[0] : null
const v = Number(variant.value)
const value_of = values.data.value, within_of = values.data.within
const nc = data.claim.length, nv = data.n_variants
const value = [], verdict = []
for (let c = 0; c < nc; c++) {
  if (r === null) { value.push(NaN); verdict.push("pick a reading"); continue }
  const at = (data.reading_row[r] * nv + v) * nc + c
  value.push(value_of[at])
  verdict.push(within_of[at] ? "pass" : "fail")
}
const d = {...claims.data}
d.value = value; d.verdict = verdict
claims.data = d
claim_table.view.change.emit()  // a DataTable redraws its rows on its view's change
// readings: claims passed under the variant, and the picked claim's failures
const sel = claims.selected.indices.length ? claims.selected.indices[0] : null
const nr = readings.data.reading.length
const passed = [], fails = []
for (let i = 0; i < nr; i++) {
  const row = data.reading_row[i]
  let p = 0
  for (let c = 0; c < nc; c++) if (data.held[c] && within_of[(row * nv + v) * nc + c]) p++
  passed.push(p)
  const f = sel !== null && !within_of[(row * nv + v) * nc + sel]
  fails.push(sel === null ? "" : (f ? "fails" : "passes"))
}
const rd = {...readings.data}
rd.passed = passed; rd.selected_claim = fails
readings.data = rd
reading_table.view.change.emit()
const lo = Math.min(...passed), hi = Math.max(...passed)
const ld = {...lines.data}
ld.color = ld.row.map((row, i) => {
  if (sel !== null) return fails[i] === "fails" ? "#d62728" : "#c7c7c7"
  const u = hi > lo ? (passed[i] - lo) / (hi - lo) : 1
  return palette[Math.round(u * (palette.length - 1))]
})
ld.width = ld.row.map((row, i) => (r !== null && i === r) ? 4 : 1.5)
lines.data = ld
title.text = (r === null ? "No reading picked" : "Reading " + readings.data.reading[r]) +
  ", variant " + v + (sel === null ? "" : "; claim " + claims.data.claim[sel] +
  " fails under " + fails.filter(x => x === "fails").length + " of " + nr + " readings (red)")
"""


def _unknowns(ds: xr.Dataset) -> list[str]:
    """The readings' unknowns: the per-reading variables but the design's indices."""
    return [
        k
        for k in ds.data_vars
        if ds[k].dims == ("reading",) and k not in ("combination", "candidate")
    ]


def _readings_table(ds: xr.Dataset, passed: np.ndarray, held: int, name: str):
    """Every reading with its unknowns, the held-out claims it passes and whether it
    passes the picked claim: its source and its sortable table."""
    n = ds.sizes["reading"]
    data = {"reading": ds["reading"].values.astype(int), "row": np.arange(n)}
    columns = [TableColumn(field="reading", title="reading")]
    for k in _unknowns(ds):
        data[k] = ds[k].values
        unit = ds[k].attrs.get("units", "1")
        if np.issubdtype(ds[k].dtype, np.number):
            title = k + (f" ({unit})" if unit != "1" else "")
            columns.append(
                TableColumn(field=k, title=title, formatter=NumberFormatter(format="0.0000[00]"))
            )
        else:
            columns.append(TableColumn(field=k, title=k))
    data["passed"] = passed
    data["selected_claim"] = [""] * n
    columns.append(TableColumn(field="passed", title=f"held-out passed (of {held})"))
    columns.append(TableColumn(field="selected_claim", title="picked claim"))
    source = ColumnDataSource(data, name=f"{name}-readings")
    return source, data_table(source, columns, 260, f"{name}-reading-table")


def _claims_table(ds: xr.Dataset, claims: pd.DataFrame, held: np.ndarray, name: str):
    """Every claim: paper's value, tolerance, unit, its value and verdict under the
    picked reading (filled by the page), the default reading's value and status (the
    claims table) and its role; its source and its sortable table."""
    ids = [str(c) for c in ds["claim"].values]
    by_id = claims.set_index("id").loc[ids]
    source = ColumnDataSource(
        {
            "claim": ids,
            "unit": [str(u) for u in ds["claim_unit"].values],
            "paper": ds["paper_value"].values,
            "tolerance": ds["tolerance"].values,
            "held": [
                "held out" if h else f"fit ({f})"
                for f, h in zip(by_id["fit_set"], held, strict=True)
            ],
            "value": np.full(len(ids), np.nan),
            "verdict": ["pick a reading"] * len(ids),
            "default": by_id["reproduced_value"].to_numpy(dtype=float),
            "default_status": [str(v) for v in by_id["status"]],
        },
        name=f"{name}-claims",
    )
    number = NumberFormatter(format="0.0[000]")
    columns = [TableColumn(field="claim", title="claim", width=230)]
    for field, title in (
        ("paper", "paper"),
        ("tolerance", "tolerance"),
        ("unit", "unit"),
        ("value", "picked reading"),
        ("verdict", "verdict"),
        ("default", "default reading"),
        ("default_status", "default status"),
        ("held", "role"),
    ):
        numeric = field in ("paper", "tolerance", "value", "default")
        columns.append(
            TableColumn(field=field, title=title, **({"formatter": number} if numeric else {}))
        )
    return source, data_table(source, columns, 420, f"{name}-claim-table")


def multiverse_view(ds: xr.Dataset, claims: pd.DataFrame, name: str = "multiverse"):
    """Every consistent reading of ``ds`` (``results/robustness/claims.nc``): a sortable
    table of the readings, parallel coordinates of their unknowns coloured by the number
    of held-out claims passed, a variant picker, and the claims table under the picked
    reading beside the default reading's (``claims``: the claims table)."""
    ids = [str(c) for c in ds["claim"].values]
    held = (claims.set_index("id").loc[ids, "fit_set"] == "").to_numpy()
    order = ds.transpose("reading", "variant", "claim")
    within = order["within"].values.astype(np.int8)
    passed = (within[:, 0, :].astype(bool) & held).sum(axis=1)
    readings, reading_table = _readings_table(ds, passed, int(held.sum()), name)
    claim_source, claim_table = _claims_table(ds, claims, held, name)
    variants = [k for k in ds.data_vars if ds[k].dims == ("variant",)]
    options = [
        (str(v), f"{v}: " + ", ".join(f"{k} = {ds[k].values[v]}" for k in variants))
        for v in range(ds.sizes["variant"])
    ]
    variant = Select(
        title="claim-level variant", value="0", options=options, width=700, name=f"{name}-variant"
    )
    lines = ColumnDataSource(_parallel_lines(ds, passed), name=f"{name}-lines")
    overview = bokeh_figure(
        title="Every consistent reading: its unknowns, scaled to their range",
        x_range=_unknowns(ds),
        y_range=(-0.05, 1.05),
        tools="pan,box_zoom,reset,save",
        width=1000,
        height=300,
        name=f"{name}-overview",
    )
    overview.multi_line(
        "xs", "ys", source=lines, line_color="color", line_width="width", line_alpha=0.7
    )
    overview.yaxis.visible = False
    heading = Div(
        text="<b>No reading picked</b>: pick a row of the readings table",
        width=1000,
        name=f"{name}-title",
    )
    pick = CustomJS(
        args={
            "readings": readings,
            "claims": claim_source,
            "reading_table": reading_table,
            "claim_table": claim_table,
            "variant": variant,
            "lines": lines,
            "title": heading,
            "palette": list(Viridis256),
            # every claim under every (reading, variant), flat in that order: arrays, not
            # lists (Bokeh walks a list's every item looking for models)
            "values": ColumnDataSource(
                {"value": order["value"].values.ravel(), "within": within.ravel()},
                name=f"{name}-values",
            ),
            "data": {
                "claim": ids,
                "held": held.astype(int).tolist(),
                "n_variants": int(ds.sizes["variant"]),
                "reading_row": list(range(ds.sizes["reading"])),
            },
        },
        code=_PICK_JS,
    )
    readings.selected.js_on_change("indices", pick)
    claim_source.selected.js_on_change("indices", pick)
    variant.js_on_change("value", pick)
    return column(heading, variant, reading_table, overview, claim_table, name=name)


def _parallel_lines(ds: xr.Dataset, passed: np.ndarray) -> dict[str, list]:
    """One polyline per reading over the unknowns' axes, each scaled to [0, 1] (a
    discrete unknown by its options' order), coloured by ``passed``."""
    unknowns = _unknowns(ds)
    columns = []
    for k in unknowns:
        values = ds[k].values
        if np.issubdtype(values.dtype, np.number):
            lo, hi = float(np.min(values)), float(np.max(values))
            columns.append((values - lo) / (hi - lo) if hi > lo else np.full(len(values), 0.5))
        else:
            options = sorted({str(v) for v in values})
            scale = max(len(options) - 1, 1)
            columns.append(np.array([options.index(str(v)) / scale for v in values]))
    ys = np.column_stack(columns)
    lo, hi = passed.min(), passed.max()
    shade = (passed - lo) / (hi - lo) if hi > lo else np.ones(len(passed))
    return {
        "xs": [list(unknowns)] * len(passed),
        "ys": [list(map(float, row)) for row in ys],
        "color": [Viridis256[int(round(u * 255))] for u in shade],
        "width": [1.5] * len(passed),
        "row": list(range(len(passed))),
    }
