"""The independent scipy path's entry points (tennis_stroke.solver.reference): what they
refuse, in one line naming the argument, before anything is integrated."""

import contextlib
import math
import signal

import numpy as np
import pytest
from conftest import FIG4_A

from tennis_stroke.model.params import ParameterError
from tennis_stroke.solver.reference import MAX_STROKE_TIME, free_swing, solve_stroke


@contextlib.contextmanager
def _within(seconds: int):
    """A TimeoutError after ``seconds`` (a refusal that regressed would hang the run)."""

    def stop(signum, frame):
        raise TimeoutError(f"still running after {seconds} s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"t_max": math.nan}, "argument 't_max' must be a finite number > 0 and <= 2 s, got nan"),
        ({"follow_through": math.nan}, "argument 'follow_through' must be a finite number >= 0"),
        ({"follow_through": math.inf}, "argument 'follow_through' must be a finite number >= 0"),
        ({"follow_through": 1e6}, "'follow_through' must be a finite number >= 0 and <= 2 s"),
        ({"t_max": 1e6}, "argument 't_max' must be a finite number > 0 and <= 2 s, got 1000000.0"),
        ({"contact_min_steps": 0}, "argument 'contact_min_steps' must be a finite number > 0"),
        ({"contact_min_steps": math.nan}, "argument 'contact_min_steps' must be a finite"),
        ({"rtol": -1e-9}, "argument 'rtol' must be a finite number > 0, got -1e-09"),
    ],
)
def test_an_option_that_would_hang_or_divide_by_zero_is_refused(kwargs, fragment):
    """NaN or inf durations and a follow-through of 1e6 s ran at full CPU until killed
    (issue 66, case 4); contact_min_steps = 0 was a ZeroDivisionError and NaN was
    accepted (case 18)."""
    with _within(10), pytest.raises(ParameterError) as raised:
        solve_stroke(*FIG4_A, **kwargs)
    assert fragment in str(raised.value) and "\n" not in str(raised.value)


def test_the_longest_follow_through_is_a_bound_of_the_durations():
    assert MAX_STROKE_TIME == 2.0
    with _within(10), pytest.raises(ParameterError, match="argument 't_end' must be"):
        free_swing(*FIG4_A, 1e6)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (  # the result for 0.5; 0.4 dropped silently (issue 66, case 3)
            lambda: solve_stroke(*FIG4_A, {"M2": np.array([0.5, 0.4])}),
            "solve_stroke computes one stroke: parameter 'M2' must be one value, got "
            "array([0.5, 0.4]) (strike_batch takes arrays)",
        ),
        (
            lambda: solve_stroke(np.array([120.0, 100.0]), 81.5),
            "solve_stroke computes one stroke: initial angle 'theta0' must be one value",
        ),
        (
            lambda: free_swing(120.0, 81.5, 0.1, {"L1": np.array([0.3, 0.4])}),
            "free_swing computes one stroke: parameter 'L1' must be one value",
        ),
        # scipy's message on y0 before (issue 66, case 18)
        (lambda: solve_stroke(math.nan, 81.5), "initial angle 'theta0' must be finite, got nan"),
        # the swing passed phi = 360 deg and hit a turn later (case 2)
        (lambda: solve_stroke(480.0, 81.5), "initial angle 'theta0' must be <= 360 degree"),
    ],
)
def test_one_stroke_of_scalars_within_the_rule_of_the_angles(call, fragment):
    with _within(10), pytest.raises(ParameterError) as raised:
        call()
    assert fragment in str(raised.value) and "\n" not in str(raised.value)
