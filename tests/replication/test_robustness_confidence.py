"""The confidence of the robustness classes (replication/robustness.py): each claim's pass
share with an exact interval over the sampled readings, the bound that states its class,
and the words every reader sees."""

from __future__ import annotations

import numpy as np
import pytest

from tennis_stroke.replication import robustness as rb


def test_a_claim_the_variants_do_not_decide_gets_the_exact_binomial_interval():
    """Passing under all n readings (every variant alike): Clopper-Pearson's closed form,
    ``(alpha/2)**(1/n)`` two-sided and ``alpha**(1/n)`` one-sided (the rule of three:
    about 3/n for the failure share)."""
    for n in (60, 300):
        low, high, fail_bound, pass_bound = rb.share_interval(np.ones((n, 8), bool))
        alpha = 1.0 - rb.CONFIDENCE
        assert low == pytest.approx((alpha / 2) ** (1 / n), rel=1e-9) and high == 1.0
        assert fail_bound == pytest.approx(1 - alpha ** (1 / n), rel=1e-9)
        assert fail_bound == pytest.approx(3 / n, rel=0.03)  # -ln(0.05) = 2.996
        assert pass_bound == 1.0
    low, high, fail_bound, pass_bound = rb.share_interval(np.zeros((60, 8), bool))
    assert (low, high) == (0.0, pytest.approx(1 - (alpha / 2) ** (1 / 60)))
    assert pass_bound == pytest.approx(1 - alpha ** (1 / 60)) and fail_bound == 1.0


def test_a_share_the_enumerated_variants_decide_is_not_widened_as_if_sampled():
    """Passing under one claim-level variant always and under the other never: the share
    is 1/2 for every reading, and its interval is the two variants' mean (0.5 +- half a
    one-variant interval), not the +-0.13 of 60 coin flips."""
    ok = np.zeros((60, 2), bool)
    ok[:, 0] = True
    low, high, _, _ = rb.share_interval(ok)
    width = 1 - 0.025 ** (1 / 60)
    assert low == pytest.approx(0.5 - width / 2) and high == pytest.approx(0.5 + width / 2)
    flips = rb.share_interval(np.arange(60)[:, None] < 30)  # 30 of 60 readings
    assert high - low < (flips[1] - flips[0]) / 4


def test_the_interval_covers_the_true_share_at_its_confidence_at_least():
    """Readings drawn at random from a set where the claim passes under a share p: the
    interval holds p in at least 95 % of 400 draws for each p (exact intervals are
    conservative)."""
    # one claim's interval depends on its count of passes alone: each count's once
    interval = [rb.share_interval(np.arange(60)[:, None] < k)[:2] for k in range(61)]
    rng = np.random.default_rng(20261206)
    for p in (0.03, 0.5, 0.9):
        held = 0
        for _ in range(400):
            low, high = interval[int(np.sum(rng.random((60, 1)) < p))]
            held += low <= p <= high
        assert held / 400 >= rb.CONFIDENCE - 0.02, (p, held)  # 0.02: 1.6 sigma of 400 draws


@pytest.mark.parametrize(
    ("cls", "n", "sure"),
    [("robust", 60, False), ("robust", 300, True), ("not_reproduced", 300, True)],
)
def test_robust_means_a_failure_share_below_the_margin_only_with_enough_readings(cls, n, sure):
    """All passing (or all failing) under n readings: 60 bound the other share at 4.9 %,
    above the 1 % margin, so the sample cannot decide the class; 300 bound it below 1 %."""
    ok = np.full((n, 8), cls == "robust")
    low, high, fail_bound, pass_bound = rb.share_interval(ok)
    bound, decided = rb.class_bound(cls, low, high, fail_bound, pass_bound)
    assert decided is sure and (bound <= rb.MARGIN) is sure


def test_a_reading_dependent_share_near_an_edge_says_the_sample_cannot_decide():
    """Passing under 1 of 60 readings: reading-dependent for certain (a pass and a failure
    were seen), but its interval reaches below 1 %, so it cannot be told from not
    reproduced; under 30 of 60 it can."""
    for k, sure in ((1, False), (30, True)):
        ok = np.zeros((60, 1), bool)
        ok[:k] = True
        assert rb.class_bound("reading_dependent", *rb.share_interval(ok))[1] is sure


def test_every_class_is_stated_with_its_bound_in_words():
    row = {"robustness": "robust", "readings": 60, "class_bound": 0.0487, "class_sure": False}
    assert rb.across_text(row) == (
        "robust: passes under all 60 readings; fails under at most 4.9 % (95 %); "
        "too few readings to bound it below 1 %"
    )
    assert rb.across_short(row) == "all 60, fails <= 4.9 % *"
    row = {
        "robustness": "reading_dependent",
        "readings": 60,
        "pass_share": 0.0167,
        "pass_share_low": 0.00042,
        "pass_share_high": 0.089,
        "class_sure": False,
    }
    assert rb.across_text(row).endswith(
        "passes in 1.7 % (0.042 %-8.9 %, 95 %, 60 readings); too few readings to tell it "
        "from not reproduced at 1 %"
    )
    row = {
        "robustness": "not_reproduced",
        "readings": 300,
        "class_bound": 0.00994,
        "class_sure": True,
        "best_value": 229.7,
    }
    assert rb.across_text(row) == (
        "not reproduced under any of 300 readings; passes under at most 0.99 % (95 %); best 229.7"
    )
    assert rb.across_text({"robustness": "used_for_fit"}) == "used for fit"
