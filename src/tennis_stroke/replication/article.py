"""The replication as an article: ``report/article.pdf``, a ReScience-style [Re] paper
written from the result files, and ``report/metadata.yaml`` in ReScience C's format.

Every number in the article is read from the results: the claims table
(``results/claims.csv``: each claim's paper value, ours, tolerance, verdict, robustness
class and evidence), the paper's figures (``results/figures/*.png``), the configuration
record and the result files' provenance (commit, lock).  The text around them is the
template ``templates/article.typ``, typeset by the Typst compiler (the ``typst`` wheel:
no LaTeX).  The template reads the numbers from a JSON file as data, never as markup, so
no text from a file can change the layout.  A missing or unreadable input is one line
(:class:`~tennis_stroke.replication.formats.ReportInputError`).
"""

from __future__ import annotations

import json
import platform
import re
import shutil
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd
import yaml

from ..inference.claims import load_claims
from ..io.config_files import load_yaml
from ..io.netcdf import load_result
from ..model.params import READINGS
from .claims import ClaimsTableError, read_table
from .formats import ReportInputError, _number, _timings
from .registry import FIGURES

#: The article's template (Typst), beside the report's templates, and a scenario's.
TEMPLATE = Path(__file__).parent / "templates" / "article.typ"
#: The replicated article.
ORIGINAL = {
    "authors": "Sun-Hyun Youn",
    "title": "Double pendulum model for tennis stroke including a collision process",
    "reference": "arXiv:1505.01916 [physics.pop-ph] (2015)",
    "url": "https://arxiv.org/abs/1505.01916",
    "doi": "10.48550/arXiv.1505.01916",
}
TITLE = f"[Re] {ORIGINAL['title']}"
#: The verdicts and robustness classes in the article's words.
VERDICTS = {
    "pass": "reproduced",
    "known_deviation": "deviates",
    "used_for_fit": "used for fit",
    "fail": "fails",
}
_FIGURE = re.compile(r"Fig\. (\d+)")
_SECTION = re.compile(r"Sec\. ([IVX]+)")


def _claim(c: Mapping) -> dict:
    return {
        "id": str(c["id"]),
        "quantity": str(c["quantity"]),
        "unit": str(c["unit"]),
        "paper": _number(float(c["paper_value"])),
        "ours": _number(float(c["reproduced_value"])),
        "tolerance": _number(float(c["tolerance"])),
        "verdict": VERDICTS.get(str(c["status"]), str(c["status"])),
        "robustness": str(c.get("robustness", "") or "").replace("_", " "),
        "evidence": str(c.get("evidence", "") or "").replace("_", " "),
        "cause": str(c.get("reason", "") or c.get("map_cause", "") or ""),
    }


def _counts(table: pd.DataFrame) -> dict:
    status = table["status"].value_counts()
    deviating = table[table["status"] == "known_deviation"]
    held = table[table["status"] != "used_for_fit"]
    robustness = held["robustness"].value_counts() if "robustness" in held else pd.Series()
    return {
        "claims": int(len(table)),
        "reproduced": int(status.get("pass", 0)),
        "deviating": int(status.get("known_deviation", 0)),
        "failing": int(status.get("fail", 0)),
        "fit": int(status.get("used_for_fit", 0)),
        "evidence": [
            {"class": str(k).replace("_", " "), "n": int(n)}
            for k, n in deviating["evidence"].fillna("not classified").value_counts().items()
        ],
        "robustness": [
            {"class": str(k).replace("_", " "), "n": int(n)} for k, n in robustness.items()
        ],
    }


def _sections(table: pd.DataFrame, figures: Mapping[str, str], titles: Mapping) -> list[dict]:
    """One subsection per section of the paper: its figures (each with the claims its
    source names) and its other claims."""
    out = []
    for sid, spec in titles.items():
        claims = [c for c in table.to_dict("records") if sid in _SECTION.findall(c["source"])]
        shown = []
        for name, path in figures.items():
            figure = FIGURES[name]
            if figure.section != sid:
                continue
            number = name[3:5].lstrip("0")
            own = [c for c in claims if number in _FIGURE.findall(c["source"])]
            shown.append(
                {
                    "file": Path(path).name,
                    "title": figure.title.split(":")[0],
                    "claims": [_claim(c) for c in own],
                }
            )
        placed = {c["id"] for f in shown for c in f["claims"]}
        out.append(
            {
                "id": sid,
                "title": spec.get("title", ""),
                "figures": shown,
                "claims": [_claim(c) for c in claims if c["id"] not in placed],
            }
        )
    return out


def _provenance(results: Sequence[str]) -> dict:
    """The commit and lock the result files record, and the machine this ran on."""
    commits, locks = set(), set()
    for path in results:
        attrs = load_result(path).attrs
        commits.add(str(attrs.get("git_commit", "unknown")))
        locks.add(str(attrs.get("environment_lock_sha256_16", "unknown")))
    return {
        "commits": sorted(commits),
        "locks": sorted(locks),
        "machine": f"{platform.system()} {platform.machine()}, Python {platform.python_version()}",
    }


def article_data(
    claims_csv: str,
    claims_yaml: str,
    figures: Mapping[str, str],
    results: Sequence[str],
    job_seconds: float | None = None,
) -> dict:
    """Everything the article states, from the result files (the template's data)."""
    declared = load_claims(claims_yaml)
    try:
        table = read_table(claims_csv, [c["id"] for c in declared])
    except ClaimsTableError as exc:
        raise ReportInputError(str(exc)) from None
    titles = (load_yaml(claims_yaml) or {}).get("sections") or {}
    return {
        "title": TITLE,
        "original": ORIGINAL,
        "counts": _counts(table),
        "sections": _sections(table, figures, titles),
        "claims": [_claim(c) for c in table.to_dict("records")],
        "deviations": [
            _claim(c) for c in table.to_dict("records") if c["status"] == "known_deviation"
        ],
        "readings": [
            {
                "name": r.name,
                "choices": ", ".join(r.choices),
                "default": r.default,
                "literal": r.literal,
                "description": r.description,
            }
            for r in READINGS.values()
        ],
        "provenance": _provenance(results),
        "job_seconds": "-" if job_seconds is None else f"{job_seconds:.0f}",
    }


def job_seconds(benchmarks: Path) -> float | None:
    """The wall time of the paper's run's jobs summed (the report's table of timings,
    :func:`~tennis_stroke.replication.report._timings`, less this job), or None without
    any."""
    timings = _timings(benchmarks) if benchmarks.is_dir() else pd.DataFrame()
    if timings.empty:
        return None
    return float(timings.loc[timings["job"] != "article", "wall time (s)"].sum())


def locked_software(lock: str | Path | None) -> list[str]:
    """``name==version`` of every package the lock pins (``requirements.lock``)."""
    if lock is None or not Path(lock).is_file():
        return []
    found = re.findall(r"^([A-Za-z0-9_.\-]+==[^\s\\;]+)", Path(lock).read_text(), flags=re.M)
    return sorted(set(found), key=str.lower)


def metadata(data: Mapping, repository: str = "", software: Sequence[str] = ()) -> dict:
    """``report/metadata.yaml``: the fields of ReScience C's template, the authors left
    to fill; ``software``: the packages of the lock."""
    commits = data["provenance"]["commits"]
    return {
        "title": data["title"],
        "authors": [{"name": "(to fill)", "orcid": "(to fill)", "affiliations": "1"}],
        "affiliations": [{"code": "1", "name": "(to fill)"}],
        "contact": {"name": "(to fill)", "email": "(to fill)"},
        "code": {"url": repository or "(to fill)", "commit": commits[0] if commits else ""},
        "data": {"url": "results/ (this run)", "lock": ", ".join(data["provenance"]["locks"])},
        "replication": {
            "cite": f"{ORIGINAL['authors']}, {ORIGINAL['title']}, {ORIGINAL['reference']}",
            "bib": ORIGINAL["doi"],
            "url": ORIGINAL["url"],
            "doi": ORIGINAL["doi"],
        },
        "type": "Replication",
        "language": "Python",
        "domain": "Sports physics, biomechanics",
        "keywords": ["double pendulum", "tennis", "collision", "replication"],
        "software": list(software),
    }


def _require(*paths) -> None:
    """One line naming the first input of an article that does not exist."""
    missing = [p for p in paths if not Path(p).is_file()]
    if missing:
        raise ReportInputError(f"the article needs {missing[0]}, which does not exist")


def _typeset(template: Path, data: Mapping, images: Sequence[str], output_pdf: str) -> None:
    """Typeset ``template`` with ``data`` (as ``data.json``) and ``images`` beside it."""
    import typst  # the workflow's extra: only the article jobs load it

    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        shutil.copy(template, work / template.name)
        for path in images:
            shutil.copy(path, work / Path(path).name)
        (work / "data.json").write_text(json.dumps(data))
        pdf = typst.compile(str(work / template.name), root=str(work))
    Path(output_pdf).parent.mkdir(parents=True, exist_ok=True)
    Path(output_pdf).write_bytes(pdf)


def build_article(
    claims_csv: str,
    claims_yaml: str,
    figures: Sequence[str],
    results: Sequence[str],
    output_pdf: str,
    output_metadata: str,
    job_seconds: float | None = None,
    repository: str = "",
    lock: str | Path | None = None,
) -> None:
    """Write the article (``output_pdf``) and its ``metadata.yaml`` from the results
    (``lock``: ``requirements.lock``, the software it lists)."""
    _require(claims_csv, claims_yaml, *figures, *results)
    shown = {Path(p).stem: p for p in figures if Path(p).stem in FIGURES}
    data = article_data(claims_csv, claims_yaml, shown, results, job_seconds)
    _typeset(TEMPLATE, data, list(shown.values()), output_pdf)
    Path(output_metadata).write_text(
        yaml.safe_dump(
            metadata(data, repository, locked_software(lock)), sort_keys=False, allow_unicode=True
        )
    )
