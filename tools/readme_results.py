"""The README's "results at a glance", generated from the claims table of a finished run.

Usage: ``python tools/readme_results.py [--claims results/claims.csv] [--readme README.md]
[--check]``.  Writes the block between the README's ``<!-- results:begin -->`` and
``<!-- results:end -->`` lines from ``results/claims.csv``: the claims by status and
robustness class (a status in the report's words, so the README and the report's
scoreboard speak alike), and every claim that deviates, with the paper's value, ours and
the evidence class.  ``--check`` writes nothing and exits 1 when the README's block differs
from what the claims table gives (``make report`` runs it: the README's numbers cannot go
stale).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from tennis_stroke.inference.paper_config import (
    PaperConfigError,
    describe_departures,
    read_record,
)
from tennis_stroke.replication.report import STATUS_WORDS

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
STATUSES = ("pass", "used_for_fit", "known_deviation", "fail")
CLASSES = ("robust", "reading_dependent", "not_reproduced", "used_for_fit")


class ReadmeError(ValueError):
    """The README has no results block (one line)."""


def block(table: pd.DataFrame) -> str:
    """The Markdown between the markers, from a claims table (``results/claims.csv``):
    the claims by their verdict under the default reading (rows, in the report's words)
    and by how they fare across the consistent readings (columns, the robustness
    classes), then the claims that deviate or fail."""
    counts = pd.crosstab(table["status"], table["robustness"])
    lines = [
        f"{len(table)} claims: a row for each verdict under the default reading, a column "
        "for how those claims fare across every reading consistent with the paper.",
        "",
        "| default reading | claims | robust (pass under every reading) "
        "| reading-dependent (pass under some) | not reproduced under any reading |",
        "|---|---:|---:|---:|---:|",
    ]
    for status in STATUSES:
        if status not in counts.index:
            continue
        row = counts.loc[status]
        cells = [int(row.get(c, 0)) for c in ("robust", "reading_dependent", "not_reproduced")]
        total = int(row.sum())
        if status == "used_for_fit":  # chose the readings: no robustness class
            cells = ["-"] * 3
        word = STATUS_WORDS[status][1]
        lines.append(f"| {word} | {total} | " + " | ".join(map(str, cells)) + " |")
    deviating = table[table["status"].isin(("known_deviation", "fail"))]
    if len(deviating):
        which = " and ".join(
            _claims_that(int((deviating["status"] == status).sum()), status)
            for status in ("known_deviation", "fail")
            if (deviating["status"] == status).any()
        )
        lines += [
            "",
            f"The {which} under the default reading (the report gives each one's cause):",
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


def _claims_that(n: int, status: str) -> str:
    """``9 claims that deviate``, ``1 claim that fails``: the report's verb for ``status``."""
    verb = STATUS_WORDS[status][1]
    return f"{n} claim that {verb}" if n == 1 else f"{n} claims that {verb.removesuffix('s')}"


def replaced(readme: str, content: str) -> str:
    """``readme`` with ``content`` between the markers."""
    if (
        readme.count(BEGIN) != 1
        or readme.count(END) != 1
        or readme.index(BEGIN) > readme.index(END)
    ):
        raise ReadmeError(f"the README needs one {BEGIN} line and one {END} line after it")
    head, rest = readme.split(BEGIN)
    _, tail = rest.split(END)
    return f"{head}{BEGIN}\n{content}\n{END}{tail}"


def not_the_papers(claims: str) -> str:
    """Why the claims table ``claims`` may not write the README (empty: it may): the
    README's results are the paper's configuration's, never a scenario's or a departing
    configuration's (the record beside the table, tennis_stroke.inference.paper_config)."""
    record = read_record(claims)
    if record["scenario"]:
        return (
            f"{claims} is scenario {record['scenario']['name']!r}'s, an exploration: the "
            "README shows the paper's configuration only"
        )
    if record["departures"]:
        return (
            f"{claims} was computed under a configuration that departs from the paper's "
            f"({describe_departures(record)}): the README shows the paper's configuration only"
        )
    return ""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--claims", default="results/claims.csv")
    parser.add_argument("--readme", default="README.md")
    parser.add_argument("--check", action="store_true", help="exit 1 if the README is stale")
    args = parser.parse_args(argv)
    try:
        refusal = not_the_papers(args.claims)
        if refusal:
            sys.stderr.write(f"readme_results: {refusal}\n")
            return 2
        table = pd.read_csv(args.claims, keep_default_na=False)
        readme = Path(args.readme).read_text()
        new = replaced(readme, block(table))
    except (OSError, ReadmeError, KeyError, PaperConfigError) as exc:
        sys.stderr.write(f"readme_results: {exc}\n")
        return 2
    if args.check:
        if new != readme:
            sys.stderr.write(
                f"readme_results: {args.readme}'s results are stale against {args.claims}: "
                "run python tools/readme_results.py\n"
            )
            return 1
        return 0
    Path(args.readme).write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
