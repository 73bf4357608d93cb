"""The claims as JUnit XML (tennis_stroke.replication.junit), read back with junitparser:
one test case per claim, a suite per section, each status mapped as CI tools read it."""

import os
import stat

import pandas as pd
import pytest
from conftest import record_configuration
from junitparser import Failure, JUnitXml, Skipped

from tennis_stroke.cli import main
from tennis_stroke.replication.claims import COLUMNS, measure_text
from tennis_stroke.replication.junit import write_junit

ROWS = [
    ("a", "Sec. III, Fig. 2", "pass", "", ""),
    ("b", "Sec. III, Fig. 4", "used_for_fit", "model", ""),
    ("c", "Table I", "known_deviation", "", "irreducible"),
    ("d", "Sec. V, Fig. 9", "fail", "", ""),
]


def table() -> pd.DataFrame:
    rows = []
    for cid, source, status, fit_set, evidence in ROWS:
        row = dict.fromkeys(COLUMNS, "")
        row.update(id=cid, source=source, quantity=f"quantity {cid}", unit="km/h")
        row.update(paper_value="1.0", reproduced_value="1.5", tolerance="0.1", status=status)
        row.update(fit_set=fit_set, evidence=evidence, reason=f"reason {cid}")
        row["expectation"] = "known_deviation" if status == "known_deviation" else "reproduce"
        rows.append(row)
    return pd.DataFrame(rows)


def test_each_status_maps_to_a_junit_result(tmp_path):
    path = tmp_path / "claims.xml"
    write_junit(table(), path)
    xml = JUnitXml.fromfile(str(path))
    assert (xml.tests, xml.failures, xml.skipped, xml.errors) == (4, 1, 1, 0)
    suites = {s.name: s for s in xml}
    assert list(suites) == ["Sec. III", "Table I", "Sec. V"]
    cases = {c.name: c for s in xml for c in s}
    assert cases["a"].is_passed and cases["b"].is_passed
    props = {p.name: p.value for p in cases["b"].child(__import__("junitparser").Properties)}
    assert props == {"used_for_fit": "model"}
    (skipped,) = cases["c"].result
    assert isinstance(skipped, Skipped) and "irreducible" in skipped.message
    assert skipped.text == "reason c"
    (failure,) = cases["d"].result
    assert isinstance(failure, Failure)
    assert failure.message == "paper 1.0 km/h, ours 1.5 km/h, tolerance 0.1 (Sec. V, Fig. 9)"
    assert cases["d"].classname == "claims.Sec. V"


#: The measure of every claim of :func:`claims_files` (a speed, as their unit).
SPEED = {"file": "fig9", "var": "best_v_out"}


def claims_files(folder):
    """A claims table of :data:`ROWS` in ``folder`` whose statuses follow from its values,
    with the claims it grades: ``(csv, declared claims, the table)``."""
    record_configuration(folder)
    csv = folder / "claims.csv"
    declared = folder / "claims.yaml"
    claims = [
        {
            "id": cid,
            "source": s,
            "quantity": f"quantity {cid}",
            "unit": "km/h",
            "paper_value": 1.0,
            "tolerance": 0.1,
            "measure": SPEED,
            "expectation": "known_deviation" if status == "known_deviation" else "reproduce",
            "reason": f"reason {cid}",
        }
        for cid, s, status, _, _ in ROWS
    ]
    declared.write_text(__import__("json").dumps({"claims": claims}))
    # the table's statuses follow from its values: a, b pass only if within tolerance
    frame = table()
    frame["measure"] = measure_text(SPEED)
    frame.loc[frame["id"].isin(["a", "b"]), "reproduced_value"] = "1.05"
    frame.to_csv(csv, index=False)
    return csv, declared, frame


def test_the_claims_command_writes_the_junit_file_also_when_a_claim_fails(tmp_path, capsys):
    csv, declared, frame = claims_files(tmp_path)
    out = tmp_path / "claims.xml"
    assert main(["claims", str(csv), "--claims", str(declared), "--junit", str(out)]) == 1
    xml = JUnitXml.fromfile(str(out))
    counts = frame["status"].value_counts()
    assert xml.tests == len(frame) and xml.failures == counts["fail"]
    assert xml.skipped == counts["known_deviation"]


def test_a_scenario_table_is_never_junit(tmp_path, capsys):
    record_configuration(tmp_path, scenario={"name": "s", "overrides": {}, "changes": []})
    csv = tmp_path / "claims.csv"
    csv.write_text("id\n")
    with pytest.raises(SystemExit):
        main(["claims", str(csv), "--junit", str(tmp_path / "x.xml")])
    assert not (tmp_path / "x.xml").exists()


def test_a_junit_target_that_cannot_be_written_is_one_line(tmp_path, capsys):
    """A missing folder, a folder, a pipe (a file that is not a regular one, as a device
    would be): one line, exit 2, nothing replaced; a symbolic link stays a link."""
    csv, declared, frame = claims_files(tmp_path)
    pipe = tmp_path / "pipe"
    os.mkfifo(pipe)
    for target, words in [
        (tmp_path / "missing" / "claims.xml", "does not exist"),
        (tmp_path, "is a directory"),
        (pipe, "is not a regular file"),
    ]:
        with pytest.raises(SystemExit) as stop:
            main(["claims", str(csv), "--claims", str(declared), "--junit", str(target)])
        err = capsys.readouterr().err
        assert stop.value.code == 2 and err.count("\n") == 1 and words in err, err
    assert stat.S_ISFIFO(pipe.stat().st_mode)
    real = tmp_path / "real.xml"
    real.write_text("old")
    link = tmp_path / "link.xml"
    link.symlink_to(real)
    write_junit(frame, link)
    assert link.is_symlink() and JUnitXml.fromfile(str(real)).tests == len(frame)
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".tmp")] == []


def test_a_junit_report_keeps_its_mode_and_a_read_only_one_is_refused(tmp_path, capsys):
    """Every writer of a user's file: a replaced file keeps its mode (a private 0600 report
    stayed private only by luck: the umask's 0644 replaced it), a read-only one is refused
    in one line and kept (it was replaced, even as root)."""
    csv, declared, frame = claims_files(tmp_path)
    private = tmp_path / "private.xml"
    private.write_text("old")
    private.chmod(0o600)
    write_junit(frame, private)
    assert stat.S_IMODE(private.stat().st_mode) == 0o600
    assert JUnitXml.fromfile(str(private)).tests == len(frame)
    kept = tmp_path / "kept.xml"
    kept.write_text("old")
    kept.chmod(0o444)
    with pytest.raises(SystemExit) as stop:
        main(["claims", str(csv), "--claims", str(declared), "--junit", str(kept)])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and err.count("\n") == 1 and "is read-only" in err, err
    assert kept.read_text() == "old" and stat.S_IMODE(kept.stat().st_mode) == 0o444
