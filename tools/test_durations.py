"""Where a test run's time goes, by kind of test: the durations of a JUnit report summed
per kind (the ``kind`` property tests/conftest.py gives every test from its markers:
workflow, browser, compile, slurm, signals, process, unit).

Usage::

    .venv/bin/python -m pytest -n 2 --maxschedchunk 1 --junitxml=run.xml   # or make test
    .venv/bin/python tools/test_durations.py run.xml [--top 3] [--kinds other.xml]

Prints a Markdown table (docs/testing.md, "Where the time goes"): per kind the tests,
their summed durations (setup, call and teardown: a shared fixture is counted in the first
test that uses it), the share of all, and the slowest tests.  The sum is the time on one
core: with several xdist workers the run's wall time is shorter.  ``--kinds``: take each
test's kind from another report (for a report written before the kinds existed).
"""

from __future__ import annotations

import argparse
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict
from pathlib import Path

#: The kinds in the order of the table (tests/conftest.py, SLOW_KINDS, then the others).
KINDS = ("workflow", "compile", "browser", "slurm", "signals", "process", "unit")


def durations(report: Path) -> list[tuple[str, str, float]]:
    """``(kind, test id, seconds)`` of every test case of a JUnit report."""
    try:
        root = ET.parse(report).getroot()
    except (OSError, ET.ParseError) as error:
        raise SystemExit(f"test_durations: cannot read {report}: {error}") from None
    out = []
    for case in root.iter("testcase"):
        props = {p.get("name"): p.get("value") for p in case.iter("property")}
        test = f"{case.get('classname', '')}::{case.get('name', '')}"
        out.append((props.get("kind", "unit"), test, float(case.get("time") or 0.0)))
    return out


def with_kinds(rows, kinds_from: list[tuple[str, str, float]]):
    """``rows`` with each test's kind as ``kinds_from`` gives it (unknown tests: unit)."""
    kind_of = {test: kind for kind, test, _ in kinds_from}
    return [(kind_of.get(test, "unit"), test, seconds) for _, test, seconds in rows]


def table(rows: list[tuple[str, str, float]], top: int = 3) -> str:
    """The Markdown table of :func:`durations`' rows by kind."""
    by_kind: dict[str, list[tuple[float, str]]] = defaultdict(list)
    for kind, test, seconds in rows:
        by_kind[kind].append((seconds, test))
    total = sum(s for _, _, s in rows) or 1.0
    lines = [
        "| kind | tests | seconds (one core) | share | slowest |",
        "| --- | ---: | ---: | ---: | --- |",
    ]
    for kind in [*KINDS, *sorted(set(by_kind) - set(KINDS))]:
        cases = sorted(by_kind.get(kind, []), reverse=True)
        if not cases:
            continue
        seconds = sum(s for s, _ in cases)
        slowest = ", ".join(f"`{t.rsplit('.', 1)[-1]}` {s:.1f} s" for s, t in cases[:top])
        lines.append(
            f"| {kind} | {len(cases)} | {seconds:.1f} | {seconds / total:.0%} | {slowest} |"
        )
    lines.append(f"| all | {len(rows)} | {total:.1f} | 100% | |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report", type=Path, help="a JUnit XML report of pytest")
    parser.add_argument("--top", type=int, default=3, help="slowest tests named per kind")
    parser.add_argument("--kinds", type=Path, help="a report giving each test's kind")
    args = parser.parse_args(argv)
    rows = durations(args.report)
    if args.kinds is not None:
        rows = with_kinds(rows, durations(args.kinds))
    print(table(rows, args.top))
    return 0


if __name__ == "__main__":
    sys.exit(main())
