"""The replication report: one self-contained HTML page (figures embedded as PNG data).

A scoreboard first (how many claims reproduce, deviate, fail or chose the readings, and how
robust they are across the readings consistent with the paper), then what does not
reproduce grouped by cause, then one section per section of the paper: its statements,
our figures and, right under each figure, its claims with paper value, ours, tolerance,
status (a word and a colour) and robustness.  Then the fits and the robustness analysis,
the speed-against-accuracy studies, the assumption ledger (``docs/assumptions.md``
rendered with markdown-it-py), the configuration as YAML, provenance and per-job timings.

The page is rendered by jinja2 with autoescape (``templates/report.html.j2``): every text
from a file is escaped.  The only HTML inserted as it is comes from this module and
:mod:`~tennis_stroke.replication.analyses`, marked safe on purpose
(:func:`~tennis_stroke.replication.formats._safe`): tables written by pandas (which
escapes their cells) and the ledger rendered by markdown-it-py with raw HTML disabled.
"""

from __future__ import annotations

import base64
import platform
import re
from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from pathlib import Path

import jinja2
import pandas as pd
import xarray as xr
import yaml
from markdown_it import MarkdownIt
from markupsafe import Markup

from .._version import __version__
from ..experiments.specs import PAPER_RESULTS
from ..inference.claims import load_claims
from ..inference.optimum_claims import note as optimum_note
from ..inference.optimum_claims import short_note as optimum_short
from ..inference.paper_config import PaperConfigError, departure_lines, read_record
from ..io.config_files import load_yaml
from ..io.environment import environment_table
from ..io.failures import failure_counts
from ..io.netcdf import git_commit, load_result
from ..model.listing import origin
from ..model.params import PARAMETERS, READINGS
from .analyses import (
    fit_tables,
    ladder_summary,
    model_ladder_section,
    robustness_section,
    studies_section,
    validation_section,
)
from .claims import (
    STATUS_WORDS,
    ClaimsTableError,
    cause_of,
    checked_table,
    read_table,
    tally,
)
from .formats import ReportInputError, _number, _safe, _table, _timings
from .marks import mark_values
from .registry import FIGURES, LIVE, UNIT_SHORT, claim_figure
from .robustness import EVIDENCE_MEANING, across_text, class_words

#: The page template, rendered with autoescape.
ENVIRONMENT = jinja2.Environment(
    loader=jinja2.PackageLoader("tennis_stroke.replication", "templates"),
    autoescape=True,
    undefined=jinja2.StrictUndefined,
    trim_blocks=False,
)


def markdown_html(text: str) -> Markup:
    """Markdown (CommonMark with tables) as HTML; raw HTML in the text is escaped, HTML
    comments (the markers of the generated blocks, ``tools/readme_results.py``) are dropped."""
    text = re.sub(r"<!--.*?-->", "", text, flags=re.DOTALL)
    md = MarkdownIt("commonmark", {"html": False}).enable("table")
    return _safe(md.render(text))


def claim_row(claim: Mapping) -> dict:
    """What the page shows of one claim (a row of ``results/claims.csv``)."""
    symbol, word, _ = STATUS_WORDS.get(claim["status"], ("?", claim["status"], ""))
    qualitative = str(claim["unit"]) == "1" and float(claim["tolerance"]) == 0
    if qualitative:
        paper = "yes" if float(claim["paper_value"]) else "no"
        ours = "yes" if float(claim["reproduced_value"]) == 1 else "no"
        tolerance = "exact"
    else:
        paper, ours = _number(claim["paper_value"], 6), _number(claim["reproduced_value"])
        tolerance = (
            f"\u00b1{_number(claim['tolerance'])} {UNIT_SHORT.get(claim['unit'], claim['unit'])}"
        )
    across = across_text(claim) if claim.get("robustness", "") else "-"
    return {
        "id": claim["id"],
        "source": claim["source"],
        "quantity": claim["quantity"],
        "unit": claim["unit"],
        "unit_short": UNIT_SHORT.get(claim["unit"], claim["unit"]),
        "paper": paper,
        "ours": ours,
        "tolerance": tolerance,
        "status": claim["status"],
        "symbol": symbol,
        "word": word,
        "fit_set": claim.get("fit_set", ""),
        "across": across,
        "deciding": f"deciding: {claim['deciding']}" if claim.get("deciding") else "",
        "optimum": optimum_note(claim),
        "optimum_short": optimum_short(claim),
        "cause": cause_of(claim),
        "reason": claim.get("reason", ""),
    }


def _paper_place(
    source: str, claim_id: str, sections: Mapping[str, Mapping]
) -> tuple[str | None, str]:
    """Where a claim goes: the section its ``source`` names (``"Sec. V, Fig. 9"``; a
    table's section for ``"Table I"``; None if the page has no section for it) and the
    block: its figure (:func:`~.registry.claim_figure`), else a table's name, else ``""``
    (the section's other claims)."""
    section = re.search(r"Sec\.\s*([IVX]+)\b", source)
    figure = claim_figure({"source": source, "id": claim_id})
    table = next(
        ((sid, t) for sid, s in sections.items() for t in s.get("tables", ()) if t in source),
        None,
    )
    sid = section.group(1) if section else (table[0] if table else None)
    if figure:
        return sid, figure
    return sid, table[1] if table else ""


def _anchor(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()


def _block(anchor: str, heading: str, claims: list[dict], **shown) -> dict:
    """One block of a section: its anchor and heading, its claims, and what it shows
    beside them (``figure``, ``statement``, ``key``; none by default)."""
    return {
        "anchor": anchor,
        "heading": heading,
        "figure": None,
        "statement": "",
        **shown,
        "claims": claims,
    }


def _figure_blocks(
    sid: str,
    figures: Mapping[str, dict],
    statements: Mapping[str, str],
    placed: Mapping[tuple[str | None, str], list[dict]],
) -> list[dict]:
    """The blocks of the figures of section ``sid`` (the registry's ``section``), in the
    order of their names: the paper's statement, the figure and its claims."""
    blocks = []
    for name in sorted(n for n in figures if FIGURES[n].section == sid):
        key = FIGURES[name].key
        blocks.append(
            _block(
                _anchor(name),
                f"Fig. {int(key[3:])}",
                placed.get((sid, key), []),
                key=key,
                figure=figures[name],
                statement=statements.get(key, ""),
            )
        )
    return blocks


def _table_blocks(
    sid: str,
    tables: Sequence[str],
    statements: Mapping[str, str],
    placed: Mapping[tuple[str | None, str], list[dict]],
) -> list[dict]:
    """The blocks of the paper's ``tables`` in section ``sid``: statement and claims."""
    return [
        _block(
            _anchor(f"{sid} {table}"),
            table,
            placed.get((sid, table), []),
            key=table,
            statement=statements.get(_anchor(table).replace("-", ""), ""),
        )
        for table in tables
    ]


def paper_sections(
    rows: list[dict],
    figures: Mapping[str, dict],
    statements: Mapping[str, str],
    sections: Mapping[str, Mapping],
) -> list[dict]:
    """One entry per section of the paper: a block per figure (statement, figure, its
    claims), per table, and the section's other claims; claims the sections do not place
    end in a last section, so no claim is ever left out."""
    placed: dict[tuple[str | None, str], list[dict]] = {}
    for row in rows:
        placed.setdefault(_paper_place(row["source"], row["id"], sections), []).append(row)
    out = []
    for sid, meta in sections.items():
        blocks = [
            *_figure_blocks(sid, figures, statements, placed),
            *_table_blocks(sid, meta.get("tables", ()), statements, placed),
        ]
        shown = {(sid, b["key"]) for b in blocks}
        rest = [r for (s, b), rs in placed.items() if s == sid and (s, b) not in shown for r in rs]
        if rest:
            blocks.append(_block(_anchor(f"sec {sid} other"), f"Other claims of Sec. {sid}", rest))
        heading = f"Sec. {sid}. {meta['title']}"
        out.append({"anchor": _anchor(f"sec {sid}"), "heading": heading, "blocks": blocks})
    leftover = [r for (s, _), rs in placed.items() if s not in sections for r in rs]
    if leftover:
        block = _block("other-claims-list", "Other claims", leftover)
        heading = "Claims outside the sections above"
        out.append({"anchor": "other-claims", "heading": heading, "blocks": [block]})
    return out


#: Each cause of a claim outside its tolerance (:func:`~.claims.cause_of`): its title
#: on the page and its meaning.
CAUSES = {
    **{k: (class_words(k).capitalize(), m) for k, m in EVIDENCE_MEANING.items()},
    "fail": (
        "Not yet explained",
        "does not reproduce, and config/claims.yaml expected it to: a regression or a "
        "finding not yet explained",
    ),
    "other": ("Not classified", "a declared deviation without a computed evidence class"),
}


def _deviation_groups(rows: list[dict]) -> list[dict]:
    """The claims outside their tolerance (held out or used for fit), grouped by their
    cause: each cause's meaning is said once, each claim's own reason beside it."""
    found = {r["cause"] for r in rows if r["cause"]}
    groups = []
    for key in [*(k for k in CAUSES if k in found), *sorted(found - set(CAUSES))]:
        title, meaning = _cause(key)
        members = [r for r in rows if r["cause"] == key]
        groups.append({"key": key, "title": title, "meaning": meaning, "claims": members})
    return groups


def _cause(key: str) -> tuple[str, str]:
    """A cause's title and meaning (:data:`CAUSES`; an evidence class it does not know
    is still shown, by its name)."""
    return CAUSES.get(key, (class_words(key).capitalize(), "an evidence class"))


def _failures(results: Sequence[str]) -> pd.DataFrame:
    """Strokes, failed strokes and the failing statuses of every result file; "-" where a
    file records no count of a status (Figs. 5-6 count failed strokes per point only)."""
    rows = []
    for path in results:
        counts = failure_counts(load_result(path))
        if counts:
            rows.append({"file": str(path), **counts})
    # integers stay integers; a count the file does not record is "-", never <NA>
    return pd.DataFrame(rows).convert_dtypes().astype(object).fillna("-")


def check_image(path: str) -> None:
    """A figure must decode as an image (a truncated file would embed as a broken one)."""
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as image:
            image.load()
    except (OSError, UnidentifiedImageError, SyntaxError) as exc:
        problem = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ReportInputError(
            f"figure {path} does not decode as an image ({problem}): remove it and make it "
            f"with: snakemake -j2 {path}"
        ) from None


def _figure_entry(path: str) -> dict:
    check_image(path)
    name = Path(path).stem
    title = FIGURES[name].title if name in FIGURES else name
    return {
        "name": name,
        "title": title if "{" not in title else title.split(":")[0],
        "data": base64.b64encode(Path(path).read_bytes()).decode(),
    }


#: The strokes animated on the page: the block (a figure's key or a table) and the file.
STROKE_VIEWS = {"fig04": "fig4", "fig10": "delay", "Table I": "elbow"}


def _interactive(
    figures: Mapping[str, dict],
    results: Sequence[str],
    inference: Mapping[str, str],
    claims: pd.DataFrame,
    claims_yaml: str | None,
) -> tuple[Markup, dict[str, Markup]]:
    """The page's interactive views (:mod:`tennis_stroke.replication.views`): BokehJS and
    the views' script for the page's head, and each view's div by name (a figure's name,
    ``strokes-<block>``, ``multiverse``); nothing for a view whose file is not given."""
    # Bokeh: only the report job draws views
    from .views.maps import figure_view
    from .views.multiverse import multiverse_view
    from .views.page import page_views
    from .views.strokes import stroke_view

    by_key = {k: p for k, rel in PAPER_RESULTS.items() for p in results if p.endswith(rel)}
    declared = {c["id"]: c for c in load_claims(claims_yaml)} if claims_yaml else {}
    ours = dict(zip(claims["id"], claims["reproduced_value"], strict=True))
    made = {}
    for name in figures:
        figure = FIGURES[name]
        if not all(k in by_key for k in figure.files):
            continue
        data = [load_result(by_key[k]) for k in figure.files]
        marks = mark_values(figure, declared, ours) if declared else []
        title = figure.filled_title(data[0].attrs)
        view = figure_view(figure, data, title, marks)
        if view is not None:
            made[name] = view
    for block, key in STROKE_VIEWS.items():
        if key in by_key:
            title = "Table I" if block == "Table I" else f"Fig. {int(block[3:])}"
            made[f"strokes-{block}"] = stroke_view(
                load_result(by_key[key]), f"strokes-{_anchor(block)}", title
            )
    if "robustness" in inference:
        made["multiverse"] = multiverse_view(load_result(inference["robustness"]), claims)
    if not made:
        return Markup(""), {}
    head, divs = page_views(made)
    return _safe(head), {k: _safe(v) for k, v in divs.items()}


def _checked_claims(claims_csv: str, claims_yaml: str | None) -> pd.DataFrame:
    """The claims table, checked as `tennis-stroke claims` checks it with the declared
    claims (:func:`~tennis_stroke.replication.claims.checked_table`: a status edited by
    hand is refused), else only read (:func:`~tennis_stroke.replication.claims.read_table`)."""
    declared = load_claims(claims_yaml) if claims_yaml else None
    try:
        table = checked_table(claims_csv, declared) if declared else read_table(claims_csv)
    except ClaimsTableError as exc:
        raise ReportInputError(str(exc)) from None
    table["reproduced_value"] = table["reproduced_value"].astype(float)
    return table


def _checked_inputs(
    claims_csv: str, statements_yaml: str | None, assumptions_md: str | None
) -> tuple[pd.DataFrame, list[str]]:
    """The checked claims table (:func:`_checked_claims`) and the lines saying how its
    configuration departs from the paper's (its record beside it); a record that does not
    read or an empty assumption ledger is a :class:`ReportInputError`."""
    claims = _checked_claims(claims_csv, statements_yaml)
    try:
        record = read_record(claims_csv)
    except PaperConfigError as exc:
        raise ReportInputError(str(exc)) from None
    if assumptions_md and not Path(assumptions_md).read_text(encoding="utf-8").strip():
        raise ReportInputError(f"the assumption ledger {assumptions_md} is empty")
    return claims, departure_lines(record)


def _score(claims: pd.DataFrame) -> dict:
    """The scoreboard's counts (:func:`~.claims.tally`), each line a partition: the
    held-out claims that pass, deviate or fail, each of the last two by cause; the claims
    used for fit within and outside their tolerance, the latter by cause; every claim
    outside its tolerance, by status and by cause (the section below the board)."""
    counts = tally(claims)

    def causes(name: str) -> list[dict]:
        return [{"key": k, "n": n, "title": _cause(k)[0]} for k, n in counts[name].parts]

    return {
        "claims": counts["claims"].total,
        "held": counts["held"].total,
        "pass": counts["held"]["pass"],
        "deviate": counts["held"]["known_deviation"],
        "fail": counts["held"]["fail"],
        "fit": counts["fit"].total,
        "fit_ok": counts["fit"]["within"],
        "fit_outside": counts["fit"]["outside"],
        "outside": counts["outside_tolerance"].total,
        "causes": {k: causes(k) for k in ("known_deviation", "fail", "outside")},
    }


def _figures_of(entries: Mapping[str, dict], section: str) -> list[dict]:
    """The figures (:func:`_figure_entry`, by name) the registry puts in ``section``."""
    return [e for n, e in entries.items() if n in FIGURES and FIGURES[n].section == section]


def _attach_views(sections: list[dict], views: Mapping[str, Markup]) -> None:
    """Give each block of the paper's ``sections`` its figure's interactive view (with
    the live explorer's name for it, if it has one) and its strokes' animation."""
    for block in (b for s in sections for b in s["blocks"]):
        name = block["figure"]["name"] if block.get("figure") else None
        block["view"] = views.get(name) if name else None
        block["live"] = LIVE.get(name) if block["view"] else None
        block["strokes"] = views.get(f"strokes-{block.get('key')}")


def _toc(sections: Sequence[dict]) -> list[dict]:
    """The page's table of contents: the deviations, the paper's ``sections``, ours."""
    return [
        {"anchor": "deviations", "label": "What does not reproduce, and why"},
        *({"anchor": s["anchor"], "label": s["heading"]} for s in sections),
        {"anchor": "inference", "label": "The paper's unstated readings: fits and robustness"},
        {"anchor": "model-ladder", "label": "Model no more than a scene needs: the ladder"},
        {"anchor": "studies", "label": "Speed against accuracy"},
        {"anchor": "ledger", "label": "Assumption ledger"},
        {"anchor": "run", "label": "Configuration, provenance and timings"},
    ]


def _run(config: Mapping, results: Sequence[str], benchmarks_dir: str) -> dict:
    """The run's section: the configuration as YAML, provenance (versions, commit, the
    solver's settings from the first result file, the environment), the installed
    distributions, failed strokes per file and per-job timings."""
    with xr.open_dataset(results[0]) as ds:
        solver = {k: v for k, v in ds.attrs.items() if k.startswith("solver_")}
    environment = environment_table()
    meta = {
        "tennis_stroke version": __version__,
        "git commit": git_commit(),
        "python": platform.python_version(),
        "built": datetime.now(UTC).isoformat(timespec="seconds"),
        **solver,
        "lock (requirements.lock, sha256)": environment["lock"],
        "environment": "the lock"
        if environment["is_lock"]
        else "not the lock: " + "; ".join(environment["differences"]),
        "results written under": _file_environments(results),
        "CPU": environment["cpu"],
        "numba compile target": environment["compile_target"],
    }
    return {
        "config_yaml": yaml.safe_dump(_builtin(config), sort_keys=False),
        "meta": meta,
        "distributions": environment["distributions"],
        "failure_table": _table(_failures(results), index=False, na_rep="-"),
        "timing_table": _table(_timings(Path(benchmarks_dir)), index=False),
        "max_failure_share": f"{100 * float(config['max_failure_share']):g} %",
    }


def build_report(
    figures: Sequence[str],
    claims_csv: str,
    inference: Mapping[str, str],
    results: Sequence[str],
    config: Mapping,
    benchmarks_dir: str,
    output: str,
    assumptions_md: str | None = None,
    studies: Mapping[str, str] | None = None,
    statements_yaml: str | None = None,
) -> None:
    """Write the report page to ``output`` (``assumptions_md``: the ledger's text;
    ``studies``: the studies' result files by key,
    :data:`~tennis_stroke.experiments.specs.STUDY_RESULTS`; ``statements_yaml``:
    ``config/claims.yaml``, whose ``statements`` quote the paper on each figure and whose
    ``sections`` name the paper's sections).  Each figure goes where the registry's
    ``section`` puts it.  A claims table whose configuration departs from the paper's
    (its record beside it, :mod:`tennis_stroke.inference.paper_config`) is said so at the
    top."""
    claims, departures = _checked_inputs(claims_csv, statements_yaml, assumptions_md)
    paper = load_yaml(statements_yaml) if statements_yaml else {}
    rows = [claim_row(c) for c in claims.to_dict("records")]
    entries = {e["name"]: e for e in map(_figure_entry, figures)}
    paper_figures = {n: e for n, e in entries.items() if n in FIGURES and FIGURES[n].of_paper}
    page_sections = paper_sections(
        rows, paper_figures, paper.get("statements") or {}, paper.get("sections") or {}
    )
    views_head, views = _interactive(paper_figures, results, inference, claims, statements_yaml)
    _attach_views(page_sections, views)
    ladder_error, study_tables = studies_section(studies or {})
    html = ENVIRONMENT.get_template("report.html.j2").render(
        departures=departures,
        score=_score(claims),
        deviation_groups=_deviation_groups(rows),
        toc=_toc(page_sections),
        sections=page_sections,
        inference={"figures": _figures_of(entries, "inference")},
        model_ladder={**model_ladder_section(inference), "figures": _figures_of(entries, "ladder")},
        fits=fit_tables(inference),
        robustness=robustness_section(claims, inference),
        validation=validation_section(claims, inference),
        views_head=views_head,
        multiverse=views.get("multiverse"),
        study_figures=_figures_of(entries, "study"),
        study_tables=study_tables,
        ladder=ladder_summary(ladder_error, claims),
        readings=[
            {**vars(r), "source": origin(r.name, _fitted(inference))} for r in READINGS.values()
        ],
        ledger=markdown_html(Path(assumptions_md).read_text()) if assumptions_md else "",
        **_run(config, results, benchmarks_dir),
    )
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    Path(output).write_text(html)


def _fitted(inference: Mapping[str, str]) -> set[str]:
    """The model parameters and readings whose default the fits chose (their files'
    ``default_*`` attributes: the fit sets of ``config/readings.yaml``)."""
    names = {
        k.removeprefix("default_")
        for key in inference
        if key.endswith("_fits")
        for k in load_result(inference[key]).attrs
        if k.startswith("default_")
    }
    return {n for n in names if n in PARAMETERS or n in READINGS}


def _file_environments(results: Sequence[str]) -> str:
    """The environments the result files record (the lock's hash; whether it was the
    lock), each with its count of files."""
    seen: dict[str, int] = {}
    for path in results:
        with xr.open_dataset(path) as ds:
            lock = ds.attrs.get("environment_lock_sha256_16", "not recorded")
            state = ds.attrs.get("environment_is_lock", "")
        key = f"lock {lock}" + (f", environment is the lock: {state}" if state else "")
        seen[key] = seen.get(key, 0) + 1
    return "; ".join(f"{k} ({n} files)" for k, n in seen.items())


def _builtin(node):
    """Config as plain YAML-able data (Snakemake's config may hold its own mapping types)."""
    if isinstance(node, Mapping):
        return {str(k): _builtin(v) for k, v in node.items()}
    if isinstance(node, list | tuple):
        return [_builtin(v) for v in node]
    return node
