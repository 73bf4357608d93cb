"""The strokes' curves (experiments/strokes.py): the stick figure and the kinetic energy
the report animates, checked against the positions alone."""

import numpy as np
import pytest

from tennis_stroke.experiments.strokes import fig4_strokes
from tennis_stroke.solver.settings import SolverSettings


@pytest.mark.parametrize("curves", ["free_swing", "with_ball"])
def test_the_kinetic_energy_is_that_of_the_moving_stick_figure(curves):
    """The rods' kinetic energy equals 1/2 M v_cm^2 + 1/2 I_cm omega^2 with the centres'
    velocities differentiated from the sampled positions (an independent path: no
    equation of motion), and is zero at rest at t = 0."""
    params = {"M2": 0.35, "F0": 20.0, "psi_F_deg": 76.0}  # a moving elbow with a pulse
    ds = fig4_strokes([[120.0, 81.5], [75.0, 39.0]], 0.3, 3001, params, SolverSettings())
    ds = (
        ds
        if curves == "free_swing"
        else fig4_strokes([[120.0, 81.5]], 0.3, 3001, params, SolverSettings(), curves)
    )
    p = {k.removeprefix("param_"): v for k, v in ds.attrs.items() if k.startswith("param_")}
    t = ds["t"].values
    for i in range(ds.sizes["stroke"]):
        e = ds["kinetic_energy"].values[i]
        assert e[0] == 0.0
        pts = {v: ds[v].values[i] for v in ds.data_vars if v.startswith(("x_", "y_"))}
        energy = 0.0
        for rod, (a, b) in {"1": ("elbow", "wrist"), "2": ("wrist", "racket")}.items():
            vx = np.gradient(0.5 * (pts[f"x_{a}"] + pts[f"x_{b}"]), t)
            vy = np.gradient(0.5 * (pts[f"y_{a}"] + pts[f"y_{b}"]), t)
            omega = ds[f"omega{rod}"].values[i]
            energy = energy + 0.5 * p[f"M{rod}"] * (vx**2 + vy**2)
            energy = energy + 0.5 * p[f"I{rod}_cm"] * omega**2
        inner = np.isfinite(e) & np.isfinite(energy)
        inner[[0, -1]] = False  # one-sided differences at the ends
        # with the ball, the contact's start and end kink the curves: leave them out
        kinks = np.zeros_like(inner)
        for edge in (float(ds["t_contact_start"][i]), float(ds["t_separation"][i])):
            kinks |= np.abs(t - edge) < 2 * (t[1] - t[0])
        inner &= ~kinks
        assert inner.sum() > 1000
        np.testing.assert_allclose(energy[inner], e[inner], rtol=1e-4, atol=1e-6)


@pytest.mark.parametrize("curves", ["free_swing", "with_ball"])
def test_the_curves_come_from_the_compiled_solver_not_solve_ivp(curves, monkeypatch):
    """Each stroke's curves were a ``solve_ivp`` run (about half of a robustness chunk):
    now every stroke of a file is one call of the compiled solver, and no stroke of a
    file reaches scipy's integrator (tests/solver/test_curves.py compares the two)."""

    def refuse(*args, **kwargs):
        raise AssertionError("solve_ivp was called")

    monkeypatch.setattr("tennis_stroke.solver.reference.solve_ivp", refuse)
    ds = fig4_strokes([[120.0, 81.5], [75.0, 39.0]], 0.32, 65, {}, SolverSettings(), curves)
    assert np.isfinite(ds["omega2"].values).all()
