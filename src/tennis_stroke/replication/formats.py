"""What the report, the article and a scenario's page write alike: a number as text, a
table as HTML, the per-job timings of a run, and the one-line error of an input the
workflow did not write (a unit's short form is the registry's, ``UNIT_SHORT``)."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path

import pandas as pd
from markupsafe import Markup


class ReportInputError(ValueError):
    """An input of the report is not one the workflow wrote (one line)."""


def _number(value, digits: int = 4) -> str:
    try:
        x = float(value)
    except (TypeError, ValueError):
        return str(value)
    return f"{x:.{digits}g}" if pd.notna(x) else "-"


def _safe(html: str) -> Markup:
    """HTML the report's modules wrote (pandas tables, which escape their cells;
    markdown-it-py output with raw HTML disabled; Bokeh's script and divs, whose data are
    JSON with ``<`` escaped), inserted into the page as it is."""
    return Markup(html)


def _table(frame: pd.DataFrame, **kwargs) -> Markup:
    """A pandas table as escaped HTML."""
    return _safe(frame.to_html(escape=True, border=0, **kwargs))


def _timings(directory: Path) -> pd.DataFrame:
    """Per-job timings, with the time each was measured: jobs of an earlier run (e.g.
    with other chunk counts) keep their files until ``logs/benchmarks`` is removed.
    Every job writes one (a gather's below ``gather_map/``); the scenarios' (below
    ``scenarios/``, the workflow's scenario folder) are not the paper's run."""
    rows = []
    paths = [
        p for p in directory.rglob("*.tsv") if "scenarios" not in p.relative_to(directory).parts
    ]
    for path in sorted(paths):
        table = pd.read_csv(path, sep="\t")
        rows.append(
            {
                "job": path.relative_to(directory).with_suffix("").as_posix().replace("/", "_"),
                "wall time (s)": round(float(table["s"].iloc[-1]), 2),
                "max RSS (MB)": table.get("max_rss", pd.Series([float("nan")])).iloc[-1],
                "measured (UTC)": datetime.fromtimestamp(path.stat().st_mtime, UTC).isoformat(
                    timespec="seconds"
                ),
            }
        )
    return pd.DataFrame(rows)
