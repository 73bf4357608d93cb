"""ReScience C's metadata of the article (``report/metadata.yaml``), and what the article
shares with it: the title's mark, decided from the claims table, and the authors, read
from ``CITATION.cff`` (the one place a user names them).

The file has the shape of ReScience C's template (``metadata-draft.yaml`` of
https://github.com/rescience-c/template, vendored in ``tools/rescience/``), which the
template's ``article.py`` reads key by key, stopping at the first one missing:

* ``code``, ``data``, ``replication``, ``review``, ``dates``, ``article`` and ``journal``
  are lists of one-key maps; ``keywords`` is one comma-separated string;
* the contact author is marked by ``*`` among the codes of the author's affiliations;
* the keys the editor fills after acceptance (``review``, the ``contributors``' names,
  ``dates``, ``article``, the journal's volume and issue) are present and empty.  The
  journal's name and ISSN are the journal's own and stay: the template's parser writes
  an empty one as the text ``None``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd
import yaml

from .claims import tally
from .formats import ReportInputError

#: The replicated article; ``key``: its BibTeX key (ReScience C's ``bib`` field).
ORIGINAL = {
    "key": "Youn2015",
    "authors": "Sun-Hyun Youn",
    "title": "Double pendulum model for tennis stroke including a collision process",
    "reference": "arXiv:1505.01916 [physics.pop-ph] (2015)",
    "url": "https://arxiv.org/abs/1505.01916",
    "doi": "10.48550/arXiv.1505.01916",
}
#: ReScience C's marks of a replication's title (the template's rule for ``title``): a
#: successful replication's and a failed one's.
SUCCESS, FAILURE = "[Re]", "[\u00acRe]"
#: The rule of the mark: a replication succeeds when more than this share of the paper's
#: held-out claims reproduce under the default reading.  Held out: the claims used for fit
#: chose the readings and cannot confirm them.  Every other claim counts, a deviation
#: declared beforehand (``known_deviation``) as much as an unexpected failure: a declared
#: reason explains a result of the paper that was not reproduced, it does not reproduce
#: it.  More than half: the title says whether the paper's results mostly stand, and the
#: article gives each claim's verdict.
SUCCESS_SHARE = 0.5
#: The ReScience C journal (``journal``: its name and ISSN, the editor's volume and issue).
JOURNAL = {"name": "ReScience C", "issn": "2430-3658"}
#: ORCID iDs in CITATION.cff are URLs; the template's are the bare iD.
_ORCID = re.compile(r"^https?://orcid\.org/")


def verdict(table: pd.DataFrame) -> dict:
    """The title's mark from a claims ``table`` (:data:`SUCCESS_SHARE`), with what
    decided it: the held-out claims, those that reproduce, their share (text) and the
    rule in words."""
    t = tally(table)
    held, reproduced = t["claims"]["held"], t["held"]["pass"]
    success = held > 0 and reproduced > SUCCESS_SHARE * held
    return {
        "mark": SUCCESS if success else FAILURE,
        "success": success,
        "held": held,
        "reproduced": reproduced,
        "share": f"{100 * reproduced / held:.0f} %" if held else "-",
        "rule": f"more than {100 * SUCCESS_SHARE:.0f} %",
    }


def title(mark: str) -> str:
    """The article's title: the mark, then the original's (the template's rule)."""
    return f"{mark} {ORIGINAL['title']}"


def read_citation(path: str | Path | None) -> dict:
    """``CITATION.cff`` as data ({} for None); unreadable: one line."""
    if path is None:
        return {}
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        problem = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ReportInputError(f"{path}: the citation file cannot be read ({problem})") from None
    if not isinstance(data, Mapping):
        raise ReportInputError(f"{path}: the citation file is not a mapping")
    return dict(data)


def _name(person: Mapping) -> str:
    """A CFF person's or entity's name as the template writes it: ``Given Family``, or
    ``particle Family, Given`` where the family name is not the last word (the template
    takes the last word, or what stands before a comma, as the family name)."""
    if person.get("name"):  # an entity
        return str(person["name"])
    given, family = str(person.get("given-names", "")), str(person.get("family-names", ""))
    family = " ".join(p for p in (str(person.get("name-particle", "")), family) if p)
    suffix = str(person.get("name-suffix", ""))
    if len(family.split()) > 1 and given:
        return f"{family}, {given}" + (f" {suffix}" if suffix else "")
    return " ".join(p for p in (given, family, suffix) if p)


def _affiliation(person: Mapping) -> tuple[str, str] | None:
    """An author's affiliation (name, address): a person's ``affiliation``; an entity
    (a group as author) is its own, at its address."""
    if person.get("name"):
        where = ", ".join(str(person[k]) for k in ("address", "city", "country") if person.get(k))
        return str(person["name"]), where
    if person.get("affiliation"):
        return str(person["affiliation"]), ""
    return None


def _same(a: Mapping, b: Mapping) -> bool:
    """The same person: the same ORCID, email or name."""
    return any(a.get(k) and a.get(k) == b.get(k) for k in ("orcid", "email")) or _name(a) == _name(
        b
    )


def authors(citation: Mapping) -> tuple[list[dict], list[dict]]:
    """The template's ``authors`` and ``affiliations`` from ``citation`` (CITATION.cff as
    data): each author's name, ORCID iD, email and affiliation codes (``1,2``), the
    contact author (the first of CFF's ``contact`` who is an author, else the first
    author) marked ``*``; the affiliations numbered in the order they first occur.
    Without authors, one empty author and affiliation: the template's shape, to fill.

    Raises
    ------
    ReportInputError
        The contact author has no affiliation: the template marks the contact by a ``*``
        beside an affiliation's code and reads no contact from a lone ``*``.
    """
    people = [p for p in citation.get("authors") or [] if isinstance(p, Mapping)]
    if not people:
        return (
            [{"name": "", "orcid": "", "email": "", "affiliations": "1,*"}],
            [{"code": 1, "name": "", "address": ""}],
        )
    contacts = [p for p in citation.get("contact") or [] if isinstance(p, Mapping)]
    contact = next((i for c in contacts for i, p in enumerate(people) if _same(p, c)), 0)
    codes: dict[tuple[str, str], int] = {}
    out = []
    for i, person in enumerate(people):
        where = _affiliation(person)
        if where is not None:
            codes.setdefault(where, len(codes) + 1)
        marks = [str(codes[where])] if where is not None else []
        if i == contact:
            if not marks:
                raise ReportInputError(
                    f"CITATION.cff: the contact author {_name(person)!r} has no affiliation: "
                    "ReScience C marks the contact by '*' beside an affiliation's code"
                )
            marks.append("*")
        out.append(
            {
                "name": _name(person),
                "orcid": _ORCID.sub("", str(person.get("orcid", ""))),
                "email": str(person.get("email", "")),
                "affiliations": ",".join(marks),
            }
        )
    affiliations = [
        {"code": code, "name": name, "address": address} for (name, address), code in codes.items()
    ]
    return out, affiliations


def byline(citation: Mapping) -> dict:
    """The article's byline from ``citation``: each author with the codes of their
    affiliations, the affiliations, and the contact (name and email); ``names`` empty
    without authors."""
    people, affiliations = authors(citation)
    if not any(p["name"] for p in people):
        return {"names": [], "affiliations": [], "contact": ""}
    contact = next(p for p in people if p["affiliations"].endswith("*"))
    return {
        "names": [{"name": p["name"], "codes": p["affiliations"]} for p in people],
        "affiliations": [
            {"code": str(a["code"]), "text": ", ".join(v for v in (a["name"], a["address"]) if v)}
            for a in affiliations
        ],
        "contact": contact["name"] + (f" <{contact['email']}>" if contact["email"] else ""),
    }


def metadata(
    title: str,
    abstract: str,
    citation: Mapping,
    code_url: str = "",
    software: Sequence[str] = (),
) -> dict:
    """``report/metadata.yaml``: every key of ReScience C's template, in its order and
    shape (module docstring), the title and abstract the article's, the authors,
    keywords and code URL (``code_url``, else CFF's ``repository-code``) from
    ``citation``; then ``software``, what the replication runs on (not a template key:
    the template's parser reads none it does not know)."""
    people, affiliations = authors(citation)
    keywords = [str(k) for k in citation.get("keywords") or []]
    return {
        "title": title,
        "authors": people,
        "affiliations": affiliations,
        "keywords": ", ".join(keywords),
        "code": [
            {"url": code_url or str(citation.get("repository-code", "")) or None},
            {"doi": None},
        ],
        "data": [{"url": None}, {"doi": None}],
        "replication": [
            {"cite": f"{ORIGINAL['authors']}, {ORIGINAL['title']}, {ORIGINAL['reference']}"},
            {"bib": ORIGINAL["key"]},
            {"url": ORIGINAL["url"]},
            {"doi": ORIGINAL["doi"]},
        ],
        "abstract": abstract,
        "bibliography": None,
        "type": "Replication",
        "domain": "Sports physics",
        "language": "Python",
        # the editor's, after acceptance
        "review": [{"url": None}],
        "contributors": [
            {"name": None, "orcid": None, "role": role}
            for role in ("editor", "reviewer", "reviewer")
        ],
        "dates": [{"received": None}, {"accepted": None}, {"published": None}],
        "article": [{"number": None}, {"doi": None}, {"url": None}],
        "journal": [
            {"name": JOURNAL["name"]},
            {"issn": JOURNAL["issn"]},
            {"volume": None},
            {"issue": None},
        ],
        "software": list(software),
    }


class _Dumper(yaml.SafeDumper):
    """YAML as the template writes it: an empty value is nothing after its key."""


_Dumper.add_representer(
    type(None), lambda dumper, _: dumper.represent_scalar("tag:yaml.org,2002:null", "")
)
#: The first lines of the written file: where its values come from.
HEADER = (
    "# ReScience C metadata (the template's metadata.yaml), written by tennis-stroke from\n"
    "# the results and CITATION.cff at every run: name the authors in CITATION.cff.\n"
)


def metadata_text(meta: Mapping) -> str:
    """``meta`` as the file's text: :data:`HEADER`, then the keys in their order."""
    return HEADER + yaml.dump(
        dict(meta), Dumper=_Dumper, sort_keys=False, allow_unicode=True, width=88
    )
