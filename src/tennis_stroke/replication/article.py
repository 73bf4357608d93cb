"""The replication as an article: ``report/article.pdf``, a ReScience C paper (``[Re]`` or
``[¬Re]`` by its claims) written from the result files, and ``report/metadata.yaml`` in
ReScience C's format (:mod:`.rescience`: the title's mark from the claims table, the authors
from ``CITATION.cff``).

Every number in the article is read from the results: the claims table
(``results/claims.csv``: each claim's paper value, ours, tolerance, verdict, robustness
class and evidence), the paper's figures (``results/figures/*.png``), the result files'
provenance (commit, lock, Python: each stated from every file, a mix stated as a mix).
The claims go where the report puts them (:func:`~.report.paper_sections`), each row as
the report writes it (:func:`~.report.claim_row`), and the table is the one
``tennis-stroke claims`` accepts (:func:`~.claims.checked_table`).  The model's equations
are rendered from the code that computes them (:mod:`.article_equations`).  The
Discussion and the Conclusion are sentences around the claims table's counts, classes
and deciding readings, never a number typed by hand.

The text around them is the template ``templates/article.typ``, typeset by the Typst
compiler (the ``typst`` wheel: no LaTeX).  The template reads everything from a JSON
file as data, never as markup (but the equations, Typst math this package writes from
its own source), so no text from a result file can change the layout.  A missing,
damaged or unreadable input is one line
(:class:`~tennis_stroke.replication.formats.ReportInputError`) and the previous PDF is
kept: the PDF is written to a temporary file beside it and renamed on success.
"""

from __future__ import annotations

import json
import re
import shutil
import sys
import tempfile
import tomllib
from collections import Counter
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from ..inference.claims import load_claims
from ..io.config_files import load_yaml
from ..io.environment import canonical, locked
from ..io.netcdf import load_result, write_bytes_whole
from ..model.params import READINGS
from ..studies.tables import rule_table
from .analyses import rule_caption
from .article_equations import EquationError, equations
from .claims import ClaimsTableError, checked_table, tally
from .formats import ReportInputError, _timings
from .registry import FIGURES
from .report import check_image, claim_row, paper_sections
from .rescience import ORIGINAL, byline, metadata, metadata_text, read_citation, title, verdict
from .robustness import CONFIDENCE, EVIDENCE_MEANING, across_short, class_words

#: The article's template (Typst), beside the report's templates, and a scenario's.
TEMPLATE = Path(__file__).parent / "templates" / "article.typ"
#: The provenance the article states: global attributes every result file records.
PROVENANCE = {
    "git_commit": "commit",
    "environment_lock_sha256_16": "lock (SHA-256 of requirements.lock, first 16 digits)",
    "environment_is_lock": "environment is the lock",
    "python_version": "Python",
    "tennis_stroke_version": "tennis-stroke",
}
#: The extras of ``pyproject.toml`` the workflow runs on (besides the dependencies).
RUNTIME_EXTRAS = ("workflow",)
#: Names listed per value of a mixed provenance fact, at most.
SHOWN_NAMES = 4


def _with_unit(value: str, unit: str) -> str:
    """A value the report wrote (:func:`~.report.claim_row`) with its unit, none after
    a value that is none (``-``) or a yes/no, with a space: ``0.185 s``, ``20 deg``."""
    if not unit or value in ("-", "yes", "no"):
        return value
    return f"{value} {unit}"


def _row(row: Mapping) -> dict:
    """A claim as the article's tables show it: the report's row, every value with its
    unit."""
    unit = row["unit_short"]
    return {
        "id": row["id"],
        "source": row["source"],
        "quantity": row["quantity"],
        "paper": _with_unit(row["paper"], unit),
        "ours": _with_unit(row["ours"], unit),
        "tolerance": row["tolerance"].strip(),
        "verdict": f"{row['word']} ({row['optimum_short']})"
        if row["optimum_short"]
        else row["word"],
    }


def _caption(name: str, attrs: Mapping[str, Mapping]) -> str:
    """A figure's title, filled from its first result file's attributes where the
    article has it, else its number (the paper's: the article's only figure numbers)."""
    figure = FIGURES[name]
    found = next((a for path, a in attrs.items() if path.endswith(figure.inputs[0])), None)
    if found is not None:
        try:
            return figure.filled_title(found)
        except (KeyError, ValueError, IndexError):
            pass
    return figure.title.split(":")[0] if "{" in figure.title else figure.title


def _sections(
    rows: list[dict], figures: Mapping[str, str], attrs: Mapping, paper: Mapping
) -> list[dict]:
    """The paper's sections as the report places them (:func:`~.report.paper_sections`):
    per block its heading, the paper's statement, its figure (file and caption) and its
    claims."""
    entries = {name: {"name": name, "file": Path(path).name} for name, path in figures.items()}
    placed = paper_sections(
        rows, entries, paper.get("statements") or {}, paper.get("sections") or {}
    )
    return [
        {
            "heading": section["heading"],
            "blocks": [
                {
                    "heading": block["heading"],
                    "statement": block["statement"],
                    "figure": None
                    if block["figure"] is None
                    else {
                        "file": block["figure"]["file"],
                        "caption": _caption(block["figure"]["name"], attrs),
                    },
                    "claims": [_row(r) for r in block["claims"]],
                }
                for block in section["blocks"]
            ],
        }
        for section in placed
    ]


def _counts(table: pd.DataFrame) -> dict:
    """The abstract's counts, each a partition of one set (:func:`~.claims.tally`, the
    report's and the README's): every claim held out (by status) or used for fit; the
    declared deviations by cause; the held-out claims by robustness class."""
    t = tally(table)

    def parts(name: str) -> list[dict]:
        found = t[name].parts if name in t else ()
        return [
            {"class": "not classified" if k == "other" else class_words(k), "n": n}
            for k, n in found
        ]

    return {
        "claims": t["claims"].total,
        "held": t["claims"]["held"],
        "reproduced": t["held"]["pass"],
        "deviating": t["held"]["known_deviation"],
        "failing": t["held"]["fail"],
        "fit": t["claims"]["fit"],
        "evidence": parts("known_deviation"),
        "robustness": parts("robustness"),
    }


def _listed(parts: Sequence[Mapping]) -> str:
    """``3 irreducible, 1 ill conditioned``: a tally's parts (:func:`_counts`)."""
    return ", ".join(f"{p['n']} {p['class']}" for p in parts)


def abstract(counts: Mapping) -> str:
    """The article's abstract (and ReScience C's ``abstract``): the paper's model in one
    sentence, then the claims table's counts (:func:`_counts`)."""
    evidence = f" ({_listed(counts['evidence'])})" if counts["evidence"] else ""
    robustness = (
        " Across the readings of the paper's unstated assumptions consistent with it, the "
        f"held-out claims are {_listed(counts['robustness'])}."
        if counts["robustness"]
        else ""
    )
    return (
        f"{ORIGINAL['authors']} modelled a forehand tennis stroke as a double pendulum (arm "
        "and forearm, hand and racket) driven by joint torques from a moving elbow, with a "
        "one-dimensional spring contact for the ball, and mapped the rebound speed over the "
        "initial angles, the racket's mass and the arm's length, a delay of the wrist torque "
        "and an extra elbow force. We reimplemented the model and checked each of the "
        f"paper's {counts['claims']} quantitative and qualitative claims against a tolerance "
        f"declared before the results were computed. {counts['reproduced']} claims "
        f"reproduce, {counts['deviating']} deviate{evidence}, {counts['failing']} fail, and "
        f"{counts['fit']} were used to fit what the paper leaves unstated.{robustness}"
    )


def _first_unknown(deciding: str) -> str:
    """The unknown a claims table's ``deciding`` names (``contact_lead_rule (a 0/8, b
    8/8)``)."""
    return deciding.split(" (")[0].strip()


def discussion(table: pd.DataFrame, rows: Sequence[Mapping]) -> dict:
    """What the Discussion and the Conclusion say, from the claims table: what
    reproduces (held-out claims that pass, and how many of them under every reading),
    what does not and why (the deviations and failures grouped by their evidence class,
    with its meaning, :data:`~.robustness.EVIDENCE_MEANING`), and what the unstated
    readings decide (each reading-dependent claim with the unknown that decides it)."""
    records = table.to_dict("records")
    shown = {r["id"]: _row(r) for r in rows}
    held = [c for c in records if not c.get("fit_set")]  # as tally() counts them
    passing = [c for c in held if c["status"] == "pass"]
    robust = [c for c in passing if c.get("robustness") == "robust"]
    groups = []
    for key, meaning in {**EVIDENCE_MEANING, "": "not classified"}.items():
        members = [
            c
            for c in records
            if c["status"] in ("known_deviation", "fail") and (c.get("evidence") or "") == key
        ]
        if members:
            groups.append(
                {
                    "class": class_words(key) if key else "not classified",
                    "meaning": meaning,
                    "claims": [
                        {**shown[c["id"]], "reason": str(c.get("reason") or "")} for c in members
                    ],
                }
            )
    dependent = [c for c in held if c.get("robustness") == "reading_dependent"]
    deciding = Counter(_first_unknown(str(c.get("deciding") or "")) for c in dependent)
    bounds = [float(c.get("class_bound", "nan")) for c in robust]
    bounds = [b for b in bounds if np.isfinite(b)]
    sure = {
        "readings": str(int(float(robust[0]["readings"]))) if bounds else "",
        "bound": f"{100 * max(bounds):.2g} %" if bounds else "",
        "confidence": f"{100 * CONFIDENCE:.0f} %",
    }
    return {
        "held": len(held),
        "passing": len(passing),
        "robust": len(robust),
        "sure": sure,
        "not_reproduced": sum(c.get("robustness") == "not_reproduced" for c in held),
        "groups": groups,
        "dependent": [
            {
                "id": c["id"],
                "verdict": shown[c["id"]]["verdict"],
                "share": across_short(c).removesuffix(" *"),
                "deciding": str(c.get("deciding") or "not named"),
            }
            for c in dependent
        ],
        "deciders": [{"name": k or "not named", "n": n} for k, n in deciding.most_common()],
        "fit_sets": sorted({str(c["fit_set"]) for c in records if c.get("fit_set")}),
    }


def _attributes(results: Sequence[str]) -> dict[str, Mapping]:
    """Each result file's global attributes (read whole: a damaged file is one line)."""
    return {str(path): dict(load_result(path).attrs) for path in results}


def provenance(attrs: Mapping[str, Mapping]) -> list[dict]:
    """Each provenance fact of :data:`PROVENANCE` as every result file records it: one
    value (``mixed`` False), or a mix, each value with its files' count and names (the
    most common value first).  A mix is stated, never resolved: the workflow reruns only
    the jobs a change touches, so a run's files may come from several commits; which one
    a reader needs is the reader's to choose."""
    facts = []
    for key, label in PROVENANCE.items():
        by_value: dict[str, list[str]] = {}
        for path, record in attrs.items():
            value = str(record.get(key, "not recorded"))
            by_value.setdefault(value, []).append(Path(path).name)
        values = sorted(by_value.items(), key=lambda item: (-len(item[1]), item[0]))
        facts.append(
            {
                "key": key,
                "label": label,
                "mixed": len(values) > 1,
                "values": [
                    {"value": v, "files": len(names), "names": sorted(names)} for v, names in values
                ],
                "text": _fact_text(label, values, len(attrs)),
            }
        )
    return facts


def _fact_text(label: str, values: Sequence[tuple[str, list[str]]], files: int) -> str:
    """``commit: abc (all 31 result files)``, or a mix with each value's files."""
    if not values:
        return f"{label}: no result file"
    if len(values) == 1:
        return f"{label}: {values[0][0]} (all {files} result files)"

    def listed(value: str, names: list[str], first: bool) -> str:
        count = f"{len(names)} file{'s' if len(names) > 1 else ''}"
        if first:
            return f"{value} ({count})"
        more = f" and {len(names) - SHOWN_NAMES} more" if len(names) > SHOWN_NAMES else ""
        return f"{value} ({count}: {', '.join(sorted(names)[:SHOWN_NAMES])}{more})"

    parts = [listed(v, n, i == 0) for i, (v, n) in enumerate(values)]
    return f"{label}: a mix of {len(values)}: " + "; ".join(parts)


def _shown(value: float, digits: int) -> str:
    return "-" if not np.isfinite(value) else f"{value:.{digits}g}"


def rule_section(work_precision: str) -> dict:
    """The work-precision study's rule table as the article shows it: the report's
    (:func:`~.analyses.rule_caption`, :func:`~tennis_stroke.studies.tables.rule_table`),
    its caption and one row per scene, every value a string."""
    ds = load_result(work_precision)
    rows = [
        {
            "scene": r.scene,
            "rule": "none" if r.method == "none" else f"{r.method} @ {r.setting:g}",
            "evals": _shown(r.rhs_evals, 3),
            "v_out": _shown(r.v_out_error_worst, 2),
            "events": _shown(r.event_time_error_worst, 2),
            "default": f"{'meets' if r.default_meets else 'misses'} it, "
            f"{_shown(r.default_rhs_evals, 3)}",
        }
        for r in rule_table(ds).itertuples()
    ]
    return {"caption": rule_caption(ds), "rows": rows}


def article_data(
    claims_csv: str,
    claims_yaml: str,
    figures: Mapping[str, str],
    results: Sequence[str],
    job_seconds: float | None = None,
    work_precision: str | None = None,
    citation: Mapping | None = None,
) -> dict:
    """Everything the article states, from the result files (the template's data);
    ``work_precision``: the study's file, whose rule table it shows (None: no table);
    ``citation``: ``CITATION.cff`` as data, whose authors it names
    (:func:`~.rescience.byline`)."""
    try:
        table = checked_table(claims_csv, load_claims(claims_yaml))
    except ClaimsTableError as exc:
        raise ReportInputError(str(exc)) from None
    paper = load_yaml(claims_yaml) or {}
    rows = [claim_row(c) for c in table.to_dict("records")]
    attrs = _attributes(results)
    facts = provenance(attrs)
    try:
        shown_equations = equations()
    except EquationError as exc:
        raise ReportInputError(f"the article's equations: {exc}") from None
    counts = _counts(table)
    mark = verdict(table)
    return {
        "title": title(mark["mark"]),
        "verdict": mark,
        "byline": byline(citation or {}),
        "abstract": abstract(counts),
        "original": ORIGINAL,
        "counts": counts,
        "equations": shown_equations,
        "sections": _sections(rows, figures, attrs, paper),
        "discussion": discussion(table, rows),
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
        "provenance": facts,
        "provenance_mixed": [f["label"] for f in facts if f["mixed"]],
        "job_seconds": "-" if job_seconds is None else f"{job_seconds:.0f}",
        "rule": None if work_precision is None else rule_section(work_precision),
    }


def job_seconds(benchmarks: Path) -> float | None:
    """The wall time of the paper's run's jobs summed (the report's table of timings,
    :func:`~tennis_stroke.replication.formats._timings`, less this job), or None without
    any."""
    timings = _timings(benchmarks) if benchmarks.is_dir() else pd.DataFrame()
    if timings.empty:
        return None
    return float(timings.loc[timings["job"] != "article", "wall time (s)"].sum())


def runtime_software(pyproject: str | Path | None, lock: str | Path | None) -> list[str]:
    """What the replication runs on (ReScience C's ``software``): the package's
    dependencies and its workflow extra (:data:`RUNTIME_EXTRAS`, from ``pyproject.toml``)
    as ``name==version`` of the lock, never the lint and test tools; a name the lock does
    not pin keeps its declared range."""
    if pyproject is None or not Path(pyproject).is_file():
        return []
    project = tomllib.loads(Path(pyproject).read_text(encoding="utf-8"))["project"]
    extras = project.get("optional-dependencies", {})
    declared = [*project.get("dependencies", []), *(r for e in RUNTIME_EXTRAS for r in extras[e])]
    pins = locked(lock) if lock is not None and Path(lock).is_file() else {}
    out = []
    for requirement in declared:
        name = re.match(r"[A-Za-z0-9_.\-]+", requirement.strip()).group(0)
        pin = pins.get(canonical(name))
        out.append(f"{name}=={pin[0]}" if pin else requirement.strip())
    return out


def _code_url(repository: str, facts: Sequence[Mapping]) -> str:
    """The code's URL: the repository at the one commit every result file records (a
    commit with uncommitted changes, or a mix, is no commit of it: the repository
    alone), or nothing without a repository."""
    if not repository:
        return ""
    commit = next(f for f in facts if f["key"] == "git_commit")
    value = commit["values"][0]["value"] if not commit["mixed"] and commit["values"] else ""
    if re.fullmatch(r"[0-9a-f]{40}", value):
        return f"{repository.rstrip('/')}/tree/{value}"
    return repository


def _require(*paths) -> None:
    """One line naming the first input of an article that does not exist."""
    missing = [p for p in paths if not Path(p).is_file()]
    if missing:
        raise ReportInputError(f"the article needs {missing[0]}, which does not exist")


def write_atomically(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` whole or not at all, its folder made where missing
    (:func:`~tennis_stroke.io.netcdf.write_bytes_whole`: a failure keeps what ``path``
    held)."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    write_bytes_whole(path, data)


def _typeset(template: Path, data: Mapping, images: Sequence[str], output_pdf: str) -> None:
    """Typeset ``template`` with ``data`` (as ``data.json``) and ``images`` beside it
    into ``output_pdf`` (:func:`write_atomically`).  Each image must decode (one line
    naming a damaged one, :func:`~.report.check_image`); a Typst error is one line."""
    import typst  # the workflow's extra: only the article jobs load it

    for path in images:
        check_image(path)
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        shutil.copy(template, work / template.name)
        for path in images:
            shutil.copy(path, work / Path(path).name)
        (work / "data.json").write_text(json.dumps(data))
        try:
            pdf = typst.compile(str(work / template.name), root=str(work))
        except typst.TypstError as exc:
            problem = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise ReportInputError(f"{template.name} does not typeset: {problem}") from None
    write_atomically(output_pdf, pdf)


def build_article(
    claims_csv: str,
    claims_yaml: str,
    figures: Sequence[str],
    results: Sequence[str],
    output_pdf: str,
    output_metadata: str,
    job_seconds: float | None = None,
    lock: str | Path | None = None,
    pyproject: str | Path | None = None,
    work_precision: str | None = None,
    citation: str | Path | None = None,
) -> None:
    """Write the article (``output_pdf``) and its ``metadata.yaml`` from the results
    (``lock``, ``pyproject``: ``requirements.lock`` and ``pyproject.toml``, whose
    runtime dependencies it lists; ``work_precision``: the study's file, for the rule
    table of the integrator's settings; ``citation``: ``CITATION.cff``, whose authors,
    keywords and ``repository-code`` both name, None: none).  A provenance fact the
    result files do not share is stated as a mix in the article and said on stderr."""
    _require(
        claims_csv, claims_yaml, *figures, *results, *([work_precision] if work_precision else [])
    )
    cff = read_citation(citation)
    shown = {
        Path(p).stem: p
        for p in figures
        if Path(p).stem in FIGURES and FIGURES[Path(p).stem].of_paper
    }
    data = article_data(claims_csv, claims_yaml, shown, results, job_seconds, work_precision, cff)
    for label in data["provenance_mixed"]:
        print(f"warning: the result files record more than one {label}", file=sys.stderr)
    _typeset(TEMPLATE, data, list(shown.values()), output_pdf)
    code_url = _code_url(str(cff.get("repository-code", "")), data["provenance"])
    meta = metadata(
        data["title"], data["abstract"], cff, code_url, runtime_software(pyproject, lock)
    )
    write_atomically(output_metadata, metadata_text(meta).encode("utf-8"))
