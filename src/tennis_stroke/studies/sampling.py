"""The strokes every study runs: drawn uniformly across the paper's parameter space."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..solver.results import OK
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch

#: Parameter space of the sampled strokes (uniform ranges; angles in degrees, L1 in m,
#: M2 in kg, C2 in N m, tau in s).
STROKE_SPACE = {
    "theta0": (60.0, 120.0),
    "delta0": (0.0, 90.0),
    "L1": (0.25, 0.45),
    "M2": (0.2, 0.45),
    "C2": (0.0, 8.0),
    "tau": (0.0, 0.2),
}
#: The model parameters among them (the rest are the initial angles).
STROKE_PARAMS = ("L1", "M2", "C2", "tau")
#: The reference solution of the studies: compiled DOP853 at rtol = atol = 1e-13.
REFERENCE = SolverSettings(rtol=1e-13, atol=1e-13, history=8192)


def sample_strokes(n: int, seed: int = 20261121) -> dict[str, np.ndarray]:
    """``n`` strokes drawn uniformly from :data:`STROKE_SPACE` (seeded), all ``ok``."""
    rng = np.random.default_rng(seed)
    out = {k: [] for k in STROKE_SPACE}
    while len(out["theta0"]) < n:
        draw = {k: rng.uniform(*r) for k, r in STROKE_SPACE.items()}
        res = strike_batch(
            draw["theta0"], draw["delta0"], {k: draw[k] for k in STROKE_PARAMS}, REFERENCE
        )
        if res["status"] == OK:
            for k in out:
                out[k].append(draw[k])
    return {k: np.array(v) for k, v in out.items()}


def stroke_params(strokes: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The model parameters of sampled strokes (one value per stroke)."""
    return {k: strokes[k] for k in STROKE_PARAMS}


def sample_scene(
    n: int, seed: int, scene: Mapping[str, object]
) -> tuple[dict[str, np.ndarray], dict[str, object]]:
    """``n`` strokes of a scene of the work-precision study, all ``ok``: the initial
    angles and :data:`STROKE_PARAMS` drawn uniformly from :data:`STROKE_SPACE` as in
    :func:`sample_strokes`, and the scene's parameters, each a value (``k_contact:
    19000``, ``contact_model: swing_speed``) or a range ``[low, high]`` drawn uniformly
    too (``psi_F_deg: [0, 360]``).

    Returns ``(strokes, params)``: the drawn values by name (one per stroke), and the
    model parameters of the strokes (the drawn ones as arrays, the scene's fixed values).
    """
    ranges = {k: tuple(v) for k, v in scene.items() if isinstance(v, list | tuple)}
    fixed = {k: v for k, v in scene.items() if k not in ranges}
    space = {**STROKE_SPACE, **ranges}
    rng = np.random.default_rng(seed)
    out = {k: [] for k in space}
    while len(out["theta0"]) < n:
        draw = {k: rng.uniform(*r) for k, r in space.items()}
        params = {**{k: draw[k] for k in (*STROKE_PARAMS, *ranges)}, **fixed}
        res = strike_batch(draw["theta0"], draw["delta0"], params, REFERENCE)
        if res["status"] == OK:
            for k in out:
                out[k].append(draw[k])
    strokes = {k: np.array(v) for k, v in out.items()}
    return strokes, {**{k: strokes[k] for k in (*STROKE_PARAMS, *ranges)}, **fixed}
