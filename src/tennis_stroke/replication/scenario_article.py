"""A scenario's article: ``report/scenarios/NAME/article.pdf``, an exploration beside the
paper, never a replication (:mod:`tennis_stroke.replication.article` typesets it): the
scenario's changes, the figures it changes against the paper's, every claim under both
configurations with the signed change, and no verdict.  Its own module, so that the
paper's article does not depend on the scenario page's code."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from ..inference.claims import load_claims
from .article import _require, _typeset
from .claims import ClaimsTableError, read_table
from .formats import ReportInputError
from .registry import FIGURES
from .rescience import ORIGINAL
from .scenario_report import _paper_table, claim_rows, movement

SCENARIO_TEMPLATE = Path(__file__).parent / "templates" / "scenario_article.typ"


def build_scenario_article(
    scenario: Mapping,
    comparisons: Sequence[str],
    claims_csv: str,
    claims_yaml: str,
    output_pdf: str,
    paper_claims_csv: str = "results/claims.csv",
) -> None:
    """Write scenario ``scenario``'s article (``{name, changes}``; ``comparisons``: the
    PNGs of the figures it changes against the paper's): an exploration beside the
    paper, never a replication: its changes, the figures and every claim under both
    configurations, the change signed."""
    _require(claims_csv, claims_yaml, *comparisons)
    ids = [c["id"] for c in load_claims(claims_yaml)]
    try:
        table = read_table(claims_csv, ids)
    except ClaimsTableError as exc:
        raise ReportInputError(str(exc)) from None
    paper, note = _paper_table(paper_claims_csv, ids)
    rows = claim_rows(table, paper)
    name = str(scenario["name"])
    data = {
        "title": f"What if {name}: an exploration beside the replication",
        "original": ORIGINAL,
        "scenario": {"name": name, "changes": [c["text"] for c in scenario["changes"]]},
        "figures": [
            {"file": Path(p).name, "title": FIGURES[Path(p).stem].title.split(":")[0]}
            for p in comparisons
        ],
        "rows": [{k: str(v) for k, v in r.items()} for r in rows],
        "values": movement(rows),
        "paper_note": note,
    }
    _typeset(SCENARIO_TEMPLATE, data, comparisons, output_pdf)
