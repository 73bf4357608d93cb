"""The model ladder read claim by claim (tennis_stroke.replication.ladder), on a small
made-up ladder whose answers are known: cheapest rungs by measured cost, the groups of
files claims read together, the verdicts a group keeps, the declared adoption rule, the
ball-independent claims, the thesis and its wording."""

import numpy as np
import pytest

from tennis_stroke.inference.ladder import ladder_dataset
from tennis_stroke.replication import ladder as rl

CLAIMS = [  # fig2 (an optimum, a speed), fig3 (a trend, with fig2), fig4 (a swing time)
    {"id": "opt", "unit": "degree", "paper_value": 20.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"function": "best_delta0", "file": "fig2"}},
    {"id": "speed", "unit": "km/h", "paper_value": 150.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"file": "fig2", "var": "best_v_out"}},
    {"id": "trend", "unit": "1", "paper_value": 1.0, "tolerance": 0.0,
     "expectation": "reproduce", "measure": {"function": "f", "file": ["fig3", "fig2"]}},
    {"id": "fitted", "unit": "degree", "paper_value": 5.0, "tolerance": 1.0,
     "expectation": "reproduce", "measure": {"file": "fig3", "var": "x"}},
    {"id": "t0", "unit": "s", "paper_value": 0.2, "tolerance": 0.002,
     "expectation": "reproduce", "measure": {"file": "fig4", "var": "t_phi0"}},
]  # fmt: skip
RUNGS = [
    {"name": "cross", "contact_model": "swing_omega2"},
    {"name": "speed", "contact_model": "swing_speed"},
    {"name": "impact", "contact_model": "impact"},
    {"name": "spring", "contact_model": "spring"},
    {"name": "lossy", "contact_model": "spring", "restitution": 0.75},
    {"name": "loose", "contact_model": "spring", "solver": {"rtol": 1e-5}},
]
VALUES = np.array(
    [  # opt, speed, trend, fitted, t0
        [40.0, 300.0, 0.0, 5.0, 0.2],  # cross: loses the optimum and the trend
        [20.05, 290.0, 1.0, 5.0, 0.2],  # speed: no ball speed, keeps the rest
        [20.5, 150.3, 1.0, 5.0, 0.2],  # impact: all pass; the optimum 0.5 tolerances away
        [20.0, 150.0, 1.0, 5.0, 0.2],  # spring: the reference
        [20.02, 128.0, 1.0, 9.0, 0.2],  # lossy: the speed (and a fit claim) fail
        [20.0, 150.0, 1.0, 5.0, 0.2001],  # loose: another integrator moves the swing time
    ]
)
# evaluations per (rung, file): the impact is the cheapest for fig2, cross for fig3
EVALS = np.array(
    [
        [50.0, 10.0, 5.0],
        [60.0, 20.0, 5.0],
        [40.0, 30.0, 5.0],
        [100.0, 100.0, 10.0],
        [105.0, 100.0, 10.0],
        [60.0, 60.0, 6.0],
    ]
)


def _ladder(values=VALUES, rungs=RUNGS):
    ladder = {"rungs": rungs, "reference": "spring", "adoption_agreement": 0.1}
    return ladder_dataset(
        CLAIMS,
        ladder,
        values,
        EVALS,
        np.ones_like(EVALS),
        ["fig2", "fig3", "fig4"],
        {"method": "DOP853", "rtol": 5e-8, "atol": 5e-8},
        {"fitted": "model"},
    )


def test_claims_by_rung_marks_no_answer_and_picks_the_cheapest_that_reproduces():
    table = rl.claims_by_rung(_ladder())
    assert table.loc["speed", "speed"] == "n/a" and table.loc["speed", "cross"] == "n/a"
    assert table.loc["opt", "impact"] == "20.5 *" and table.loc["opt", "cross"] == "40"
    cheapest = table["cheapest rung that reproduces it"]
    # "opt" passes under speed (cost 60), impact (40), spring, lossy, loose (60)
    assert cheapest["opt"] == "impact"
    # "trend" reads both maps: cross fails it; impact 40 + 30 = 70 < speed 60 + 20 = 80
    assert cheapest["trend"] == "impact"
    # "t0": every rung gives it, cross, speed and impact at the same cost: the later one
    assert cheapest["t0"] == "impact"
    assert list(table["reads"]) == ["ball speed"] * 4 + ["swing"]


def test_files_read_together_are_one_group_and_groups_follow_the_rule():
    ds = _ladder()
    assert rl.stored_groups(ds) == [["fig2", "fig3"], ["fig4"]]
    table = rl.experiments_by_rung(ds)
    maps = table.loc["fig2 + fig3"]
    assert maps["claims"] == 4
    # fig2 + fig3: speed cannot answer the speed claim, cross loses the trend; impact
    # keeps every verdict, but its optimum is 0.5 tolerances from the spring's: the rule
    # (0.1) allows only the loose integrator (cost 120 of 200) among all rungs, the
    # spring among the model rungs
    assert maps["cheapest rung keeping every verdict"] == "impact"
    assert maps["cheapest rung the adoption rule allows"] == "loose"
    assert maps["its cost / the reference's"] == pytest.approx(120 / 200)
    assert maps["cheapest model rung the rule allows"] == "spring"
    # fig4: the swing time, the same under every model rung: the cheapest of equal cost
    assert table.loc["fig4", "cheapest model rung the rule allows"] == "impact"


def test_the_thesis_counts_the_conclusions_scored_by_the_ball_each_rung_keeps():
    by_rung = {t["rung"]: t for t in rl.thesis(_ladder())}
    # conclusions: held-out claims the spring reproduces (opt, speed, trend, t0); t0
    # describes the swing
    cross = by_rung["cross"]
    assert (cross["conclusions"], cross["swing"], cross["scored"]) == (4, 1, 3)
    assert cross["lost"] == ["opt", "trend"] and cross["unanswered"] == ["speed"]
    assert by_rung["speed"]["survive"] == 2 and by_rung["speed"]["lost"] == []
    assert by_rung["lossy"]["lost"] == ["speed"]
    assert by_rung["lossy"]["largest_speed_change_kmh"] == pytest.approx(22.0)
    assert by_rung["lossy"]["mean_speed_change_percent"] == pytest.approx(-100 * 22 / 150)
    assert by_rung["impact"]["evaluations_vs_reference"] == pytest.approx(75 / 210)
    assert not by_rung["loose"]["model_rung"] and by_rung["lossy"]["model_rung"]


def test_the_verdict_follows_the_numbers():
    words = " ".join(rl.verdict(_ladder()))
    assert "3 read the ball's rebound speed" in words and "1 describe the swing" in words
    assert "thesis holds against Cross's criterion [cross]" in words
    assert "loses 2 of the 2 of these conclusions it can answer (and keeps 0)" in words
    assert "reproduces every one" in words
    assert "the conclusions that fail are the 1 that quote a ball speed" in words
    # Cross's criterion keeping everything, the lossy ball losing the optimum: said so
    values = VALUES.copy()
    values[0] = VALUES[3]
    values[4, 0] = 25.0
    words = " ".join(rl.verdict(_ladder(values)))
    assert "the paper's thesis is not borne out" in words
    assert "changes conclusions beyond the quoted ball speeds: opt" in words
    assert len(rl.findings(_ladder())) == 5


def test_a_failed_stroke_is_neither_lost_nor_kept_and_prints_no_nan():
    values = VALUES.copy()
    values[2, 1] = np.nan  # the impact's stroke failed
    ds = _ladder(values)
    assert rl.claims_by_rung(ds).loc["speed", "impact"] == "failed"
    impact = next(t for t in rl.thesis(ds) if t["rung"] == "impact")
    assert impact["failed"] == ["speed"] and impact["lost"] == []
    assert impact["speed_claims"] == 0 and impact["largest_speed_change_kmh"] is None
    assert "nan" not in " ".join(rl.findings(ds) + rl.verdict(ds))


def test_a_ball_as_lossy_as_the_references_is_not_called_lossier():
    rungs = [{**r, "restitution": 0.75} if r["contact_model"] == "spring" else r for r in RUNGS]
    ds = _ladder(rungs=rungs)
    assert "not about an elastic ball" not in " ".join(rl.verdict(ds))
