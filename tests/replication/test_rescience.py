"""ReScience C's metadata (tennis_stroke.replication.rescience), in-process on small
claims tables: every key of the template (``tools/rescience/metadata-draft.yaml``, the
vendored original) in its order and shape, the editor's keys empty, the title's mark by
the stated rule, the authors from CITATION.cff with the contact marked as the template
marks it."""

import pytest
import yaml
from claim_tables import declared_table, with_verdicts
from conftest import ROOT
from rescience_shape import TEMPLATE, departures

from tennis_stroke.replication.article import _counts, abstract
from tennis_stroke.replication.formats import ReportInputError
from tennis_stroke.replication.rescience import (
    FAILURE,
    SUCCESS,
    authors,
    byline,
    metadata,
    metadata_text,
    read_citation,
    title,
    verdict,
)

#: The original's title, after the mark.
ORIGINAL_TITLE = "Double pendulum model for tennis stroke including a collision process"
#: The keys the editor fills after acceptance (the template's second part), by section.
EDITORS = ("review", "contributors", "dates", "article")
#: A citation file's authors: two persons at two places, the second with a particle, an
#: ORCID URL and an email, and the contact by CFF's ``contact``.
CITATION = {
    "cff-version": "1.2.0",
    "repository-code": "https://github.com/example/tennis-stroke",
    "keywords": ["tennis", "double pendulum"],
    "authors": [
        {"given-names": "Ada", "family-names": "Lovelace", "affiliation": "Analytical Society"},
        {
            "given-names": "Ludwig",
            "name-particle": "van",
            "family-names": "Beethoven",
            "orcid": "https://orcid.org/0000-0002-1825-0097",
            "email": "lvb@example.org",
            "affiliation": "Bonn Court Orchestra",
        },
    ],
    "contact": [{"given-names": "Ludwig", "family-names": "Beethoven", "email": "lvb@example.org"}],
}


def written(table, citation=CITATION, code_url=""):
    """The metadata file's text for a claims ``table``, read back."""
    counts = _counts(table)
    meta = metadata(
        title(verdict(table)["mark"]), abstract(counts), citation, code_url, ["numpy==2.3.5"]
    )
    return yaml.safe_load(metadata_text(meta))


def test_the_metadata_has_every_key_of_the_template_in_its_shape():
    meta = written(declared_table())
    assert departures(meta) == []
    # the editor's keys present and empty; the contributors' roles as the template's
    for key in EDITORS:
        for entry in meta[key]:
            assert all(v is None for k, v in entry.items() if k != "role"), (key, entry)
    assert [c["role"] for c in meta["contributors"]] == [
        c["role"] for c in TEMPLATE["contributors"]
    ]
    journal = {k: v for entry in meta["journal"] for k, v in entry.items()}
    assert journal == {"name": "ReScience C", "issn": "2430-3658", "volume": None, "issue": None}
    assert meta["type"] == "Replication" and meta["language"] == "Python"
    assert isinstance(meta["keywords"], str) and meta["keywords"] == "tennis, double pendulum"
    code = {k: v for entry in meta["code"] for k, v in entry.items()}
    assert code == {"url": "https://github.com/example/tennis-stroke", "doi": None}
    replication = {k: v for entry in meta["replication"] for k, v in entry.items()}
    assert replication["bib"] == "Youn2015"
    assert replication["url"] == "https://arxiv.org/abs/1505.01916"
    assert "35 claims reproduce, 0 deviate, 0 fail, and 13 were used" in meta["abstract"]
    assert meta["software"] == ["numpy==2.3.5"]


def test_the_authors_come_from_the_citation_file_the_contact_marked_by_a_star():
    meta = written(declared_table())
    assert meta["authors"] == [
        {"name": "Ada Lovelace", "orcid": "", "email": "", "affiliations": "1"},
        {
            "name": "van Beethoven, Ludwig",  # the template reads the family name before a comma
            "orcid": "0000-0002-1825-0097",
            "email": "lvb@example.org",
            "affiliations": "2,*",
        },
    ]
    assert meta["affiliations"] == [
        {"code": 1, "name": "Analytical Society", "address": ""},
        {"code": 2, "name": "Bonn Court Orchestra", "address": ""},
    ]
    assert byline(CITATION)["contact"] == "van Beethoven, Ludwig <lvb@example.org>"
    # without a contact the first author is; the project's own file gives one author
    first, _ = authors({**CITATION, "contact": []})
    assert [a["affiliations"] for a in first] == ["1,*", "2"]
    (ours,), (place,) = authors(read_citation(ROOT / "CITATION.cff"))
    assert ours["affiliations"] == "1,*" and place["name"] == ours["name"]
    # no citation file: the template's shape with nothing filled
    (empty,), _ = authors({})
    assert empty == {"name": "", "orcid": "", "email": "", "affiliations": "1,*"}
    assert byline({})["names"] == []


def test_a_contact_author_without_an_affiliation_is_one_line():
    people = [{"given-names": "Ada", "family-names": "Lovelace"}]
    with pytest.raises(ReportInputError, match="the contact author 'Ada Lovelace' has no"):
        authors({"authors": people})


def test_the_title_s_mark_is_the_share_of_held_out_claims_that_reproduce():
    """[Re] with more than half of the held-out claims reproducing, [¬Re] at half or
    fewer; a declared deviation counts as not reproduced, the fit set not at all."""
    table = declared_table()
    assert written(table)["title"] == f"{SUCCESS} {ORIGINAL_TITLE}"
    held = list(table.loc[table["fit_set"] == "", "id"])
    fit = list(table.loc[table["fit_set"] != "", "id"])
    # an even number held out (34), so that exactly half can reproduce
    table = table[table["id"] != held.pop()].reset_index(drop=True)
    declared = set(table.loc[table["expectation"] == "known_deviation", "id"])
    half = len(held) // 2
    outside = sorted(held, key=lambda i: i not in declared)[:half]  # the declared first
    at_half = with_verdicts(table, outside=outside)
    above = with_verdicts(table, outside=outside[:-1] + fit)
    assert (at_half["status"] == "known_deviation").sum() == len(declared & set(held))
    assert verdict(at_half)["reproduced"] == half and verdict(at_half)["mark"] == FAILURE
    assert verdict(above)["reproduced"] == half + 1 and verdict(above)["mark"] == SUCCESS
    assert written(at_half)["title"] == f"[\u00acRe] {ORIGINAL_TITLE}"
    assert verdict(above)["share"] == f"{100 * (half + 1) / len(held):.0f} %"
    assert verdict(table.iloc[0:0])["mark"] == FAILURE  # nothing held out: nothing confirmed
