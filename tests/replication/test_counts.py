"""Counts that add up: every count line of the report's scoreboard, its causes, the
README's table and a scenario's page is a partition of the claims table it counts (each
claim in exactly one part), for the paper's configuration and for an edited one, whose
fit claims and held-out claims may lie outside their tolerance (issue 53, finding 4)."""

import re
import sys

import pandas as pd
import pytest
from claim_tables import declared_table, edited_shape, numbers, papers_shape, with_verdicts
from conftest import ROOT

from tennis_stroke.replication.claims import TALLIES, tally
from tennis_stroke.replication.report import _deviation_groups, _score, claim_row
from tennis_stroke.replication.scenario_report import claim_rows, movement

sys.path.insert(0, str(ROOT / "tools"))
import readme_results  # noqa: E402


def _shapes():
    base = declared_table()
    held = [i for i, f in zip(base["id"], base["fit_set"], strict=True) if not f]
    fit = [i for i, f in zip(base["id"], base["fit_set"], strict=True) if f]
    return {
        "paper": papers_shape(base),
        "edited": edited_shape(base),
        "edited, every other": edited_shape(base, every=2),
        "every claim outside": with_verdicts(base, outside=held + fit),
        "every claim inside": base,
        "no robustness analysis": edited_shape(declared_table(robustness=False)),
    }


SHAPES = _shapes()


def _sets(table: pd.DataFrame) -> dict[str, pd.Series]:
    """Each set a count line counts, read from the table here (not from the code)."""
    held = table["fit_set"] == ""
    outside = table["status"].isin(["known_deviation", "fail"])
    return {
        "claims": held | ~held,
        "held": held,
        "fit": ~held,
        "known_deviation": held & (table["status"] == "known_deviation"),
        "fail": held & (table["status"] == "fail"),
        "outside": ~held & outside,
        "outside_tolerance": outside,
        "robustness": held,
    }


def test_the_edited_shapes_hold_what_the_counts_once_mixed_up():
    """The edited tables have fit claims outside their tolerance and held-out claims
    failing (what made '7 deviate' list 15 causes and 23 + 7 + 8 of 35)."""
    edited = SHAPES["edited"]
    fit = edited["fit_set"] != ""
    assert (fit & edited["status"].isin(["known_deviation", "fail"])).any()
    assert (~fit & (edited["status"] == "fail")).any()
    assert (~fit & (edited["status"] == "known_deviation")).any()


@pytest.mark.parametrize("shape", SHAPES)
def test_every_tally_is_a_partition_of_its_set(shape):
    table = SHAPES[shape]
    counts = tally(table)
    sets = _sets(table)
    assert set(counts) <= set(TALLIES)
    for name, count in counts.items():
        assert count.total == int(sets[name].sum()), name
        assert sum(n for _, n in count.parts) == count.total, (name, count)
        assert all(n > 0 for _, n in count.parts), (name, count)


@pytest.mark.parametrize("shape", SHAPES)
def test_the_scoreboard_adds_up(shape):
    """The cards: held-out claims that reproduce, deviate or fail make the held-out
    claims; each cause list makes its card; the claims used for fit are within or
    outside their tolerance; the section below the board makes every claim outside its
    tolerance, by status and by cause (each claim in one cause group)."""
    table = SHAPES[shape]
    score = _score(table)
    sets = _sets(table)
    assert score["pass"] + score["deviate"] + score["fail"] == score["held"]
    assert score["held"] == int(sets["held"].sum())
    assert score["fit_ok"] + score["fit_outside"] == score["fit"] == int(sets["fit"].sum())
    assert score["held"] + score["fit"] == score["claims"] == len(table)
    for card, n in (
        ("known_deviation", score["deviate"]),
        ("fail", score["fail"]),
        ("outside", score["fit_outside"]),
    ):
        assert sum(c["n"] for c in score["causes"][card]) == n, card
    assert score["outside"] == score["deviate"] + score["fail"] + score["fit_outside"]
    groups = _deviation_groups([claim_row(c) for c in table.to_dict("records")])
    members = [c["id"] for g in groups for c in g["claims"]]
    assert len(members) == len(set(members)) == score["outside"]
    assert set(members) == set(table["id"][sets["outside_tolerance"]])


def _readme_rows(text: str) -> dict[str, list]:
    rows = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 5 and cells[1].isdigit() and not cells[0].startswith("`"):
            rows[cells[0]] = [int(cells[1]), *(int(c) if c.isdigit() else c for c in cells[2:])]
    return rows


@pytest.mark.parametrize("shape", [s for s in SHAPES if s != "no robustness analysis"])
def test_the_readme_s_table_adds_up(shape):
    """Its rows make every claim; a held-out row's robustness cells make the row; the
    sentence over the list of claims outside their tolerance counts the list."""
    table = SHAPES[shape]
    text = readme_results.block(table)
    rows = _readme_rows(text)
    assert sum(r[0] for r in rows.values()) == len(table), rows
    for word, (total, *cells) in rows.items():
        if "-" not in cells:
            assert sum(cells) == total, (word, total, cells)
    head = re.match(r"(\d+) claims: the (\d+) held out .*?, then the (\d+) used for fit", text)
    assert head and int(head[1]) == len(table) == int(head[2]) + int(head[3])
    listed = [line for line in text.splitlines() if line.startswith("| `")]
    sentence = re.search(r"The (.*) under the default reading", text)
    if listed:
        said = [int(n) for n in re.findall(r"(\d+) (?:claims? that|used for fit)", sentence[1])]
        assert sum(said) == len(listed), sentence[1]
    else:
        assert sentence is None


def test_the_scenario_page_s_values_add_up():
    """Each claim's value moves, stays or cannot be compared (no number under one of
    the two configurations, or no table of the paper's configuration at all)."""
    scenario = declared_table()
    paper = scenario.copy()
    paper.loc[0, "reproduced_value"] = "1e9"  # moves
    paper.loc[1, "reproduced_value"] = "nan"  # no number under the paper's configuration
    scenario.loc[2, "reproduced_value"] = "nan"  # none under the scenario
    values = movement(claim_rows(scenario, paper))
    assert values == {"all": len(scenario), "moved": 1, "same": len(scenario) - 3, "uncompared": 2}
    assert movement(claim_rows(scenario, None)) == {
        "all": len(scenario),
        "moved": 0,
        "same": 0,
        "uncompared": len(scenario),
    }


def test_the_cause_lists_read_back_from_text():
    """The helper the page tests read counts with."""
    assert numbers("1 ill conditioned, 4 irreducible, 12 reading dependent") == [1, 4, 12]
