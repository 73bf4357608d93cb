"""The model ladder claim by claim: every claim of ``config/claims.yaml`` evaluated under
each rung of the ladder (``model_ladder`` of the workflow config), with the cost of each
result file under each rung.

A rung is a contact model (the model option ``contact_model``: no ball and the swing
scored by omega2 or by the hitting point's speed, an instantaneous impact, the paper's
spring contact), a ball (``restitution``) and optionally other solver settings.  Under
each rung the files the claims read are computed by the targeted evaluation at the
default reading (:func:`tennis_stroke.inference.targeted.targeted_files`: each optimum
and threshold by its search) and every claim is measured as ``results/claims.csv``
measures it (its measure of ``config/claims.yaml``, the curves of the config's
``figure_curves``).  The cost of a file is the right-hand-side evaluations of the
compiled solver (machine-independent: every stroke counted whole) and the wall time of
its computation (where strokes differ only in the ball or the spring, they share one
swing, :func:`tennis_stroke.solver.stroke.solve_coefficients`: the time is what the
computation took, the evaluations what its strokes cost one by one).

A claim a rung cannot answer is marked not comparable (``comparable`` 0, its value kept
but never counted as reproduced): under a rung without the spring, the claims about the
spring constant (they read :data:`SPRING_FILES`); under a rung without a ball (the swing
rungs), the claims that quote a ball speed or a ratio of ball speeds (units
:data:`BALL_SPEED_UNITS`), since these rungs give a score in km/h, not a speed, and only
its order means something.  Optima, thresholds, trends, times and angles are comparable
under every rung.  Under the cheap rungs the ball meets the racket at ``t0``, so their
"contact" values (``t_contact_start``, ``omega*_contact``) are read at ``t0``, where
their contact is, and the spring's at its contact start.

What follows from the values (which rung reproduces a claim, which rung keeps an
experiment's claims, the thesis) is read off the file by
:mod:`tennis_stroke.replication.ladder`.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr
from scipy.sparse import coo_array
from scipy.sparse.csgraph import connected_components

from ..experiments.specs import PAPER_RESULTS
from ..io.netcdf import labelled, provenance
from ..model.params import resolve_params
from ..solver.settings import SolverSettings
from ..solver.stroke import rhs_evaluations
from ..solver.warmup import ready
from .claims import claim_files, difference, measure, within
from .labels import attrs, claim_facts, variable
from .ladder_plan import check_ladder, rung_model, rung_settings
from .reading_space import CURVE_FILES
from .robustness import files_of_reading
from .search_plan import SEARCHED
from .targeted import targeted_files

#: The files whose claims are about the spring constant (no answer without the spring).
SPRING_FILES = ("k_sensitivity",)
#: Measurements of files of single strokes that read the ball's speed (the others read
#: the swing: times, angles, angular velocities, the curves).
BALL_MEASURES = ("table1_minimum", "k_spread")
#: The units of a claim that quotes a ball speed or a ratio of them (no answer without
#: a ball).
BALL_SPEED_UNITS = ("km/h", "%")
#: The contact models without a ball (:mod:`tennis_stroke.model.impact`).
NO_BALL = ("swing_speed", "swing_omega2")


def comparable(claim: Mapping, contact_model: str) -> bool:
    """Whether a rung of ``contact_model`` can answer ``claim`` (module docstring)."""
    if contact_model != "spring" and set(claim_files(claim)) & set(SPRING_FILES):
        return False
    return not (contact_model in NO_BALL and claim["unit"] in BALL_SPEED_UNITS)


def scored_by_ball(claim: Mapping) -> bool:
    """Whether a claim reads the ball's rebound speed: the speed itself (``v_out``), an
    optimum, threshold or trend of it (the files found by a search), or its change with
    the spring constant.  The other claims describe the swing (times, angles, angular
    velocities, the curves), which a collision model changes only through the instant
    of the contact."""
    spec = claim["measure"]
    if set(claim_files(claim)) & {*SEARCHED, *SPRING_FILES}:
        return True
    return spec.get("var") == "v_out" or spec.get("function") in BALL_MEASURES


def rung_files(
    config: Mapping, model: Mapping, settings: SolverSettings, threads: int | None = 1
) -> tuple[dict[str, xr.Dataset], dict[str, float], dict[str, float]]:
    """The files the claims read under one rung, and per file the right-hand-side
    evaluations and the wall time (s) of its computation."""
    ready(f"batch:{settings.method}")  # compile outside the timings
    ready("reference")
    files, evaluations, seconds = {}, {}, {}
    curves = (config["figure_curves"],)
    for key in PAPER_RESULTS:
        start, n0 = time.perf_counter(), rhs_evaluations()
        files.update(targeted_files(config, model, settings, curves, None, threads, (key,)))
        seconds[key] = time.perf_counter() - start
        evaluations[key] = float(rhs_evaluations() - n0)
    return files, evaluations, seconds


def claim_values(
    claims: Sequence[Mapping], files: Mapping[str, xr.Dataset], curves: str
) -> np.ndarray:
    """Every claim measured on the files of one rung (the curves of ``curves``)."""
    default = files_of_reading(files, curves, None)
    return np.array([measure(c["measure"], default) for c in claims], dtype=float)


def evaluate_ladder(
    claims: Sequence[Mapping],
    config: Mapping,
    threads: int | None = 1,
    fit_of_claim: Mapping[str, str] | None = None,
) -> xr.Dataset:
    """Every claim under every rung of ``config["model_ladder"]`` (the workflow config
    with its ``model``, ``solver``, ``figure_curves``, ``search`` and the paper's
    sections); see :func:`ladder_dataset`."""
    ladder = config["model_ladder"]
    check_ladder(ladder)
    model = dict(config.get("model") or {})
    keys = list(PAPER_RESULTS)
    values, evaluations, seconds, restitution = [], [], [], []
    for rung in ladder["rungs"]:
        overrides = rung_model(model, rung)
        restitution.append(float(resolve_params(overrides)["restitution"]))
        files, evals, secs = rung_files(
            config, overrides, rung_settings(config["solver"], rung), threads
        )
        values.append(claim_values(claims, files, config["figure_curves"]))
        evaluations.append([evals[k] for k in keys])
        seconds.append([secs[k] for k in keys])
    ds = ladder_dataset(
        claims,
        {
            **ladder,
            "rungs": [
                {**r, "restitution": e} for r, e in zip(ladder["rungs"], restitution, strict=True)
            ],
        },
        np.array(values),
        np.array(evaluations),
        np.array(seconds),
        keys,
        config["solver"],
        fit_of_claim or {},
    )
    # provenance: the config's model and solver (each rung's own are variables)
    ds.attrs.update(provenance(resolve_params(model), SolverSettings(**config["solver"])))
    return ds


def file_groups(claims: Sequence[Mapping], keys: Sequence[str]) -> list[list[str]]:
    """The result files the claims read, in groups of files that claims read together
    (connected by the claims that read several: the connected components of that graph,
    scipy's ``connected_components``; a rung is chosen for a whole group), in the order
    of ``keys``."""
    index = {k: i for i, k in enumerate(keys)}
    read = sorted({index[f] for claim in claims for f in claim_files(claim)})
    pairs = [
        (index[files[0]], index[other]) for files in map(claim_files, claims) for other in files[1:]
    ]
    edges = np.array(pairs, dtype=int).reshape(-1, 2)
    graph = coo_array(
        (np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(len(keys), len(keys))
    )
    _, label = connected_components(graph, directed=False)
    groups: dict[int, list[str]] = {}
    for i in read:
        groups.setdefault(label[i], []).append(keys[i])
    return list(groups.values())


def ladder_dataset(
    claims: Sequence[Mapping],
    ladder: Mapping,
    values: np.ndarray,
    evaluations: np.ndarray,
    seconds: np.ndarray,
    keys: Sequence[str],
    solver: Mapping[str, object],
    fit_of_claim: Mapping[str, str],
) -> xr.Dataset:
    """The claims x rungs file: ``value``, ``comparable`` (:func:`comparable`),
    ``within`` (the paper's tolerance; 0 where not comparable) and ``from_reference``
    (distance from the reference rung's value in tolerances; a qualitative claim 0 or 1)
    over ``(rung, claim)``, the cost of each ``(rung, file)``, and each rung's model and
    solver."""
    rungs = ladder["rungs"]
    group_of = {k: g for g, files in enumerate(file_groups(claims, keys)) for k in files}
    ds = xr.Dataset(
        {
            **_verdicts(claims, ladder, values),
            "rhs_evals": variable(("rung", "file"), evaluations, "rhs_evals"),
            "seconds": (("rung", "file"), seconds, {**attrs("seconds"), "timing": 1}),
            **_rung_variables(rungs, solver),
            "file_group": variable(
                "file", np.array([group_of.get(k, -1) for k in keys], dtype=np.int32), "file_group"
            ),
            **_claim_variables(claims, group_of, fit_of_claim),
        },
        coords={
            "rung": variable("rung", [r["name"] for r in rungs], "rung"),
            "claim": variable("claim", [c["id"] for c in claims], "claim"),
            "file": variable("file", list(keys), "file"),
        },
        attrs={
            "reference_rung": ladder["reference"],
            "adoption_agreement": float(ladder["adoption_agreement"]),
            "curve_files": ",".join(CURVE_FILES),
        },
    )
    return labelled(ds)


def _verdicts(claims: Sequence[Mapping], ladder: Mapping, values: np.ndarray) -> dict:
    """Each claim's value under each rung, whether the rung answers it, whether within the
    paper's tolerance, and its distance from the reference rung's value."""
    rungs = ladder["rungs"]
    answers = np.array(
        [[comparable(c, r["contact_model"]) for c in claims] for r in rungs], dtype=bool
    )
    ref = [r["name"] for r in rungs].index(ladder["reference"])
    paper = np.array([c["paper_value"] for c in claims], dtype=float)
    tol = np.array([c["tolerance"] for c in claims], dtype=float)
    both = ("rung", "claim")
    return {
        "value": variable(both, values, "ladder.value"),
        "comparable": variable(both, answers.astype(np.int8), "comparable"),
        "within": variable(
            both, (within(values, paper, tol) & answers).astype(np.int8), "ladder.within"
        ),
        "from_reference": variable(both, difference(values, values[ref], tol), "from_reference"),
    }


def _rung_variables(rungs: Sequence[Mapping], solver: Mapping[str, object]) -> dict:
    """Each rung's contact model, restitution and solver settings."""
    settings = [{**solver, **r.get("solver", {})} for r in rungs]
    return {
        "contact_model": variable("rung", [r["contact_model"] for r in rungs], "contact_model"),
        "restitution": variable(
            "rung", [float(r.get("restitution", 1.0)) for r in rungs], "restitution"
        ),
        "method": variable("rung", [s["method"] for s in settings], "method"),
        "rtol": variable("rung", [float(s["rtol"]) for s in settings], "rtol"),
        "atol": variable("rung", [float(s["atol"]) for s in settings], "atol"),
    }


def _claim_variables(
    claims: Sequence[Mapping], group_of: Mapping[str, int], fit_of_claim: Mapping[str, str]
) -> dict:
    """What the ladder's reading needs of each claim: its group, the paper's value and
    tolerance, the files it reads, whether it reads the ball, its expectation and fit set."""
    return {
        "claim_group": variable(
            "claim",
            np.array([group_of[claim_files(c)[0]] for c in claims], dtype=np.int32),
            "claim_group",
        ),
        **claim_facts(
            np.array([c["paper_value"] for c in claims], dtype=float),
            np.array([c["tolerance"] for c in claims], dtype=float),
            [c["unit"] for c in claims],
        ),
        "claim_files": variable("claim", [",".join(claim_files(c)) for c in claims], "claim_files"),
        "scored_by_ball": variable(
            "claim", np.array([scored_by_ball(c) for c in claims], dtype=np.int8), "scored_by_ball"
        ),
        "expectation": variable("claim", [c["expectation"] for c in claims], "expectation"),
        "fit_set": variable("claim", [fit_of_claim.get(c["id"], "") for c in claims], "fit_set"),
    }
