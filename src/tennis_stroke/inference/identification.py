"""Identification of the paper's readings as a fit (``config/readings.yaml``).

The paper leaves readings open (:mod:`tennis_stroke.inference.reading_space`).  Two
declared fit sets of claims pin them down: the ten Fig. 4 numbers (the model readings and
the spring constant and ball mass) and Table I's three speeds with the elbow force (the
mass the Eq. 14 force accelerates and the pulse's extra delay).  For every combination
of a fit set's discrete readings, the continuous unknowns are fitted by bounded least
squares (:func:`scipy.optimize.least_squares`) on the normalised residuals
``(simulated - paper) / tolerance`` from several starts of a seeded Sobol design.
:func:`identify` also computes the profile of the score along each unknown (the other
unknowns refitted) and a leave-one-out prediction of every fit claim, and picks the
default reading by the declared rule.  The claims of a fit set choose the readings, so
they never count as confirmations (the report marks them ``used_for_fit``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..experiments.strokes import table1_cases
from ..io.netcdf import labelled, provenance
from ..model.params import PARAMETERS
from ..solver.results import FILE_NAMES
from ..solver.settings import SolverSettings
from ..solver.stroke import strike_batch
from .labels import claim_facts, variable
from .reading_space import ELBOW_FIT, MODEL_FIT, FitSet, ReadingSpace, literal_rank


@dataclass(frozen=True)
class Target:
    """One fit claim: the stroke (index into its experiment's strokes), the file variable
    (per quoting instant when ``quoting`` names a group), paper value and tolerance."""

    claim: str
    stroke: int
    var: str
    paper: float
    tolerance: float
    unit: str
    absolute: bool = False
    quoting: str | None = None


def quoted_variable(var: str, instant: str, space: ReadingSpace) -> str:
    """The file variable that stands for ``var`` when the quantity is quoted at
    ``instant`` (``phi0`` or ``contact``): ``omega1_contact`` -> ``omega1_phi0`` ..."""
    for by_instant in space.raw["quoted_variables"].values():
        if var in by_instant.values():
            return by_instant[instant]
    return var


def targets(space: ReadingSpace, fit: FitSet, claims: Sequence[Mapping]) -> list[Target]:
    """The fit set's claims (``config/claims.yaml``) as targets.

    Raises
    ------
    ValueError
        A fit claim does not read one stroke variable of a file (one line, its id).
    """
    by_id = {c["id"]: c for c in claims}
    quoting = space.quoting_of_claim()
    out = []
    for claim_id in fit.claims:
        c = by_id[claim_id]
        m = c["measure"]
        if "function" in m or "sel" not in m or set(m["sel"]) != {"stroke"}:
            raise ValueError(f"claim {claim_id!r}: a fit claim must read one stroke variable")
        out.append(
            Target(
                claim_id,
                int(m["sel"]["stroke"]),
                m["var"],
                float(c["paper_value"]),
                float(c["tolerance"]),
                c["unit"],
                bool(m.get("abs", False)),
                quoting.get(claim_id),
            )
        )
    return out


def _file_values(res: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    return {FILE_NAMES.get(k, k): np.asarray(v, dtype=float) for k, v in res.items()}


def model_simulator(
    strokes: Sequence[Sequence[float]], settings: SolverSettings | None = None, threads: int = 1
):
    """Fig. 4's strokes ``(theta0, delta0)`` (degrees) as a function of the overrides."""
    arr = np.asarray(strokes, dtype=float).reshape(-1, 2)

    def simulate(overrides: Mapping[str, object]) -> dict[str, np.ndarray]:
        res = strike_batch(arr[:, 0], arr[:, 1], overrides, settings, threads=threads)
        return _file_values(res)

    return simulate


def elbow_simulator(
    force: Mapping[str, object],
    stroke: Mapping[str, object],
    settings: SolverSettings | None = None,
    threads: int = 1,
):
    """Table I's strokes (:func:`tennis_stroke.experiments.strokes.table1_cases`) as a
    function of the overrides; the unknown ``table1_tau_F`` moves the pulse centre (a
    number, or an array whose last axis has length 1: the cases lie along the last axis)."""
    cases = table1_cases({**force, "table1_tau_F": 0.0}, stroke)
    columns = {k: np.array([case[k] for case in cases], dtype=float) for k in cases[0]}

    def simulate(overrides: Mapping[str, object]) -> dict[str, np.ndarray]:
        overrides = dict(overrides)
        tau_f = np.asarray(overrides.pop("table1_tau_F", force.get("table1_tau_F", 0.0)))
        moved = {**columns, "t_F": columns["t_F"] + tau_f}
        res = strike_batch(
            stroke["theta0"], stroke["delta0"], {**overrides, **moved}, settings, threads=threads
        )
        return _file_values(res)

    return simulate


def residuals(
    values: Mapping[str, np.ndarray],
    goal: Sequence[Target],
    instants: Mapping[str, str],
    space: ReadingSpace,
) -> tuple[np.ndarray, np.ndarray]:
    """Simulated values of the targets (quoted at ``instants``) and their normalised
    residuals ``(value - paper) / tolerance`` (failed strokes: NaN values, residual 1e3).

    ``values`` holds the strokes along the last axis; leading axes (one per candidate
    reading) carry through: the results have the targets along the last axis."""
    sim = []
    for t in goal:
        var = quoted_variable(t.var, instants[t.quoting], space) if t.quoting else t.var
        ok = np.asarray(values["status"])[..., t.stroke] == 0
        v = np.where(ok, np.asarray(values[var], dtype=float)[..., t.stroke], math.nan)
        sim.append(np.abs(v) if t.absolute else v)
    sim = np.stack(sim, axis=-1)
    res = (sim - np.array([t.paper for t in goal])) / np.array([t.tolerance for t in goal])
    return sim, np.where(np.isfinite(res), res, 1e3)


def _score(res: np.ndarray) -> float:
    return float(np.sqrt(np.mean(res**2)))


class _Problem:
    """One discrete combination of one fit set: residuals as a function of the unknowns
    (in unit-cube variables of their declared or exploratory ranges)."""

    def __init__(self, space, fit, goal, simulate, fixed, instants, exploratory=False):
        self.space, self.fit, self.goal, self.simulate = space, fit, goal, simulate
        self.fixed, self.instants, self.exploratory = dict(fixed), dict(instants), exploratory

    def values(self, u: Sequence[float], names: Sequence[str] | None = None) -> dict:
        names = names or self.fit.unknowns
        return {
            n: float(self.space.continuous[n].from_unit(x, self.exploratory))
            for n, x in zip(names, u, strict=True)
        }

    def evaluate(self, overrides: Mapping[str, float], keep: Sequence[int] | None = None):
        sim, res = residuals(
            self.simulate({**self.fixed, **overrides}), self.goal, self.instants, self.space
        )
        return (sim, res) if keep is None else (sim, res[list(keep)])

    def solve(self, starts, free=None, pinned=None, keep=None):
        """Best least-squares fit over ``starts`` (unit-cube points of the ``free``
        unknowns), the others ``pinned`` (values); residuals of ``keep`` targets only."""
        free = list(free or self.fit.unknowns)
        pinned = dict(pinned or {})

        def fun(u):
            return self.evaluate({**pinned, **self.values(u, free)}, keep)[1]

        # about 0.5 s to import: only a fit loads it (the claims and robustness jobs that
        # import this module for its measures do not fit)
        from scipy.optimize import least_squares

        best = None
        for x0 in starts:
            sol = least_squares(
                fun, np.clip(x0, 0, 1), bounds=(0.0, 1.0), diff_step=1e-4, x_scale=1.0
            )
            if best is None or sol.cost < best.cost:
                best = sol
        return {**pinned, **self.values(best.x, free)}


def _starts(n_unknowns: int, count: int, seed: int) -> np.ndarray:
    """The range's centre and ``count - 1`` points of a scrambled Sobol design."""
    pts = [np.full(n_unknowns, 0.5)]
    if count > 1:
        from scipy.stats import qmc  # about 1 s to import: only the samplers load it

        sobol = qmc.Sobol(n_unknowns, scramble=True, seed=seed)
        pts.extend(sobol.random(2 ** math.ceil(math.log2(count - 1)))[: count - 1])
    return np.array(pts)


def _combinations(space: ReadingSpace, fit: FitSet):
    names = list(fit.discrete)
    for combo in itertools.product(*(space.discrete[n] for n in names)):
        yield dict(zip(names, combo, strict=True))


def _split(combo: Mapping[str, str], space: ReadingSpace):
    """Model readings (overrides) and quoting instants of a discrete combination."""
    model = {k: v for k, v in combo.items() if k in space.raw["model"]}
    instants = {k: v for k, v in combo.items() if k in space.raw["quoting"]}
    return model, instants


def _problem(space, fit, goal, simulate, combo, base, exploratory=False) -> _Problem:
    """The fit problem of one discrete combination ``combo`` on top of ``base``."""
    model, instants = _split(combo, space)
    return _Problem(space, fit, goal, simulate, {**(base or {}), **model}, instants, exploratory)


def fit_all(
    space: ReadingSpace,
    fit: FitSet,
    goal: Sequence[Target],
    simulate: Callable,
    base: Mapping[str, object] | None = None,
) -> list[dict]:
    """Fit the unknowns for every discrete combination; rows sorted best first (most
    claims within tolerance, then lowest RMS normalised residual)."""
    rows = []
    starts = _starts(len(fit.unknowns), fit.starts, space.raw["fits"]["seed"])
    for combo in _combinations(space, fit):
        problem = _problem(space, fit, goal, simulate, combo, base)
        best = problem.solve(starts)
        sim, res = problem.evaluate(best)
        rows.append(_row(combo, best, sim, res))
    return sort_fits(rows, space)


def _row(combo, best, sim, res) -> dict:
    return {
        "readings": dict(combo),
        "unknowns": dict(best),
        "values": sim,
        "residuals": res,
        "passed": int(np.sum(np.abs(res) <= 1.0)),
        "score": _score(res),
    }


def sort_fits(rows: list[dict], space: ReadingSpace) -> list[dict]:
    """The declared default rule: most claims within tolerance, then lowest score; rows
    within ``tie_margin`` of the best score tie and are ordered literal choices first,
    then by the order of the declared choices."""
    margin = space.raw["default_rule"]["tie_margin"]

    def order(row):
        return tuple(space.discrete[k].index(v) for k, v in row["readings"].items())

    def literal(row):
        return tuple(literal_rank(k, v) for k, v in row["readings"].items())

    rows = sorted(rows, key=lambda r: (-r["passed"], r["score"]))
    if not rows:
        return rows
    top = rows[0]
    tied = [r for r in rows if r["passed"] == top["passed"] and r["score"] <= top["score"] + margin]
    rest = [r for r in rows if not any(r is t for t in tied)]
    return sorted(tied, key=lambda r: (literal(r), order(r))) + rest


def rounded(values: Mapping[str, float], digits: int) -> dict[str, float]:
    """Each value rounded to ``digits`` significant digits (the declared default rule)."""
    return {k: float(f"{v:.{digits}g}") for k, v in values.items()}


def profiles(
    space: ReadingSpace,
    fit: FitSet,
    goal: Sequence[Target],
    simulate: Callable,
    best: Mapping,
    base: Mapping[str, object] | None = None,
) -> dict[str, dict]:
    """The score along each unknown on ``profile_points`` points of its exploratory (or
    declared) range, the other unknowns refitted at each point, for the discrete
    combination of ``best``."""
    n = space.raw["fits"]["profile_points"]
    problem = _problem(space, fit, goal, simulate, best["readings"], base, exploratory=True)
    out = {}
    for name in fit.unknowns:
        unknown = space.continuous[name]
        grid = unknown.from_unit(np.linspace(0, 1, n), exploratory=True)
        others = [u for u in fit.unknowns if u != name]
        scores, passed, refit = [], [], []
        for value in grid:
            pinned = {name: float(value)}
            if others:
                start = [space.continuous[o].to_unit(best["unknowns"][o], True) for o in others]
                values = problem.solve([np.clip(start, 0, 1)], others, pinned)
            else:
                values = pinned
            _, res = problem.evaluate(values)
            scores.append(_score(res))
            passed.append(int(np.sum(np.abs(res) <= 1.0)))
            refit.append([values[o] for o in others])
        out[name] = {
            "grid": grid,
            "score": np.array(scores),
            "passed": np.array(passed),
            "others": others,
            "refit": np.array(refit).reshape(n, len(others)),
            "in_range": (grid >= unknown.low * (1 - 1e-12)) & (grid <= unknown.high * (1 + 1e-12)),
        }
    return out


def leave_one_out(
    space: ReadingSpace,
    fit: FitSet,
    goal: Sequence[Target],
    simulate: Callable,
    best: Mapping,
    base: Mapping[str, object] | None = None,
) -> list[dict]:
    """Refit the unknowns of ``best``'s combination without each target, and predict it."""
    problem = _problem(space, fit, goal, simulate, best["readings"], base)
    starts = _starts(len(fit.unknowns), fit.starts, space.raw["fits"]["seed"])
    start = [space.continuous[u].to_unit(best["unknowns"][u]) for u in fit.unknowns]
    rows = []
    for i, t in enumerate(goal):
        keep = [j for j in range(len(goal)) if j != i]
        values = problem.solve([np.clip(start, 0, 1), *starts], keep=keep)
        sim, res = problem.evaluate(values)
        rows.append({"claim": t.claim, "unknowns": values, "predicted": sim[i], "residual": res[i]})
    return rows


@dataclass
class Identification:
    """Everything one fit set's identification computed."""

    fit: FitSet
    goal: list[Target]
    rows: list[dict]
    default: dict
    profiles: dict
    loo: list[dict]
    units: dict[str, str]


def identify(
    space: ReadingSpace,
    fit: FitSet,
    goal: Sequence[Target],
    simulate: Callable,
    base: Mapping[str, object] | None = None,
) -> Identification:
    """Fits of every discrete combination, the default by the declared rule (the best
    row, unknowns rounded), its profiles and its leave-one-out predictions."""
    rows = fit_all(space, fit, goal, simulate, base)
    best = rows[0]
    digits = space.raw["default_rule"]["round_digits"]
    default = {"readings": best["readings"], "unknowns": rounded(best["unknowns"], digits)}
    return Identification(
        fit,
        list(goal),
        rows,
        default,
        profiles(space, fit, goal, simulate, best, base),
        leave_one_out(space, fit, goal, simulate, best, base),
        {u: space.continuous[u].unit for u in fit.unknowns},
    )


def model_overrides(space: ReadingSpace, default: Mapping) -> dict[str, object]:
    """Model readings and parameters of a default (no quoting instants, no experiment
    settings), as overrides of :func:`tennis_stroke.model.params.resolve_params`."""
    model, _ = _split(default["readings"], space)
    params = {k: v for k, v in default["unknowns"].items() if k in PARAMETERS}
    return {**model, **params}


def to_datasets(result: Identification, settings: SolverSettings | None = None) -> dict:
    """netCDF-ready datasets: ``fits`` (combination x claim), ``profiles`` (one per
    unknown) and ``loo`` (claim), each with the run's provenance."""
    datasets = {
        "fits": _fits_dataset(result),
        "profiles": _profiles_dataset(result),
        "loo": _loo_dataset(result),
    }
    for ds in datasets.values():
        defaults = dict(ds.attrs)  # after the provenance, as the files always had them
        ds.attrs = {**_attrs(result, settings), **defaults}
    # values in each claim's own unit (claim_unit) and labels carry units "1"
    return {name: labelled(ds) for name, ds in datasets.items()}


def _goal_facts(goal) -> dict[str, tuple]:
    return claim_facts([t.paper for t in goal], [t.tolerance for t in goal], [t.unit for t in goal])


def _fits_dataset(result: Identification) -> xr.Dataset:
    """Every combination of the discrete readings: its fitted unknowns, the fit claims'
    values and residuals, and the defaults as attributes."""
    fit, goal, rows = result.fit, result.goal, result.rows
    combo = "combination"
    fits = xr.Dataset(
        {
            **{
                name: variable(combo, [r["readings"][name] for r in rows], "reading", name=name)
                for name in fit.discrete
            },
            **{
                name: variable(
                    combo,
                    [r["unknowns"][name] for r in rows],
                    "fitted",
                    result.units[name],
                    name=name,
                )
                for name in fit.unknowns
            },
            "value": variable(
                (combo, "claim"), np.array([r["values"] for r in rows]), "identification.value"
            ),
            "residual": variable(
                (combo, "claim"), np.array([r["residuals"] for r in rows]), "residual"
            ),
            "passed": variable(
                combo,
                np.array([r["passed"] for r in rows], dtype=np.int32),
                "identification.passed",
            ),
            "score": variable(combo, np.array([r["score"] for r in rows]), "identification.score"),
            **_goal_facts(goal),
        },
        coords={
            combo: variable(combo, np.arange(len(rows), dtype=np.int32), "index", name=combo),
            "claim": variable("claim", [t.claim for t in goal], "claim"),
        },
    )
    for k, v in {**result.default["readings"], **result.default["unknowns"]}.items():
        fits.attrs[f"default_{k}"] = v
    return fits


def _profiles_dataset(result: Identification) -> xr.Dataset:
    """Each unknown's profile: the score and passed claims along its grid, the others
    refitted along it."""
    data, coords = {}, {}
    for name, p in result.profiles.items():
        coords[name] = variable(name, p["grid"], "unknown", result.units[name], name=name)
        data[f"score_{name}"] = variable(name, p["score"], "score_along", name=name)
        data[f"passed_{name}"] = variable(
            name, p["passed"].astype(np.int32), "passed_along", name=name
        )
        data[f"in_range_{name}"] = variable(name, p["in_range"].astype(np.int8), "in_range")
        for i, o in enumerate(p["others"]):
            data[f"refit_{o}_along_{name}"] = variable(
                name, p["refit"][:, i], "refit_along", result.units[o], other=o, name=name
            )
    return xr.Dataset(data, coords=coords)


def _loo_dataset(result: Identification) -> xr.Dataset:
    """Leave-one-out: each fit claim predicted by a fit without it."""
    goal, loo = result.goal, result.loo
    return xr.Dataset(
        {
            "predicted": variable("claim", [r["predicted"] for r in loo], "predicted"),
            "residual": variable("claim", [r["residual"] for r in loo], "loo.residual"),
            **{
                f"refit_{u}": variable(
                    "claim", [r["unknowns"][u] for r in loo], "fitted", result.units[u], name=u
                )
                for u in result.fit.unknowns
            },
            **{k: v for k, v in _goal_facts(goal).items() if k != "claim_unit"},
        },
        coords={"claim": variable("claim", [t.claim for t in goal], "claim")},
    )


def _attrs(result: Identification, settings: SolverSettings | None) -> dict:
    attrs = provenance({}, settings or SolverSettings())
    attrs["fit_set"] = result.fit.name
    attrs["fit_claims"] = " ".join(result.fit.claims)
    return attrs


#: The kinds of file each fit set writes (``results/identification/{fit}_{kind}.nc``).
KINDS = ("fits", "profiles", "loo")


def run_identification(
    space: ReadingSpace,
    claims: Sequence[Mapping],
    fig4_strokes: Sequence[Sequence[float]],
    force: Mapping[str, object],
    stroke: Mapping[str, object],
    base: Mapping[str, object] | None = None,
    settings: SolverSettings | None = None,
) -> dict[str, Identification]:
    """Both declared fits: the model on Fig. 4's strokes, then the elbow force on Table I's
    strokes (``force``: ``F0, t_d, table1_psi``; ``stroke``: the Sec. V stroke) given the
    model fit's default.  ``base``: model overrides of the config (the fitted readings and
    unknowns replace theirs)."""
    base = dict(base or {})
    model_fit = space.fits[MODEL_FIT]
    model = identify(
        space,
        model_fit,
        targets(space, model_fit, claims),
        model_simulator(fig4_strokes, settings),
        base,
    )
    elbow_fit = space.fits[ELBOW_FIT]
    elbow = identify(
        space,
        elbow_fit,
        targets(space, elbow_fit, claims),
        elbow_simulator(force, stroke, settings),
        {**base, **model_overrides(space, model.default)},
    )
    return {MODEL_FIT: model, ELBOW_FIT: elbow}


def summary(results: Mapping[str, Identification], rows: int = 6) -> str:
    """The best fits, the default by the declared rule and the leave-one-out predictions
    of each fit set, as text (``tennis-stroke identify``)."""
    lines = []
    for name, r in results.items():
        lines.append(f"== fit set {name}: {', '.join(r.fit.claims)}")
        for row in r.rows[:rows]:
            readings = " ".join(f"{k}={v}" for k, v in row["readings"].items())
            unknowns = " ".join(f"{k}={v:.4g}" for k, v in row["unknowns"].items())
            lines.append(
                f"  {row['passed']}/{len(r.goal)} within tolerance, RMS {row['score']:.3f}: "
                f"{readings} {unknowns}".rstrip()
            )
        default = {**r.default["readings"], **r.default["unknowns"]}
        lines.append(f"  default by the declared rule: {default}")
        for loo in r.loo:
            lines.append(
                f"  leave-one-out {loo['claim']}: predicted {loo['predicted']:.4g}, "
                f"residual {loo['residual']:+.2f} tolerances"
            )
    return "\n".join(lines)
