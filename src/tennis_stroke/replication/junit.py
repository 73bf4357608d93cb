"""The paper's claims as JUnit XML, the format every CI dashboard reads (GitHub, GitLab,
Jenkins): one test case per claim, one test suite per section of the paper.

A claim that reproduces passes; one used for a fit passes, marked with the property
``used_for_fit`` (its fit set: it chose the readings and confirms nothing); a known
deviation is skipped, with its evidence class and reason; a failed claim is a failure
with the paper's value, ours, the tolerance and the claim's source.  Written with
junitparser, read back with it in the tests.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
from junitparser import (
    Failure,
    JUnitXml,
    Properties,
    Property,
    Skipped,
    TestCase,
    TestSuite,
)

from ..io.netcdf import write_bytes_whole

#: The name of the whole run's test suites.
NAME = "Youn 2015 replication claims"


def section(source: str) -> str:
    """A claim's section of the paper: its source up to the first comma (``Sec. III``,
    ``Table I``)."""
    return source.split(",")[0].strip() or "claims"


def _values(row) -> str:
    unit = "" if row["unit"] == "1" else f" {row['unit']}"
    return (
        f"paper {row['paper_value']}{unit}, ours {float(row['reproduced_value']):.6g}{unit}, "
        f"tolerance {row['tolerance']}"
    )


def claim_case(row) -> TestCase:
    """One claim (a row of the claims table) as a test case."""
    case = TestCase(row["id"], f"claims.{section(row['source'])}")
    case.system_out = f"{row['source']}: {row['quantity']}: {_values(row)}"
    status = row["status"]
    if status == "used_for_fit":
        props = Properties()
        props.add_property(Property("used_for_fit", row["fit_set"] or "yes"))
        case.append(props)
    elif status == "known_deviation":
        evidence = row.get("evidence", "") or "no evidence class"
        skipped = Skipped(f"known deviation ({evidence}): {_values(row)}")
        skipped.text = row["reason"]
        case.result = [skipped]
    elif status == "fail":
        failure = Failure(f"{_values(row)} ({row['source']})", "ClaimFailed")
        failure.text = row["quantity"]
        case.result = [failure]
    return case


def claims_xml(table: pd.DataFrame) -> JUnitXml:
    """The claims table as JUnit XML: a suite per section, in the table's order."""
    xml = JUnitXml(NAME)
    suites: dict[str, TestSuite] = {}
    for row in table.to_dict("records"):
        name = section(row["source"])
        if name not in suites:
            suites[name] = TestSuite(name)
        suites[name].add_testcase(claim_case(row))
    for suite in suites.values():
        suite.update_statistics()
        xml.add_testsuite(suite)
    xml.update_statistics()
    return xml


def write_junit(table: pd.DataFrame, path: str | Path) -> None:
    """Write the claims as JUnit XML to ``path`` (a temporary file beside it renamed into
    place; a symbolic link stays a link to the file it names).  A missing folder, a
    folder, a device or a pipe as ``path``, or a write that fails, is one line
    (:class:`~tennis_stroke.io.errors.OutputError`) and leaves the target as it was."""
    text = b'<?xml version="1.0" encoding="utf-8"?>\n' + claims_xml(table).tostring()
    write_bytes_whole(path, text)
