"""One term, one meaning (issue 66, case 22): the page called a group of deviation causes
"reading dependent" just below "11 reading-dependent" robustness classes.  The words of
the robustness classes and of the evidence classes come from one place
(:func:`tennis_stroke.replication.robustness.class_words`) and share no term; an
irreducible claim's text says first why a reading found after the results does not
count."""

import re
from pathlib import Path

import yaml
from claim_tables import declared_table, with_verdicts

from tennis_stroke.replication import robustness as rb
from tennis_stroke.replication.article import _counts, abstract

ROOT = Path(__file__).resolve().parents[2]


def _term(text: str) -> str:
    return re.sub(r"[-_\s]+", " ", text).strip().lower()


def test_no_robustness_class_and_evidence_class_share_a_term():
    robustness = {_term(k) for k in rb.ROBUSTNESS} | {
        _term(w) for w in rb.ROBUSTNESS_WORDS.values()
    }
    evidence = {_term(k) for k in rb.EVIDENCE} | {_term(rb.class_words(k)) for k in rb.EVIDENCE}
    assert robustness.isdisjoint(evidence), robustness & evidence


def test_the_abstract_names_each_class_by_its_one_term():
    table = with_verdicts(declared_table(robustness=True), outside=["fig11_theta_c"])
    table.loc[table["id"] == "fig11_theta_c", "evidence"] = "reading_choice"
    text = abstract(_counts(table))
    assert "reading choice" in text and "reading dependent" not in text
    assert text.count("reading-dependent") == 1  # the robustness class, once


def test_an_irreducible_reason_says_first_why_a_later_reading_does_not_count():
    claims = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())["claims"]
    later = [
        c
        for c in claims
        if str(c.get("reason", "")).startswith("irreducible") and "after the results" in c["reason"]
    ]
    assert later  # Figs. 13-14
    for c in later:
        reason = c["reason"]
        first_number = re.search(r"\d", reason).start()
        assert reason.find("does not count") in range(first_number), c["id"]


def test_a_reason_that_opens_with_a_class_names_an_evidence_class():
    """A known deviation's reason opens with its cause, an evidence class: fig6's still
    opened with the robustness class's key, reading_dependent, after the rename."""
    claims = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())["claims"]
    keys = set(rb.EVIDENCE) | set(rb.ROBUSTNESS)
    opening = {
        c["id"]: word
        for c in claims
        if (word := re.match(r"(\w+)", c.get("reason", ""))) and (word := word[1]) in keys
    }
    assert opening and all(w in rb.EVIDENCE for w in opening.values()), opening
