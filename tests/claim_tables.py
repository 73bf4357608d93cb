"""Claims tables in the shapes a configuration gives, built from the declared claims or a
real table: the paper's (its declared deviations outside their tolerance) and an edited
one's (claims of any set pushed outside their tolerance or back inside), each row's
status the one the claims job writes for its value, so the report takes the table
(tennis_stroke.replication.claims.consistency_errors); and the count lines a page
shows, read back from its text, for the tests of the counts."""

import re

import pandas as pd
import yaml
from conftest import ROOT

from tennis_stroke.inference.reading_space import load_reading_space
from tennis_stroke.replication.claims import measure_text
from tennis_stroke.replication.robustness import EVIDENCE

DECLARED = yaml.safe_load((ROOT / "config/claims.yaml").read_text())["claims"]
FIT_OF = load_reading_space(ROOT / "config/readings.yaml").fit_of_claim()
CLASSES = ("robust", "reading_dependent", "not_reproduced")


def _outside(claim: dict) -> float:
    """A value outside the claim's tolerance (a qualitative claim's other answer)."""
    paper, tolerance = float(claim["paper_value"]), float(claim["tolerance"])
    if str(claim["unit"]) == "1" and tolerance == 0:
        return 1.0 - paper
    return paper + 10.0 * tolerance + 1.0


def with_verdicts(table: pd.DataFrame, outside=(), inside=()) -> pd.DataFrame:
    """``table`` (strings, as read_table reads it) with the claims ``outside`` moved out
    of their tolerance and those ``inside`` to the paper's value: each its status by the
    claims job's rule, an evidence class (the classes in turn) where it lies outside."""
    declared = {c["id"]: c for c in DECLARED}
    out = table.copy()
    for n, (i, row) in enumerate(out.iterrows()):
        if row["id"] not in outside and row["id"] not in inside:
            continue
        c = declared[row["id"]]
        ok = row["id"] in inside
        value = float(c["paper_value"]) if ok else _outside(c)
        if ok:
            status = "used_for_fit" if row["fit_set"] else "pass"
        else:
            status = "known_deviation" if c["expectation"] == "known_deviation" else "fail"
        out.loc[i, "reproduced_value"] = repr(value)
        out.loc[i, "status"] = status
        if "evidence" in out:
            out.loc[i, "evidence"] = "" if ok else EVIDENCE[n % len(EVIDENCE)]
    return out


def declared_table(robustness: bool = True) -> pd.DataFrame:
    """Every declared claim at the paper's value (each passes or is used for fit), in
    the claims table's columns (strings); with ``robustness``, the held-out claims get
    the robustness classes in turn."""
    rows = []
    for n, c in enumerate(DECLARED):
        fit = FIT_OF.get(c["id"], "")
        row = {
            "id": c["id"],
            "source": c["source"],
            "quantity": c["quantity"],
            "unit": str(c["unit"]),
            "paper_value": str(c["paper_value"]),
            "reproduced_value": str(float(c["paper_value"])),
            "tolerance": str(c["tolerance"]),
            "status": "used_for_fit" if fit else "pass",
            "expectation": c["expectation"],
            "reason": c.get("reason", ""),
            "measure": measure_text(c["measure"]),
            "fit_set": fit,
            "map_value": str(float(c["paper_value"])),
            "map_difference": "0.0",
            "map_cause": "agrees",
            "objective_gap": "",
            "flat": "",
            "edge": "",
        }
        if robustness:
            row |= {
                "robustness": "used_for_fit" if fit else CLASSES[n % 3],
                "pass_share": "1.0",
                "deciding": "",
                "best_value": "",
                "best_residual": "",
                "evidence": "",
            }
        rows.append(row)
    return pd.DataFrame(rows)


def papers_shape(table: pd.DataFrame) -> pd.DataFrame:
    """The paper's shape: the declared deviations outside their tolerance."""
    deviations = [c["id"] for c in DECLARED if c["expectation"] == "known_deviation"]
    return with_verdicts(table, outside=deviations)


def edited_shape(table: pd.DataFrame, every: int = 3) -> pd.DataFrame:
    """An edited configuration's shape: beside the paper's, every ``every``-th claim of
    each set (held out, used for fit) outside its tolerance, and every ``every``-th
    declared deviation back inside it."""
    shaped = papers_shape(table)
    held = [i for i, f in zip(shaped["id"], shaped["fit_set"], strict=True) if not f]
    fit = [i for i, f in zip(shaped["id"], shaped["fit_set"], strict=True) if f]
    deviations = [c["id"] for c in DECLARED if c["expectation"] == "known_deviation"]
    return with_verdicts(shaped, outside=held[1::every] + fit[::every], inside=deviations[::every])


def text_of(html: str) -> str:
    """A page's text: tags dropped, entities of quotes and ampersands read, spaces
    collapsed."""
    text = re.sub(r"<[^>]+>", "", html)
    for entity, char in (("&#39;", "'"), ("&quot;", '"'), ("&amp;", "&"), ("&minus;", "-")):
        text = text.replace(entity, char)
    return " ".join(text.split())


def numbers(text: str) -> list[int]:
    """The counts of a list such as ``1 ill conditioned, 4 irreducible``."""
    return [int(n) for n in re.findall(r"(?:^|, )(\d+) ", text)]
