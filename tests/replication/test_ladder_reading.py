"""The model ladder read claim by claim (tennis_stroke.replication.ladder), on a small
made-up ladder whose answers are known: cheapest rungs by measured cost, the verdicts an
experiment keeps, the declared adoption rule, the thesis and its wording."""

import numpy as np
import pytest

from tennis_stroke.inference.ladder import ladder_dataset
from tennis_stroke.replication import ladder as rl

CLAIMS = [  # two files: "a" (an optimum, a speed), "b" (a trend), and a fit claim
    {"id": "opt", "unit": "degree", "paper_value": 20.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"file": "a"}},
    {"id": "speed", "unit": "km/h", "paper_value": 150.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"file": "a"}},
    {"id": "trend", "unit": "1", "paper_value": 1.0, "tolerance": 0.0,
     "expectation": "reproduce", "measure": {"file": ["b", "a"]}},
    {"id": "fitted", "unit": "degree", "paper_value": 5.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"file": "b"}},
]  # fmt: skip
RUNGS = [
    {"name": "cross", "contact_model": "swing_omega2"},
    {"name": "speed", "contact_model": "swing_speed"},
    {"name": "impact", "contact_model": "impact"},
    {"name": "spring", "contact_model": "spring"},
    {"name": "lossy", "contact_model": "spring", "restitution": 0.75},
]
VALUES = np.array(
    [  # opt, speed, trend, fitted
        [40.0, 300.0, 0.0, 5.0],  # cross: loses the optimum and the trend
        [20.05, 290.0, 1.0, 5.0],  # speed: no ball speed, keeps the rest
        [20.5, 150.3, 1.0, 5.0],  # impact: all pass; the optimum 0.5 tolerances away
        [20.0, 150.0, 1.0, 5.0],  # spring: the reference
        [20.02, 128.0, 1.0, 9.0],  # lossy: only the speed (and a fit claim) move
    ]
)
# evaluations per (rung, file): the impact is the cheapest for "a", cross for "b"
EVALS = np.array([[50.0, 10.0], [60.0, 20.0], [40.0, 30.0], [100.0, 100.0], [105.0, 100.0]])


def _ladder(values=VALUES):
    ladder = {"rungs": RUNGS, "reference": "spring", "adoption_agreement": 0.1}
    return ladder_dataset(
        CLAIMS,
        ladder,
        values,
        EVALS,
        np.ones_like(EVALS),
        ["a", "b"],
        {"method": "DOP853", "rtol": 5e-8},
        {"fitted": "model"},
    )


def test_claims_by_rung_marks_no_answer_and_picks_the_cheapest_that_reproduces():
    table = rl.claims_by_rung(_ladder())
    assert table.loc["speed", "speed"] == "n/a" and table.loc["speed", "cross"] == "n/a"
    assert table.loc["opt", "impact"] == "20.5 *" and table.loc["opt", "cross"] == "40"
    cheapest = table["cheapest rung that reproduces it"]
    # "opt" passes under speed (cost 60), impact (40), spring, lossy: impact is cheapest
    assert cheapest["opt"] == "impact"
    # "trend" reads a and b: impact 40 + 30 = 70 < speed 60 + 20 = 80
    assert cheapest["trend"] == "impact"
    # the speed claim: impact (40) beats the spring (100); lossy fails it
    assert cheapest["speed"] == "impact"


def test_experiments_keep_verdicts_and_follow_the_declared_rule():
    table = rl.experiments_by_rung(_ladder())
    # file a: impact keeps every verdict (all pass) but its optimum is 0.5 tolerances
    # from the spring's: the rule (0.1) allows only the spring there
    assert table.loc["a", "cheapest rung keeping every verdict"] == "impact"
    assert table.loc["a", "cheapest rung the adoption rule allows"] == "spring"
    assert table.loc["a", "its cost / the reference's"] == 1.0
    # file b: the trend and the fit claim; cross loses the trend, speed keeps both
    assert table.loc["b", "cheapest rung keeping every verdict"] == "speed"
    assert table.loc["b", "claims"] == 2


def test_the_thesis_counts_the_conclusions_each_rung_keeps():
    by_rung = {t["rung"]: t for t in rl.thesis(_ladder())}
    # the conclusions: held-out claims the spring reproduces (opt, speed, trend)
    assert by_rung["cross"]["conclusions"] == 3
    assert by_rung["cross"]["lost"] == ["opt", "trend"]
    assert by_rung["cross"]["unanswered"] == ["speed"]
    assert by_rung["speed"]["survive"] == 2 and by_rung["speed"]["lost"] == []
    assert by_rung["lossy"]["lost"] == ["speed"]
    assert by_rung["lossy"]["largest_speed_change_kmh"] == pytest.approx(22.0)
    assert by_rung["lossy"]["mean_speed_change_percent"] == pytest.approx(-100 * 22 / 150)
    assert by_rung["impact"]["evaluations_vs_reference"] == pytest.approx(70 / 200)


def test_the_verdict_follows_the_numbers():
    words = " ".join(rl.verdict(_ladder()))
    assert "thesis holds against Cross's criterion" in words
    assert "keeps all 2 of them" in words
    assert "only the claimed speeds change (-14.7 % on average)" in words
    # Cross's criterion keeping everything, the lossy ball losing the optimum: said so
    values = VALUES.copy()
    values[0] = VALUES[3]
    values[4, 0] = 25.0
    words = " ".join(rl.verdict(_ladder(values)))
    assert "the paper's thesis is not borne out" in words
    assert "changes conclusions beyond the claimed speeds: opt" in words
    assert len(rl.findings(_ladder())) == 4
