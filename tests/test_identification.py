"""Identification: the fit targets come from the claims, and the scoring finds a reading
whose numbers are the targets."""

from pathlib import Path

import pytest

from tennis_stroke import strike
from tennis_stroke.experiments.identification import (
    CANDIDATES,
    Target,
    score_readings,
    targets_from_claims,
)
from tennis_stroke.replication.claims import load_claims

ROOT = Path(__file__).resolve().parents[1]
STROKES = [[120.0, 81.5], [75.0, 39.0]]


def test_targets_are_the_claims_marked_for_identification():
    claims = load_claims(ROOT / "config" / "claims.yaml")
    targets = targets_from_claims(claims, STROKES)
    marked = [c for c in claims if c.get("identification")]
    assert [t.name for t in targets] == [c["id"] for c in marked]
    assert [t.paper for t in targets] == [c["paper_value"] for c in marked]
    assert {t.stroke for t in targets} == {(120.0, 81.5), (75.0, 39.0)}
    assert {t.quantity for t in targets} == {
        "t_phi0",
        "theta@quoted",
        "omega1@quoted",
        "omega2@quoted",
        "v_out_kmh",
    }


def test_a_marked_claim_that_reads_no_stroke_variable_is_refused():
    bad = {
        "id": "odd",
        "identification": True,
        "paper_value": 1.0,
        "tolerance": 0.1,
        "unit": "s",
        "measure": {"function": "greater", "file": "fig4"},
    }
    with pytest.raises(ValueError, match="claim 'odd'"):
        targets_from_claims([bad], STROKES)


def test_a_reading_that_produces_the_targets_scores_zero():
    """Targets made from one reading's own numbers: that reading passes all with score 0,
    and it is ranked first."""
    reading = {
        "inertia": "paper_text",
        "contact_lead_rule": "zero",
        "collision_coupling": "newton",
        "k_contact": 1000.0,
    }
    res = strike(75.0, 39.0, reading)
    targets = [
        Target("t", (75.0, 39.0), "t_phi0", res["t_phi0"], 1e-3, "s"),
        Target("w2", (75.0, 39.0), "omega2@quoted", res["omega2_contact"], 0.1, "rad/s"),
        Target("v", (75.0, 39.0), "v_out_kmh", res["v_out_kmh"], 0.1, "km/h"),
    ]
    table = score_readings(targets)
    best = table.iloc[0]
    assert {k: best[k] for k in reading} == reading
    assert best["omega_quoted_at"] == "contact"
    assert best["passed"] == 3 and best["score"] == pytest.approx(0.0, abs=1e-9)
    assert len(table) == len(CANDIDATES["inertia"]) * 72
