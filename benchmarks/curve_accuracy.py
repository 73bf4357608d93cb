"""The accuracy of the figures' curves (``tennis_stroke.solver.curves``, docs/solver.md):
the largest differences of the compiled curves (stopping at each sample, rtol = atol =
1e-10) and of the path that drew them before (``solve_ivp`` DOP853 at 1e-10, its dense
output) against ``solve_ivp`` DOP853 at rtol = atol = 1e-13, on the 64 seeded strokes of
``tests/solver/test_curves.py`` at Fig. 4's 641 samples over 0.32 s, both curve choices;
and the right-hand-side evaluations per stroke of each.

Run: ``.venv/bin/python benchmarks/curve_accuracy.py`` (a minute or two on 2 cores).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "solver"))
from test_curves import seeded_strokes  # noqa: E402  (the test's strokes)

from tennis_stroke.model.dynamics import coefficients  # noqa: E402
from tennis_stroke.model.params import resolve_params  # noqa: E402
from tennis_stroke.solver.curves import stroke_curves  # noqa: E402
from tennis_stroke.solver.reference import free_swing, solve_stroke  # noqa: E402

TIMES = np.linspace(0.0, 0.32, 641)
NAMES = ("theta", "phi", "omega1", "omega2")


def _reference(stroke, with_ball, tol):
    theta0, delta0, p = stroke
    if with_ball:
        return solve_stroke(theta0, delta0, p, rtol=tol, atol=tol, follow_through=TIMES[-1])
    return free_swing(theta0, delta0, TIMES[-1], p, rtol=tol, atol=tol)


def main() -> None:
    strokes = seeded_strokes()
    rows = np.array([coefficients(resolve_params(p), a, b)[0] for a, b, p in strokes])
    print("largest differences (theta, phi in rad; omega1, omega2 in rad/s)")
    for with_ball in (False, True):
        ours = stroke_curves(rows, TIMES, with_ball)
        worst = {"compiled 1e-10": np.zeros(4), "solve_ivp 1e-10": np.zeros(4)}
        evals = []
        for i, stroke in enumerate(strokes):
            loose = _reference(stroke, with_ball, 1e-10)
            tight = _reference(stroke, with_ball, 1e-13).sample(TIMES)
            evals.append(loose.result.get("rhs_evals", np.nan))
            old = loose.sample(TIMES)
            for j, name in enumerate(NAMES):
                for key, value in (
                    ("compiled 1e-10", ours[name][i]),
                    ("solve_ivp 1e-10", old[name]),
                ):
                    worst[key][j] = max(worst[key][j], np.nanmax(np.abs(value - tight[name])))
        print("with the ball" if with_ball else "free swing", "against solve_ivp at 1e-13:")
        for key, values in worst.items():
            print(f"  {key:16s}", "  ".join(f"{v:.1e}" for v in values))
        print(f"  compiled right-hand sides per stroke: median {np.median(ours['rhs_evals']):.0f}")
        if with_ball:
            print(f"  solve_ivp 1e-10 right-hand sides per stroke: median {np.median(evals):.0f}")


if __name__ == "__main__":
    main()
