"""tools/test_durations.py: a JUnit report's durations summed by the kind of each test."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("test_durations", ROOT / "tools/test_durations.py")
td = importlib.util.module_from_spec(spec)
spec.loader.exec_module(td)

REPORT = """<testsuites><testsuite name="pytest">
<testcase classname="tests.a" name="t1" time="2.5">
  <properties><property name="kind" value="workflow"/></properties></testcase>
<testcase classname="tests.a" name="t2" time="1.0">
  <properties><property name="kind" value="unit"/></properties></testcase>
<testcase classname="tests.b" name="t3" time="0.5"/>
</testsuite></testsuites>"""


def test_the_durations_are_summed_by_kind(tmp_path):
    report = tmp_path / "run.xml"
    report.write_text(REPORT)
    rows = td.durations(report)
    assert rows == [
        ("workflow", "tests.a::t1", 2.5),
        ("unit", "tests.a::t2", 1.0),
        ("unit", "tests.b::t3", 0.5),
    ]  # no property: a unit test
    lines = td.table(rows).splitlines()
    assert lines[2].startswith("| workflow | 1 | 2.5 | 62% | `a::t1` 2.5 s")
    assert lines[3].startswith("| unit | 2 | 1.5 | 38% | `a::t2` 1.0 s, `b::t3` 0.5 s")
    assert lines[4] == "| all | 3 | 4.0 | 100% | |"
    older = [("unit", "tests.a::t1", 9.0)]
    assert td.with_kinds(older, rows) == [("workflow", "tests.a::t1", 9.0)]


def test_an_unreadable_report_is_one_line(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("<testsuites")
    with pytest.raises(SystemExit, match="cannot read .*bad.xml"):
        td.durations(bad)


def test_every_test_gets_a_kind_in_the_junit_report(request):
    """tests/conftest.py gives this very test its kind, which the JUnit report records."""
    assert ("kind", "unit") in request.node.user_properties
