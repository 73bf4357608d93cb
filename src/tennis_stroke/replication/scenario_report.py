"""A scenario's page: what a what-if changes, beside the paper's configuration.

A scenario (:mod:`tennis_stroke.pipeline.scenarios`) is an exploration, never a
replication: its page has no scoreboard and no verdict.  It opens with the overrides,
then shows each of the paper's figures the scenario changes beside the paper
configuration's (when that exists), and every claim's value under both configurations
with the change: the paper's value, ours under the paper's configuration, ours under the
scenario.  No cause is quoted: the causes in ``config/claims.yaml`` were written for the
paper's configuration.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd
from markupsafe import Markup

from .._version import __version__
from ..inference.claims import load_claims
from ..inference.paper_config import PaperConfigError, describe_departures, read_record
from ..io.netcdf import git_commit, load_result
from .claims import ClaimsTableError, read_table
from .formats import ReportInputError, _number
from .marks import mark_values
from .registry import FIGURES, UNIT_SHORT
from .report import ENVIRONMENT, _figure_entry


def _paper_table(path: str | Path, ids: Sequence[str]) -> tuple[pd.DataFrame | None, str]:
    """The paper configuration's claims table, if it exists and is the paper's, with a
    note on where the values come from (or why there are none)."""
    try:
        table = read_table(path, ids)
    except ClaimsTableError:
        return None, (
            f"not computed: {path} does not exist or is not a claims table "
            "(snakemake -j2 results/claims.csv computes it)"
        )
    try:
        record = read_record(path)
    except PaperConfigError as exc:
        return table, f"from {path}, whose configuration is unknown ({exc})"
    if record["departures"]:
        return table, (
            f"from {path}, computed under config/config.yaml, which departs from the "
            f"paper's: {describe_departures(record)}"
        )
    return table, f"from {path} (the paper's configuration)"


def same_values(pairs: Sequence[Sequence[str]]) -> bool:
    """Whether each (paper, scenario) pair of result files holds the same values (the
    attributes aside), where the paper's file exists: a scenario's change that the
    figure's job reads but its numbers do not feel (Figs. 5-6 sweep M2 themselves)."""
    if not pairs:
        return False
    for paper, scenario in pairs:
        if not Path(paper).is_file():
            return False
        if not load_result(paper).equals(load_result(scenario)):
            return False
    return True


def _change(ours: float, scenario: float, unit: str) -> str:
    if not (np.isfinite(ours) and np.isfinite(scenario)):
        return "-"
    if unit == "1":
        return "same" if ours == scenario else f"{_number(ours)} \u2192 {_number(scenario)}"
    delta = scenario - ours
    return "0" if delta == 0 else f"{delta:+.4g}"


def claim_rows(scenario: pd.DataFrame, paper: pd.DataFrame | None) -> list[dict]:
    """Each claim under both configurations: the paper's value, ours (the paper's
    configuration, where computed), ours (the scenario) and the change."""
    ours = (
        dict(zip(paper["id"], paper["reproduced_value"].astype(float), strict=True))
        if paper is not None
        else {}
    )
    rows = []
    for c in scenario.to_dict("records"):
        value = float(c["reproduced_value"])
        base = ours.get(c["id"], float("nan"))
        rows.append(
            {
                "id": c["id"],
                "source": c["source"],
                "quantity": c["quantity"],
                "unit_short": UNIT_SHORT.get(c["unit"], c["unit"]),
                "paper": _number(float(c["paper_value"])),
                "ours_paper": _number(base) if np.isfinite(base) else "-",
                "ours_scenario": _number(value),
                "change": _change(base, value, c["unit"]),
                "moved": bool(np.isfinite(base) and np.isfinite(value) and base != value),
                "compared": bool(np.isfinite(base) and np.isfinite(value)),
            }
        )
    return rows


def movement(rows: Sequence[Mapping]) -> dict[str, int]:
    """How the claims' values (:func:`claim_rows`) split, each claim in one part: those
    that move, those that stay, and those without two numbers to compare (not computed
    under the paper's configuration, or a failed measurement on either side); ``all``,
    their sum, is every claim."""
    compared = [r for r in rows if r["compared"]]
    moved = sum(r["moved"] for r in compared)
    return {
        "all": len(rows),
        "moved": moved,
        "same": len(compared) - moved,
        "uncompared": len(rows) - len(compared),
    }


def _scenario_views(
    shown: Sequence[Mapping],
    declared: Sequence[Mapping],
    table: pd.DataFrame,
    paper: pd.DataFrame | None,
    who: str,
):
    """The interactive view of each shown figure: against the paper configuration's
    (shared scales, the difference, linked hovers:
    :func:`.views.comparison.comparison_view`) where the paper's files exist (``linked``
    of its entry), else the scenario's alone; each with its marks at the paper's values
    and ours (the paper configuration's, the scenario's).  The page's head and divs by
    name."""
    # Bokeh: only the page jobs draw views
    from .views.comparison import comparison_view
    from .views.maps import MAP_VIEWS, figure_view
    from .views.page import page_views

    claims = {c["id"]: c for c in declared}
    ours = dict(zip(table["id"], table["reproduced_value"].astype(float), strict=True))
    base = (
        dict(zip(paper["id"], paper["reproduced_value"].astype(float), strict=True))
        if paper is not None
        else {}
    )
    made = {}
    for f in shown:
        figure = FIGURES[f["name"]]
        if figure.draw not in MAP_VIEWS or len(f["files"]) != len(figure.files):
            continue
        data = [load_result(p) for p in f["files"]]
        marks = mark_values(figure, claims, ours)
        f["linked"] = all(Path(p).is_file() for p in f["paper_files"])
        if f["linked"]:
            first = [load_result(p) for p in f["paper_files"]]
            pair = (mark_values(figure, claims, base), marks)
            made[f["name"]] = comparison_view(figure, first, data, who, pair)
        else:
            title = figure.filled_title(data[0].attrs)
            made[f["name"]] = figure_view(figure, data, title, marks)
    if not made:
        return Markup(""), {}
    head, divs = page_views(made)
    return Markup(head), {k: Markup(v) for k, v in divs.items()}


def build_scenario_report(
    scenario: Mapping,
    figures: Sequence[Mapping],
    claims_csv: str,
    claims_yaml: str,
    output: str,
    paper_claims_csv: str = "results/claims.csv",
) -> None:
    """Write scenario ``scenario``'s page (``{name, overrides, changes}``) to
    ``output``: ``figures`` lists each of the paper's figures (``name``, ``paper`` and
    ``scenario`` PNG paths, the latter None where the scenario changes nothing of it,
    and the ``changes`` it reads); ``claims_csv`` is the scenario's claims table."""
    declared = load_claims(claims_yaml)
    ids = [c["id"] for c in declared]
    try:
        table = read_table(claims_csv, ids)
    except ClaimsTableError as exc:
        raise ReportInputError(str(exc)) from None
    paper, paper_note = _paper_table(paper_claims_csv, ids)
    shown, unchanged, same = [], [], []
    for f in figures:
        title = FIGURES[f["name"]].title.split(":")[0]
        if f["scenario"] is None:
            unchanged.append(title)
            continue
        if same_values(f.get("files", [])):
            same.append(title)
            continue
        shown.append(
            {
                "name": f["name"],
                "files": [scenario for _, scenario in f.get("files", [])],
                "paper_files": [paper for paper, _ in f.get("files", [])],
                "title": title,
                "changes": f["changes"],
                "scenario": _figure_entry(f["scenario"]),
                "paper": _figure_entry(f["paper"]) if Path(f["paper"]).is_file() else None,
                "compare": (
                    _figure_entry(f["compare"])
                    if f.get("compare") and Path(f["compare"]).is_file()
                    else None
                ),
            }
        )
    views_head, views = _scenario_views(shown, declared, table, paper, scenario["name"])
    for f in shown:
        f["view"] = views.get(f["name"])
    rows = claim_rows(table, paper)
    html = ENVIRONMENT.get_template("scenario.html.j2").render(
        name=scenario["name"],
        changes=[c["text"] for c in scenario["changes"]],
        figures=shown,
        unchanged=unchanged,
        same=same,
        rows=rows,
        values=movement(rows),
        paper_note=paper_note,
        views_head=views_head,
        meta={
            "scenario": scenario["name"],
            "tennis_stroke version": __version__,
            "git commit": git_commit(),
            "built": datetime.now(UTC).isoformat(timespec="seconds"),
        },
    )
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    Path(output).write_text(html)
