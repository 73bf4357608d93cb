"""The stability study: its failure modes on an isolated contact, the closed-form
contact duration and the contact step cap."""

import numpy as np
import pytest

from tennis_stroke.studies.methods import check_case
from tennis_stroke.studies.stability import (
    OUTCOMES,
    isolated_contact,
    stability_map,
)


def _outcome(method, setting, k):
    return OUTCOMES[isolated_contact(method, setting, k)["outcome"]]


@pytest.mark.parametrize("k", [188.0, 19000.0, 1e7])
def test_default_never_fails(k):
    assert _outcome("tennis_stroke.DOP853", 5e-8, k) == "ok"


@pytest.mark.parametrize(
    "method, setting, k, outcome",
    [
        ("fixed.RK4", 1e-3, 3.2e5, "missed_contact"),  # one step is longer than the contact
        ("fixed.RK4", 1e-3, 1e7, "blow_up"),  # past the explicit stability limit
        ("scipy.RK45", 1e-3, 1e4, "energy_created"),  # a loose tolerance creates energy
        ("fixed.RK4", 1e-4, 1e7, "inaccurate"),
    ],
)
def test_failure_modes(method, setting, k, outcome):
    assert _outcome(method, setting, k) == outcome


def test_isolated_contact_matches_closed_form_duration():
    r = isolated_contact("tennis_stroke.DOP853", 1e-10, 1e6)
    assert r["duration"] == pytest.approx(r["expected_duration"], rel=0.02)
    assert abs(r["energy_change"]) < 1e-8


def test_the_contact_step_cap_is_what_keeps_a_loose_tolerance_accurate():
    """At rtol 0.1 the error estimate alone lets DOP853 take contact steps as long as the
    contact; the cap (half the two-body contact time) keeps it accurate."""
    capped = isolated_contact("tennis_stroke.DOP853", 0.1, 1e6)
    free = isolated_contact("tennis_stroke.DOP853", 0.1, 1e6, step_limit=False)
    assert OUTCOMES[capped["outcome"]] == "ok"
    assert OUTCOMES[free["outcome"]] == "inaccurate"


def test_the_stability_study_runs_loose_compiled_tolerances_on_purpose():
    """The accuracy bound of SolverSettings is lifted for this study only: it measures
    what loose tolerances do."""
    assert check_case("tennis_stroke.DP54", 1e-3) == ("tennis_stroke", "DP54")
    assert check_case("fixed.RK4", 1e-4) == ("fixed", "RK4")
    ds = stability_map([("tennis_stroke.DP54", 1e-3)], np.array([1e4]))
    assert str(ds["case"].values[0]) == "tennis_stroke.DP54 @ 0.001"
