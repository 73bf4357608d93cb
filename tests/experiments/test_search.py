"""The searches that replace dense maps (tennis_stroke.experiments.search): closed-form
objectives with known optima, the edges of the box, a periodic axis, failed strokes, the
threshold's bracket, and the stroke objective against the solver."""

import numpy as np
import pytest

from tennis_stroke.experiments.grids import bracket_size
from tennis_stroke.experiments.search import (
    StrokeObjective,
    coarse_axis,
    first_crossing,
    maximize,
    stacked,
    step_bound,
)
from tennis_stroke.solver.settings import SolverSettings
from tennis_stroke.solver.stroke import rhs_evaluations, strike_batch


def quadratic(centres: np.ndarray, scale=1.0):
    """-(x - c)^2 summed over the axes, one centre (row of ``centres``) per problem."""

    def f(points, index):
        return -scale * np.sum((points - centres[index, None, :]) ** 2, axis=-1)

    return f


def test_coarse_axis_includes_both_ends_and_keeps_the_step():
    a = coarse_axis(0.0, 100.0, 7.0)
    assert a[0] == 0.0 and a[-1] == 100.0 and np.max(np.diff(a)) <= 7.0
    assert a.size == bracket_size(0.0, 100.0, 7.0) == 16
    assert coarse_axis(3.0, 3.0, 1.0).tolist() == [3.0]
    with pytest.raises(ValueError, match="step must be > 0"):
        coarse_axis(0.0, 1.0, 0.0)


@pytest.mark.parametrize("dims", [1, 2])
def test_maximize_finds_interior_optima_between_grid_points(dims):
    rng = np.random.default_rng(3)
    centres = rng.uniform(5.0, 95.0, size=(20, dims))
    best = maximize(
        quadratic(centres), 20, [0.0] * dims, [100.0] * dims, [10.0] * dims, [1e-4] * dims
    )
    assert np.max(np.abs(best.x - centres)) <= 1e-4
    assert np.max(np.abs(best.value)) <= dims * 1e-8


def test_maximize_keeps_an_optimum_on_the_edge_and_finds_minima():
    centres = np.array([[-5.0], [120.0], [50.0]])  # below, above and inside [0, 100]
    best = maximize(quadratic(centres), 3, [0.0], [100.0], [10.0], [1e-3])
    assert best.x[:, 0] == pytest.approx([0.0, 100.0, 50.0], abs=1e-3)
    low = maximize(quadratic(centres), 3, [0.0], [100.0], [10.0], [1e-3], sign=-1.0)
    # the minimum of -(x - c)^2 is at the end farthest from c; the value is not negated
    assert low.x[:, 0] == pytest.approx([100.0, 0.0, 0.0], abs=1e-3)
    assert low.value == pytest.approx(-((low.x[:, 0] - centres[:, 0]) ** 2))


def _ridge(points, index):
    """A narrow diagonal ridge rising to (97, 97): from the coarse grid's best corner
    (100, 100), the compass search climbs it in hundreds of small steps."""
    x, y = points[..., 0], points[..., 1]
    return -100.0 * (x - y) ** 2 - (x - 97.0) ** 2


def test_a_long_climb_converges_and_a_search_still_moving_is_named():
    """A whole climb (542 steps here) is not cut short (the Figs. 5-6 searches at
    C1 = -10 N m took up to about 3900 and were stopped at 200): the search's bound is
    the lattice points it can visit; a search stopped while it still moves says how
    many are."""
    box = ([0.0, 0.0], [100.0, 100.0], [50.0, 50.0], [1e-3, 1e-3])
    best = maximize(_ridge, 1, *box)
    assert best.x[0] == pytest.approx([97.0, 97.0], abs=0.1)  # on the ridge, near its top
    with pytest.raises(RuntimeError, match=r"in 200 steps \(1 of 1 searches still moving\)"):
        maximize(_ridge, 1, *box, max_iterations=200)


def test_the_step_bound_counts_the_lattice_points_of_every_step_size():
    # h = 2.5 over a width of 10: 5 points; h = 1.25: 9; h = 0.625 is below the tolerance
    assert step_bound(np.array([10.0]), np.array([2.5]), np.array([1.0])) == 5 + 9 + 1
    # a second axis of one point (no step) multiplies nothing
    assert step_bound(np.array([10.0, 0.0]), np.array([2.5, 0.0]), np.array([1.0, 1.0])) == 15
    # 0.6 / 0.05 is 11.999999999999998: still 13 points, not 12
    assert step_bound(np.array([0.6]), np.array([0.05]), np.array([0.04])) == 13 + 1
    # a bound beyond 64 bits is a Python int, not an overflow
    assert step_bound(np.array([1.0] * 3), np.array([0.5] * 3), np.array([1e-30] * 3)) > 2**64


def test_a_periodic_axis_wraps_around():
    # a peak at 359 deg of a full turn: on [0, 360] without wrapping the search would
    # stop at the edge 360 or at 0; wrapped it finds 359 (or the same point mod 360)
    def f(points, index):
        return np.cos(np.radians(points[..., 0] - 359.0))

    best = maximize(f, 1, [0.0], [360.0], [20.0], [1e-4], periods=[360.0])
    assert best.x[0, 0] == pytest.approx(359.0, abs=1e-3)
    with pytest.raises(ValueError, match="span exactly one period"):
        maximize(f, 1, [0.0], [180.0], [20.0], [1e-4], periods=[360.0])


def test_failed_strokes_are_the_worst_value():
    centres = np.array([[30.0]])

    def f(points, index):
        v = quadratic(centres)(points, index)
        return np.where(points[..., 0] > 60.0, np.nan, v)  # fails beyond 60

    best = maximize(f, 1, [0.0], [100.0], [10.0], [1e-4])
    assert best.x[0, 0] == pytest.approx(30.0, abs=1e-4)

    def never(points, index):
        return np.full(points.shape[:-1], np.nan)

    assert np.isnan(maximize(never, 2, [0.0], [1.0], [0.5], [0.1]).value).all()


def test_first_crossing_brackets_each_switch_to_its_tolerance():
    switch = np.array([0.123, 7.77, 2.5])
    lo, hi = first_crossing(
        lambda x, index: x >= switch[index, None], np.zeros(3), np.full(3, 10.0), 1e-3
    )
    assert np.all(hi - lo <= 1e-3) and np.all(lo < switch) and np.all(switch <= hi)


def test_the_stroke_objective_is_the_solver_and_counts_its_strokes():
    settings = SolverSettings()
    theta0 = np.array([70.0, 110.0])
    objective = StrokeObjective(("delta0",), 2, {"theta0": theta0}, {"L1": 0.35}, settings)
    points = np.array([[[10.0], [40.0]], [[20.0], [60.0]]])
    got = objective(points, np.arange(2))
    want = strike_batch(theta0[:, None], points[..., 0], {"L1": 0.35}, settings)["v_out_kmh"]
    assert np.array_equal(got, want)
    assert objective.evaluated.tolist() == [2, 2] and objective.failed.tolist() == [0, 0]


def test_a_bracket_narrow_enough_is_left_alone_while_others_narrow():
    """A problem's bracket is the same alone or beside others that need more iterations
    (the searches of several readings run in lockstep)."""
    switch = np.array([0.3, 7.77])
    seen = []

    def predicate(x, index):
        seen.append(index.tolist())
        return x >= switch[index, None]

    together = first_crossing(predicate, np.array([0.0, 0.0]), np.array([1.0, 10.0]), 0.1)
    alone = first_crossing(lambda x, i: x >= 0.3, np.zeros(1), np.ones(1), 0.1)
    assert together[0][0] == alone[0][0] and together[1][0] == alone[1][0]
    assert [0] not in seen[2:] and seen[0] == [0, 1] and seen[-1] == [1]


def test_stacked_sets_share_what_they_give_alike_and_give_the_rest_per_problem():
    models = [
        {"L1": 0.4, "k_contact": 188.0, "inertia": "uniform_rod"},
        {"L1": 0.4, "k_contact": 7800.0, "inertia": "paper_text"},
    ]
    shared, per = stacked(models, [2, 3])
    assert shared == {"L1": 0.4}
    assert per["k_contact"].tolist() == [188.0, 188.0, 7800.0, 7800.0, 7800.0]
    assert per["inertia"].tolist() == ["uniform_rod"] * 2 + ["paper_text"] * 3
    assert stacked(models[:1], [4]) == (models[0], {})
    with pytest.raises(ValueError, match="do not all set 'k_contact'"):
        stacked([{"k_contact": 1.0}, {"L1": 0.4}], [1, 1])


def test_a_search_of_several_parameter_sets_gives_each_what_it_gives_alone():
    """Two readings searched in lockstep (one batch of strokes per iteration): bit for
    bit the optimum of each searched alone."""
    settings = SolverSettings()
    theta0 = np.array([80.0, 110.0])
    models = [
        {"L1": 0.4, "k_contact": 188.0, "inertia": "uniform_rod"},
        {"L1": 0.4, "k_contact": 19000.0, "inertia": "paper_text"},
    ]

    def search(sets):
        shared, per = stacked(sets, [theta0.size] * len(sets))
        fixed = {"theta0": np.tile(theta0, len(sets)), **per}
        n = theta0.size * len(sets)
        objective = StrokeObjective(("delta0",), n, fixed, shared, settings)
        return maximize(objective, n, [0.0], [100.0], [20.0], [0.5])

    both = search(models)
    alone = [search([m]) for m in models]
    assert both.x.tobytes() == np.concatenate([a.x for a in alone]).tobytes()
    assert both.value.tobytes() == np.concatenate([a.value for a in alone]).tobytes()
    assert not np.array_equal(alone[0].value, alone[1].value)  # the readings differ


def test_a_memo_runs_no_stroke_twice_and_changes_nothing_else():
    """The same searches (an interior optimum by Chandrupatla's method, an optimum on the
    box's edge by the compass search, failing strokes among the points) with the memo
    and without: bit for bit the same optima, values, evaluations and counts of the
    strokes asked for and failed, with fewer strokes run (counted by the solver)."""
    settings = SolverSettings()
    theta0 = np.array([60.0, 90.0, 120.0])

    def search(memo, dims):
        fixed = {"theta0": theta0} if dims == 1 else {}
        axes = ("delta0",) if dims == 1 else ("theta0", "delta0")
        params = {"L1": 0.35, "C1": -8.0}  # a weak shoulder: some strokes fail
        objective = StrokeObjective(axes, 3, fixed, params, settings, memo=memo)
        lower, upper = ([0.0], [100.0]) if dims == 1 else ([60.0, 0.0], [120.0, 100.0])
        before = rhs_evaluations()
        best = maximize(objective, 3, lower, upper, [20.0] * dims, [0.05] * dims)
        return best, objective, rhs_evaluations() - before

    for dims in (1, 2):
        (plain, o1, run1), (memo, o2, run2) = search(False, dims), search(True, dims)
        assert plain.x.tobytes() == memo.x.tobytes()
        assert plain.value.tobytes() == memo.value.tobytes()
        assert plain.evaluations == memo.evaluations
        assert np.array_equal(o1.evaluated, o2.evaluated)
        assert np.array_equal(o1.failed, o2.failed)
        assert 0 < run2 < run1  # fewer strokes run
    assert o1.failed.sum() > 0  # failing strokes were among the points
