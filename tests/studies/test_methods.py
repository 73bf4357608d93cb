"""The integrators a study can name: unknown methods and bad cases are refused by name,
before any run."""

import numpy as np
import pytest

from tennis_stroke.studies.methods import check_case, parse_method
from tennis_stroke.studies.stability import stability_map


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
