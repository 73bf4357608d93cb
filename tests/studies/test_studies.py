"""Speed against accuracy: failure modes of the stability study, the fixed-step path,
the impact model and the work-precision table."""

import numpy as np
import pytest

from tennis_stroke.solver.rk4 import MISSED_CONTACT, fixed_step_stroke
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import strike
from tennis_stroke.studies.ladder import ladder
from tennis_stroke.studies.methods import check_case, parse_method
from tennis_stroke.studies.sampling import sample_strokes
from tennis_stroke.studies.stability import (
    OUTCOMES,
    isolated_contact,
    stability_map,
)
from tennis_stroke.studies.work_precision import work_precision


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


@pytest.mark.parametrize(("theta0", "delta0"), [(120.0, 81.5), (75.0, 39.0)])
def test_fixed_step_rk4_converges_at_fourth_order(theta0, delta0):
    """v_out's error against a tight compiled stroke falls as h**4 (the slope of log error
    over log step, issue 36's 4 +- 0.3): the events are located on each step's Hermite
    cubic; with the linear interpolation they had before the slope was 2.1."""
    ref = strike(theta0, delta0, settings=SolverSettings(rtol=1e-12, atol=1e-12))["v_out_kmh"]
    steps = np.array([4e-4, 2e-4, 1e-4])
    errors = [abs(fixed_step_stroke(theta0, delta0, {}, h)["v_out_kmh"] - ref) for h in steps]
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.3)


def test_fixed_step_rk4_jumps_over_a_contact_shorter_than_its_step():
    assert fixed_step_stroke(120.0, 81.5, {}, 1e-2)["status"] == MISSED_CONTACT


def test_impact_model_is_close_to_but_not_the_spring_contact():
    """The random-stroke ladder: the impact rung, timed as the spring contact is."""
    ds = ladder(sample_strokes(6, seed=5), repeats=1)
    err = np.abs(ds["v_out_impact"] - ds["v_out_spring"])
    assert 0.05 < float(err.max()) < 5.0
    assert ds.attrs["max_error_impact_kmh"] == float(err.max())
    assert ds.attrs["us_per_stroke_impact"] > 0  # a timing: measured, never compared here


def test_work_precision_table_shape_and_order():
    s = sample_strokes(2, seed=2)
    ds = work_precision(s, [1e-4, 1e-8], [1e-6], [1e-3], scipy_methods=("DOP853",), repeats=1)
    assert ds["error_kmh"].dims == ("method", "setting")
    compiled = ds["error_kmh"].isel(method=1)
    assert float(compiled.sel(setting=1e-8)) < float(compiled.sel(setting=1e-4))
    assert float(ds["failed"].sum()) == 0


def test_the_contact_step_cap_is_what_keeps_a_loose_tolerance_accurate():
    """At rtol 0.1 the error estimate alone lets DOP853 take contact steps as long as the
    contact; the cap (half the two-body contact time) keeps it accurate."""
    capped = isolated_contact("tennis_stroke.DOP853", 0.1, 1e6)
    free = isolated_contact("tennis_stroke.DOP853", 0.1, 1e6, step_limit=False)
    assert OUTCOMES[capped["outcome"]] == "ok"
    assert OUTCOMES[free["outcome"]] == "inaccurate"


@pytest.mark.parametrize("name", ["fixed.RK5", "scipy.Euler", "tennis_stroke.RK4", "DOP853", ""])
def test_unknown_methods_are_refused_by_name(name):
    with pytest.raises(ValueError, match="unknown method"):
        parse_method(name)
    with pytest.raises(ValueError, match="unknown method"):
        stability_map([(name, 1e-3)], np.array([1e4]))


@pytest.mark.parametrize(
    "case, fragment",
    [
        (("fixed.RK5", 1e-3), "unknown method 'fixed.RK5' (known: tennis_stroke.DP54"),
        (("tennis_stroke.dp54", 1e-3), "unknown method 'tennis_stroke.dp54'"),
        (("fixed.RK4", 0.0), "RK4 step (s) of case 'fixed.RK4' must be a number > 0"),
        (("scipy.RK45", -1e-3), "tolerance of case 'scipy.RK45' must be a number > 0"),
        (("scipy.RK45", "1e-3"), "must be a number > 0, got '1e-3'"),
        (("tennis_stroke.DOP853", float("nan")), "must be a number > 0, got nan"),
    ],
)
def test_bad_stability_cases_are_refused_before_any_run(case, fragment):
    with pytest.raises(ValueError) as err:
        check_case(*case)
    assert fragment in str(err.value) and "\n" not in str(err.value)
    with pytest.raises(ValueError, match="must be a number|unknown method"):
        stability_map([("tennis_stroke.DOP853", 5e-8), case], np.array([1e4]))


def test_the_stability_study_runs_loose_compiled_tolerances_on_purpose():
    """The accuracy bound of SolverSettings is lifted for this study only: it measures
    what loose tolerances do."""
    assert check_case("tennis_stroke.DP54", 1e-3) == ("tennis_stroke", "DP54")
    assert check_case("fixed.RK4", 1e-4) == ("fixed", "RK4")
    ds = stability_map([("tennis_stroke.DP54", 1e-3)], np.array([1e4]))
    assert str(ds["case"].values[0]) == "tennis_stroke.DP54 @ 0.001"
