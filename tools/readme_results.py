"""The numbers the README and the docs quote from a finished run, generated from its
result files.

Usage: ``python tools/readme_results.py [--claims results/claims.csv] [--readme PAGE ...]
[--check]``.  A page holds generated blocks, each between a ``<!-- NAME:begin -->`` and a
``<!-- NAME:end -->`` line, NAME one of :data:`BLOCKS`: the README's results at a glance
(``results``); the held-out claims by status and robustness class and the model ladder's
findings (``held-out``, ``ladder``: docs/inference.md); the assumption ledger's fit and
robustness tables (``identification``, ``robustness``: docs/assumptions.md, made by
tools/assumptions_tables.py).  Each is written from the folder of ``--claims``: the
claims table and the result files beside it.  The pages are README.md, docs/inference.md
and docs/assumptions.md unless ``--readme`` names others.  ``--check`` writes nothing and
exits 1 when a page's blocks differ from what the results give (``make report`` runs it:
the numbers the pages quote cannot go stale).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import assumptions_tables
import pandas as pd
import xarray as xr

from tennis_stroke.inference.paper_config import (
    PaperConfigError,
    describe_departures,
    read_record,
)
from tennis_stroke.replication.claims import STATUS_WORDS, tally
from tennis_stroke.replication.ladder import findings, verdict

PAGES = ("README.md", "docs/inference.md", "docs/assumptions.md")
STATUSES = ("pass", "used_for_fit", "known_deviation", "fail")
CLASSES = ("robust", "reading_dependent", "not_reproduced", "used_for_fit")


class ReadmeError(ValueError):
    """A page has no generated block, or a broken one (one line)."""


def markers(name: str) -> tuple[str, str]:
    """The lines that open and close the generated block ``name``."""
    return f"<!-- {name}:begin -->", f"<!-- {name}:end -->"


def block(table: pd.DataFrame) -> str:
    """The README's results at a glance, from a claims table (``results/claims.csv``):
    the claims by their verdict under the default reading (rows, in the report's words:
    the held-out claims by status, then the claims used for fit within and outside their
    tolerance, so the rows add up to every claim) and by how they fare across the
    consistent readings (columns, the robustness classes), then the claims outside their
    tolerance."""
    counts = tally(table)
    held = table[table["fit_set"] == ""]
    classes = pd.crosstab(held["status"], held["robustness"])
    lines = [
        f"{counts['claims'].total} claims: the {counts['held'].total} held out by their "
        f"verdict under the default reading, then the {counts['fit'].total} used for fit; "
        "a column for how the held-out claims fare across every reading consistent with "
        "the paper.",
        "",
        "| default reading | claims | robust (pass under every reading) "
        "| reading-dependent (pass under some) | not reproduced under any reading |",
        "|---|---:|---:|---:|---:|",
    ]
    rows = {s: counts["held"][s] for s in ("pass", "known_deviation", "fail")}
    rows |= {"used_for_fit": counts["fit"]["within"], "outside": counts["fit"]["outside"]}
    for status in ROWS:
        if not rows[status]:
            continue
        cells: list = ["-"] * 3  # a claim used for fit has no robustness class
        if status in classes.index:
            row = classes.loc[status]
            cells = [int(row.get(c, 0)) for c in CLASSES[:3]]
        word = ROW_WORDS.get(status) or STATUS_WORDS[status][1]
        lines.append(f"| {word} | {rows[status]} | " + " | ".join(map(str, cells)) + " |")
    deviating = table[table["status"].isin(("known_deviation", "fail"))]
    if len(deviating):
        which = [_claims_that(counts["held"][s], s) for s in ("known_deviation", "fail")] + [
            f"{counts['fit']['outside']} used for fit outside their tolerance"
        ]
        which = [w for w in which if not w.startswith("0 ")]
        lines += [
            "",
            f"The {_and(which)} under the default reading (the report gives each one's cause):",
            "",
            "| claim | paper | ours | unit | evidence |",
            "|---|---:|---:|---|---|",
        ]
        for _, r in deviating.iterrows():
            lines.append(
                f"| `{r['id']}` | {float(r['paper_value']):.4g} | "
                f"{float(r['reproduced_value']):.4g} | {r['unit']} | {r['evidence'] or '-'} |"
            )
    return "\n".join(lines)


#: The rows of the README's table: the held-out claims by status, then the claims used
#: for fit within their tolerance (``used_for_fit``) and outside it (``outside``).
ROWS = ("pass", "used_for_fit", "known_deviation", "fail", "outside")
ROW_WORDS = {"outside": "used for fit, outside tolerance"}


def _and(items: list[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return " and ".join([", ".join(items[:-1]), items[-1]] if len(items) > 1 else items)


def _claims_that(n: int, status: str) -> str:
    """``9 claims that deviate``, ``1 claim that fails``: the report's verb for ``status``."""
    singular, plural = STATUS_WORDS[status][1:]
    return f"{n} claim that {singular}" if n == 1 else f"{n} claims that {plural}"


def held_out(table: pd.DataFrame, results: Path) -> str:
    """docs/inference.md's held-out claims: the counts by status and robustness class, and
    which claims each pair holds (the claims table; the number of kept readings and
    claim-level variants from ``results/robustness/claims.nc``)."""
    held = table[table["fit_set"] == ""]
    with xr.open_dataset(results / "robustness" / "claims.nc") as kept:
        readings, variants = kept.sizes["reading"], kept.sizes["variant"]
    statuses = held["status"].value_counts()
    classes = held["robustness"].value_counts()
    fit = tally(table)["fit"]
    off = f", {fit['outside']} of them outside their tolerance" if fit["outside"] else ""
    lines = [
        f"{len(table)} claims: {fit.total} chose the readings (`used_for_fit`{off}), "
        f"{len(held)} are held out: "
        + ", ".join(f"{int(statuses.get(s, 0))} `{s}`" for s in STATUSES if s != "used_for_fit")
        + f". Across the {readings} kept readings consistent with the paper, each under "
        f"{variants} claim-level variants, the held-out claims are "
        + ", ".join(f"{int(classes.get(c, 0))} `{c}`" for c in CLASSES if c != "used_for_fit")
        + ".",
        "",
        "| status | robustness | claims |",
        "|---|---|---|",
    ]
    for status in STATUSES:
        for robustness in CLASSES:
            ids = held["id"][(held["status"] == status) & (held["robustness"] == robustness)]
            if len(ids):
                names = ", ".join(f"`{i}`" for i in ids)
                lines.append(f"| {status} | {robustness} ({len(ids)}) | {names} |")
    return "\n".join(lines)


def ladder(results: Path) -> str:
    """docs/inference.md's findings of the model ladder, in the sentences of the report's
    section (``results/ladder/claims_by_rung.nc``, tennis_stroke.replication.ladder)."""
    with xr.open_dataset(results / "ladder" / "claims_by_rung.nc") as ds:
        ds = ds.load()
    return "\n".join(f"* {line}" for line in [*verdict(ds), *findings(ds)])


#: Every generated block by name: what it is made of (the claims table and the results
#: folder).
BLOCKS: dict[str, Callable[[pd.DataFrame, Path], str]] = {
    "results": lambda table, results: block(table),
    "held-out": held_out,
    "ladder": lambda table, results: ladder(results),
    "identification": lambda table, results: assumptions_tables.tables(results / "identification"),
    "robustness": lambda table, results: assumptions_tables.robustness_tables(results),
    "coverage": lambda table, results: assumptions_tables.coverage(results),
}


def replaced(page: str, name: str, content: str) -> str:
    """``page`` with ``content`` in its block ``name``."""
    begin, end = markers(name)
    if page.count(begin) != 1 or page.count(end) != 1 or page.index(begin) > page.index(end):
        raise ReadmeError(f"the block {name!r} needs one {begin} line and one {end} line after it")
    head, rest = page.split(begin)
    _, tail = rest.split(end)
    return f"{head}{begin}\n{content.strip()}\n{end}{tail}"


def regenerated(page: str, table: pd.DataFrame, results: Path) -> str:
    """``page`` with each of its generated blocks written anew."""
    names = [n for n in BLOCKS if any(m in page for m in markers(n))]
    if not names:
        raise ReadmeError(
            "no generated block: a page needs a <!-- NAME:begin --> line and a "
            f"<!-- NAME:end --> line after it, NAME one of {', '.join(BLOCKS)}"
        )
    for name in names:
        page = replaced(page, name, BLOCKS[name](table, results))
    return page


def not_the_papers(claims: str) -> str:
    """Why the claims table ``claims`` may not write the pages (empty: it may): their
    results are the paper's configuration's, never a scenario's or a departing
    configuration's (the record beside the table, tennis_stroke.inference.paper_config)."""
    record = read_record(claims)
    if record["scenario"]:
        return (
            f"{claims} is scenario {record['scenario']['name']!r}'s, an exploration: the "
            "README and the docs show the paper's configuration only"
        )
    if record["departures"]:
        return (
            f"{claims} was computed under a configuration that departs from the paper's "
            f"({describe_departures(record)}): the README and the docs show the paper's "
            "configuration only"
        )
    return ""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--claims", default="results/claims.csv")
    parser.add_argument("--readme", nargs="+", default=PAGES, help="the pages to write")
    parser.add_argument("--check", action="store_true", help="exit 1 if a page is stale")
    args = parser.parse_args(argv)
    try:
        refusal = not_the_papers(args.claims)
        if refusal:
            sys.stderr.write(f"readme_results: {refusal}\n")
            return 2
        table = pd.read_csv(args.claims, keep_default_na=False)
        pages, new = {}, {}
        for page in map(Path, args.readme):
            pages[page] = page.read_text()
            try:
                new[page] = regenerated(pages[page], table, Path(args.claims).parent)
            except ReadmeError as exc:
                raise ReadmeError(f"{page}: {exc}") from None
    except (OSError, ReadmeError, KeyError, PaperConfigError) as exc:
        sys.stderr.write(f"readme_results: {exc}\n")
        return 2
    stale = [p for p in pages if new[p] != pages[p]]
    if args.check:
        for page in stale:
            sys.stderr.write(
                f"readme_results: {page}'s results are stale against {args.claims}: "
                "run python tools/readme_results.py\n"
            )
        return 1 if stale else 0
    for page in stale:
        page.write_text(new[page])
    return 0


if __name__ == "__main__":
    sys.exit(main())
