"""check a claims table: exit 1 if a claim marked reproduce failed

Check a claims table the workflow wrote and print it: every claim with its status, the
paper's value and ours; exit 1 if a claim marked reproduce failed.
"""

from __future__ import annotations

import argparse

from .tables import text_table


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "csv",
        nargs="?",
        default="results/claims.csv",
        metavar="CLAIMS.csv",
        help="the claims table (default: results/claims.csv)",
    )
    parser.add_argument(
        "--claims",
        default="config/claims.yaml",
        help="the declared claims the table must hold, in order (default: config/claims.yaml)",
    )
    parser.add_argument(
        "--junit",
        metavar="FILE.xml",
        help="also write the claims as JUnit XML for CI (a test case per claim)",
    )


def _claims_table(table) -> str:
    """Every claim of a claims table (checked) as one aligned line: id, status (in the
    report's words), the paper's value, ours, unit and tolerance, and where the table has
    the robustness analysis, the claim across the consistent readings with its bound."""
    from ..replication.claims import STATUS_WORDS
    from ..replication.robustness import CONFIDENCE, MARGIN, across_short

    records = table.to_dict("records")
    across = "robustness" in table.columns
    rows = [
        (
            row["id"],
            STATUS_WORDS[row["status"]][1],
            f"{float(row['paper_value']):.4g}",
            f"{float(row['reproduced_value']):.4g}",
            row["unit"],
            f"{float(row['tolerance']):g}",
        )
        + ((across_short(row),) if across else ())
        for row in records
    ]
    columns = ("claim", "status", "paper", "ours", "unit", "tolerance")
    text = text_table(columns + (("across readings",) if across else ()), rows, right=(2, 3, 5))
    if across:
        text += (
            f"\nacross readings: the consistent readings it passes under, with a "
            f"{100 * CONFIDENCE:.0f} % bound or interval (exact, over the readings); * the "
            f"readings are too few to decide its class at {100 * MARGIN:.0f} %"
        )
    return text


def run(args: argparse.Namespace) -> int:
    import io
    from contextlib import redirect_stdout
    from pathlib import Path

    from ..inference.claims import ClaimError, load_claims
    from ..inference.paper_config import describe_departures, read_record
    from ..replication.claims import check, read_table

    try:
        declared = load_claims(args.claims)
    except ClaimError as exc:
        raise ValueError(f"the declared claims: {exc}") from None
    if not Path(args.csv).is_file():
        raise ValueError(f"claims table {args.csv!r} does not exist (run the workflow first)")
    record = read_record(args.csv)
    if record["scenario"]:
        # a scenario is an exploration: the table is checked, never graded
        read_table(args.csv, [c["id"] for c in declared])
        if args.junit:
            raise ValueError("--junit grades the paper's configuration only, not a scenario")
        name = record["scenario"]["name"]
        print(f"{args.csv}: scenario {name!r}, an exploration beside the paper: not graded")
        for change in record["scenario"]["changes"]:
            print(f"  {change['text']}")
        return 0
    if record["departures"]:
        raise ValueError(
            f"{args.csv} was computed under a configuration that departs from the paper's, "
            f"so it is not graded: {describe_departures(record)} (declare a change as a "
            "scenario in config/scenarios.yaml and restore config/config.yaml)"
        )
    # the check prints its verdict; the table goes above it, and nothing is printed when
    # the check refuses the table
    verdict = io.StringIO()
    with redirect_stdout(verdict):
        status = check(args.csv, [c["id"] for c in declared], declared)
    print(_claims_table(read_table(args.csv)))
    print(verdict.getvalue(), end="")
    if args.junit:
        from ..replication.junit import write_junit

        write_junit(read_table(args.csv), args.junit)
        print(f"wrote {args.junit}")
    return status
