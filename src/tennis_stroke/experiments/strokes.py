"""The paper's single strokes over time (Figs. 4, 10-12, 14 and Table I), each a dataset
of curves and stroke numbers."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..io.netcdf import result_dataset
from ..io.units import cf_attrs
from ..model.dynamics import coefficients, rod_points
from ..model.params import resolve_params
from ..solver.curves import stroke_curves
from ..solver.results import results_from_output
from ..solver.settings import SolverSettings
from ..solver.stroke import solve_coefficients
from .specs import CURVE_VARIABLES

#: How the curves of omega(t) are drawn: the free swing without the ball (the paper
#: computes the swing and the collision separately, Sec. II) or the stroke with the ball.
CURVES = ("free_swing", "with_ball")


def stroke_rows(
    strokes: Sequence[tuple[float, float, Mapping[str, object]]], params: Mapping[str, object]
) -> np.ndarray:
    """The coefficient rows (``(len(strokes), N_CF)``) of the strokes ``(theta0, delta0,
    extra params)`` under the model overrides ``params``."""
    return np.array(
        [coefficients(resolve_params({**params, **extra}), a, b)[0] for a, b, extra in strokes]
    )


def trajectory_arrays(
    strokes: Sequence[Sequence[tuple[float, float, Mapping[str, object]]]],
    params: Sequence[Mapping[str, object]],
    times: np.ndarray,
    settings: SolverSettings,
    curves: Sequence[str] = ("free_swing",),
) -> tuple[dict[str, np.ndarray], dict[str, dict[str, np.ndarray]]]:
    """What :func:`trajectories` computes, for several parameter sets at once: set ``r``
    runs the strokes ``strokes[r]`` (as many in every set) under ``params[r]``.

    Returns the stroke numbers (the fields of
    :func:`~tennis_stroke.solver.results.results_from_output`, each ``(sets, strokes)``;
    every stroke of every set in one call of the compiled stroke) and, for each choice
    of ``curves``, the curves of :data:`~tennis_stroke.experiments.specs.CURVE_VARIABLES`
    (each ``(sets, strokes, len(times))``; every stroke in one call of
    :func:`~tennis_stroke.solver.curves.stroke_curves`).  Each stroke is computed on its
    own, so a set's numbers are those it gets alone."""
    for c in curves:
        if c not in CURVES:
            raise ValueError(f"curves must be one of {', '.join(CURVES)}, got {c!r}")
    rows = np.stack([stroke_rows(s, p) for s, p in zip(strokes, params, strict=True)])
    flat = rows.reshape(-1, rows.shape[-1])
    numbers = results_from_output(solve_coefficients(flat, settings, 1), rows.shape[:2])
    drawn = {}
    for c in curves:
        sampled = stroke_curves(flat, times, c == "with_ball", settings)
        samples = {k: sampled[k] for k in ("omega1", "omega2", "x_elbow", "y_elbow")}
        samples["theta"] = np.degrees(sampled["theta"])
        samples["phi"] = np.degrees(sampled["phi"])
        points = [
            rod_points(*(sampled[k][i] for k in ("theta", "phi", "x_elbow", "y_elbow")), cf)
            for i, cf in enumerate(flat)
        ]
        samples.update({key: np.array([p[key] for p in points]) for key in points[0]})
        samples["kinetic_energy"] = sampled["kinetic_energy"]
        drawn[c] = {k: samples[k].reshape(*rows.shape[:2], -1) for k in CURVE_VARIABLES}
    return numbers, drawn


def trajectories(
    strokes: Sequence[tuple[float, float, Mapping[str, object]]],
    labels: Sequence[str],
    times: np.ndarray,
    params: Mapping[str, object],
    settings: SolverSettings,
    curves: str = "free_swing",
) -> xr.Dataset:
    """Figs. 4, 10-12, 14: omega1, omega2, theta, phi, the elbow path, the stick figure's
    points (:data:`~tennis_stroke.experiments.specs.POINTS`) and the rods' kinetic energy over time.

    Each stroke is ``(theta0, delta0, extra params)``.  Curves come from the compiled
    solver, all strokes in one call (:func:`~tennis_stroke.solver.curves.stroke_curves`:
    the free swing until ``times[-1]``, or with ``curves="with_ball"`` the stroke with
    the contact and the follow-through), the stroke numbers from the compiled stroke
    (:func:`~tennis_stroke.solver.stroke.solve_coefficients`, each stroke on its own,
    also in one call): :func:`trajectory_arrays` of one parameter set.  Curves are NaN
    outside the simulated span.
    """
    numbers, drawn = trajectory_arrays([strokes], [params], times, settings, (curves,))
    ds = result_dataset(
        {k: v[0] for k, v in numbers.items()},
        {"stroke": np.arange(len(strokes))},
        resolve_params(params),
        settings,
    )
    ds = ds.assign_coords(
        label=("stroke", list(labels)),
        theta0=("stroke", [s[0] for s in strokes], cf_attrs("theta0")),
        delta0=("stroke", [s[1] for s in strokes], cf_attrs("delta0")),
    )
    ds["label"].attrs = cf_attrs("label")
    ds = ds.assign_coords(t=("t", times, cf_attrs("t")))
    ds.attrs["curves"] = curves
    samples = drawn[curves]
    return ds.assign(
        {key: (("stroke", "t"), samples[key][0], cf_attrs(key)) for key in CURVE_VARIABLES}
    )


def _times(spec: Mapping[str, object]) -> np.ndarray:
    """Sample times ``0 ... t_end`` (s), ``samples`` of them."""
    return np.linspace(0.0, spec["t_end"], spec["samples"])


def fig4_cases(
    strokes: Sequence[Sequence[float]], t_end: float, samples: int
) -> tuple[list[tuple[float, float, dict]], list[str], np.ndarray]:
    """Fig. 4's strokes ``(theta0, delta0)`` (degrees) as :func:`trajectories` takes
    them, their labels and the sample times ``0 ... t_end`` (s)."""
    return (
        [(a, b, {}) for a, b in strokes],
        [f"({a:g}, {b:g})" for a, b in strokes],
        _times({"t_end": t_end, "samples": samples}),
    )


def fig4_strokes(
    strokes: Sequence[Sequence[float]],
    t_end: float,
    samples: int,
    params: Mapping[str, object],
    settings: SolverSettings,
    curves: str = "free_swing",
) -> xr.Dataset:
    """Fig. 4: the strokes ``(theta0, delta0)`` (degrees) over ``0 ... t_end`` (s)."""
    return trajectories(*fig4_cases(strokes, t_end, samples), params, settings, curves)


#: The delays of Figs. 10-12's strokes, in order (keys of the Sec. V stroke).
DELAYS = ("tau_L", "tau_H")


def delay_cases(
    stroke: Mapping[str, object],
) -> tuple[list[tuple[float, float, dict]], list[str], np.ndarray]:
    """Figs. 10-12's strokes (the Sec. V stroke with the wrist torque delayed by each of
    :data:`DELAYS`) as :func:`trajectories` takes them, their labels and sample times."""
    extra = {"L1": stroke["L1"], "C2": stroke["C2"]}
    cases = [(stroke["theta0"], stroke["delta0"], {**extra, "tau": stroke[k]}) for k in DELAYS]
    return cases, list(DELAYS), _times(stroke)


def delay_strokes(
    stroke: Mapping[str, object],
    params: Mapping[str, object],
    settings: SolverSettings,
    curves: str = "free_swing",
) -> xr.Dataset:
    """Figs. 10-12: the Sec. V stroke (``L1, theta0, C2, delta0``) with the wrist torque
    delayed by ``tau_L`` and by ``tau_H`` (s)."""
    ds = trajectories(*delay_cases(stroke), params, settings, curves)
    ds["tau"] = ("stroke", [stroke[k] for k in DELAYS], cf_attrs("tau"))
    return ds


def table1_cases(force: Mapping[str, object], stroke: Mapping[str, object]) -> list[dict]:
    """The overrides of Table I's strokes: the force ``F0`` of Eq. 14 (width ``t_d``,
    centred at ``tau_H + table1_tau_F``) in each direction of ``table1_psi``, then no
    force; all on the Sec. V stroke (``L1``, ``C2``, ``tau_H``)."""
    base = {
        "L1": stroke["L1"],
        "C2": stroke["C2"],
        "tau": stroke["tau_H"],
        "t_d": force["t_d"],
        "t_F": stroke["tau_H"] + force.get("table1_tau_F", 0.0),
    }
    return [{**base, "F0": force["F0"], "psi_F_deg": p} for p in force["table1_psi"]] + [
        {**base, "F0": 0.0, "psi_F_deg": 0.0}
    ]


def elbow_force_strokes(
    force: Mapping[str, object],
    stroke: Mapping[str, object],
    params: Mapping[str, object],
    settings: SolverSettings,
    curves: str = "free_swing",
) -> xr.Dataset:
    """Table I and Fig. 14: the ``tau_H`` stroke with the elbow force of Eq. 14 (``F0``,
    ``t_d``, centred at ``tau_H + table1_tau_F``, s; 0 if not given) in each direction of
    ``table1_psi`` (degrees), and without it (the last stroke)."""
    psi = list(force["table1_psi"])
    cases = table1_cases(force, stroke)
    labels = [f"F0={force['F0']:g} N, psi={p:g} deg" for p in psi] + ["no force"]
    ds = trajectories(
        [(stroke["theta0"], stroke["delta0"], case) for case in cases],
        labels,
        _times(stroke),
        params,
        settings,
        curves,
    )
    ds["psi_F"] = ("stroke", [*psi, np.nan], cf_attrs("psi_F"))
    ds["F0"] = (
        "stroke",
        [force["F0"]] * len(psi) + [0.0],
        cf_attrs("F0"),
    )
    return ds
