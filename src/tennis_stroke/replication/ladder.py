"""The model ladder read claim by claim (``results/ladder/claims_by_rung.nc``, written by
:mod:`tennis_stroke.inference.ladder`): which rung each claim needs, which rung each
experiment needs, and what the ladder says about the paper's thesis.

* A rung *reproduces* a claim when it can answer it and its value is within the claim's
  tolerance of the paper's.
* A rung *keeps* an experiment (a result file) when every claim that reads the file has
  the same verdict under it as under the reference rung (the paper's model).
* A rung *may replace* the reference for an experiment, by the rule declared in the
  config (``model_ladder.adoption_agreement``), when every claim that reads the file is
  within that share of its tolerance of the reference rung's value (a qualitative claim:
  the same answer).
* A rung's cost for a claim or a file is the right-hand-side evaluations of the compiled
  solver spent on the files; "cheapest" is by that count, measured, not by the rungs'
  order in the config.
* The paper's *conclusions*: the held-out claims (no fit set) the reference rung
  reproduces.  A conclusion *survives* a rung when the rung reproduces it too.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr


def _files(ds: xr.Dataset) -> list[list[str]]:
    return [str(f).split(",") for f in ds["claim_files"].values]


def claim_cost(ds: xr.Dataset) -> np.ndarray:
    """``(rung, claim)``: the evaluations spent on the files each claim reads."""
    evals = ds["rhs_evals"].to_pandas()
    return np.array([[evals.loc[r, files].sum() for files in _files(ds)] for r in evals.index])


def reference_index(ds: xr.Dataset) -> int:
    return list(ds["rung"].values).index(ds.attrs["reference_rung"])


def _cheapest(mask: np.ndarray, cost: np.ndarray, names: np.ndarray) -> list[str]:
    """Per column of ``mask`` (``(rung, item)``), the rung of least ``cost`` where true
    ("" where none)."""
    out = []
    for j in range(mask.shape[1]):
        ok = np.flatnonzero(mask[:, j])
        out.append(str(names[ok[np.argmin(cost[ok, j])]]) if ok.size else "")
    return out


def claims_by_rung(ds: xr.Dataset) -> pd.DataFrame:
    """One row per claim: its value under each rung (``n/a`` where the rung cannot
    answer it; a trailing ``*`` where within tolerance), the paper's value and tolerance,
    and the cheapest rung that reproduces it."""
    names = ds["rung"].values
    within = ds["within"].values.astype(bool)
    table = pd.DataFrame(index=pd.Index(ds["claim"].values, name="claim"))
    table["fit set"] = ds["fit_set"].values
    for i, rung in enumerate(names):
        cells = []
        for value, ok, answers in zip(
            ds["value"].values[i], within[i], ds["comparable"].values[i], strict=True
        ):
            cells.append("n/a" if not answers else f"{value:.4g}{' *' if ok else ''}")
        table[str(rung)] = cells
    table["paper"] = [f"{v:g}" for v in ds["paper_value"].values]
    table["tolerance"] = [f"{v:g}" for v in ds["tolerance"].values]
    table["unit"] = ds["claim_unit"].values
    table["cheapest rung that reproduces it"] = _cheapest(within, claim_cost(ds), names)
    return table


def experiments_by_rung(ds: xr.Dataset) -> pd.DataFrame:
    """One row per result file the claims read: its claims, the cheapest rung that keeps
    all their verdicts, the cheapest rung the adoption rule allows, and that rung's cost
    against the reference rung's."""
    names = ds["rung"].values
    ref = reference_index(ds)
    within = ds["within"].values.astype(bool)
    answers = ds["comparable"].values.astype(bool)
    close = answers & (ds["from_reference"].values <= ds.attrs["adoption_agreement"] + 1e-12)
    same = answers & (within == within[ref])
    evals = ds["rhs_evals"].to_pandas()
    # the model rungs: those with the reference rung's integrator and tolerance
    model_rungs = (ds["method"].values == ds["method"].values[ref]) & (
        ds["rtol"].values == ds["rtol"].values[ref]
    )
    rows = []
    for key in ds["file"].values:
        reads = np.array([key in files for files in _files(ds)])
        if not reads.any():
            continue
        cost = evals[key].values[:, None]
        keeps = _cheapest(same[:, reads].all(axis=1)[:, None], cost, names)[0]
        rule = close[:, reads].all(axis=1)
        allowed = _cheapest(rule[:, None], cost, names)[0]
        model = _cheapest((rule & model_rungs)[:, None], cost, names)[0]
        rows.append(
            {
                "file": str(key),
                "claims": int(reads.sum()),
                "cheapest rung keeping every verdict": keeps,
                "cheapest rung the adoption rule allows": allowed,
                "its cost / the reference's": _ratio(evals, allowed, names[ref], key),
                "cheapest model rung the rule allows": model,
                "its cost / the reference's ": _ratio(evals, model, names[ref], key),
            }
        )
    return pd.DataFrame(rows).set_index("file")


def _ratio(evals: pd.DataFrame, rung: str, reference: str, key: str) -> float:
    return float(evals.loc[rung, key] / evals.loc[reference, key]) if rung else np.nan


def conclusions(ds: xr.Dataset) -> np.ndarray:
    """The paper's conclusions: held-out claims the reference rung reproduces."""
    held_out = ds["fit_set"].values == ""
    return held_out & ds["within"].values[reference_index(ds)].astype(bool)


def thesis(ds: xr.Dataset) -> list[dict]:
    """Per rung other than the reference: how many of the paper's conclusions survive
    it, which are lost and which it cannot answer, and how far the claimed ball speeds
    move (the largest change in km/h and the mean change in %, over the speed claims it
    can answer)."""
    ref = reference_index(ds)
    kept = conclusions(ds)
    ids = ds["claim"].values
    speeds = ds["claim_unit"].values == "km/h"
    out = []
    for i, rung in enumerate(ds["rung"].values):
        if i == ref:
            continue
        answers = ds["comparable"].values[i].astype(bool)
        within = ds["within"].values[i].astype(bool)
        moved = speeds & answers
        change = ds["value"].values[i, moved] - ds["value"].values[ref, moved]
        relative = change / ds["value"].values[ref, moved]
        out.append(
            {
                "rung": str(rung),
                "contact_model": str(ds["contact_model"].values[i]),
                "restitution": float(ds["restitution"].values[i]),
                "method": str(ds["method"].values[i]),
                "rtol": float(ds["rtol"].values[i]),
                "conclusions": int(kept.sum()),
                "survive": int((kept & within).sum()),
                "lost": [str(c) for c in ids[kept & answers & ~within]],
                "unanswered": [str(c) for c in ids[kept & ~answers]],
                "speed_claims": int(moved.sum()),
                "largest_speed_change_kmh": float(np.max(np.abs(change))) if change.size else None,
                "mean_speed_change_percent": (
                    float(100 * np.mean(relative)) if relative.size else None
                ),
                "evaluations_vs_reference": float(
                    ds["rhs_evals"].values[i].sum() / ds["rhs_evals"].values[ref].sum()
                ),
            }
        )
    return out


def _label(t: dict, reference: dict) -> str:
    """What a rung is, in words, from its model and solver against the reference's."""
    if t["contact_model"] == "swing_omega2":
        return "Cross's criterion (no ball: the swing scored by omega2 at phi = 0)"
    if t["contact_model"] == "swing_speed":
        return "The hitting point's speed (no ball: the swing scored by it at phi = 0)"
    if t["contact_model"] == "impact":
        return "An instantaneous impact at phi = 0"
    if t["restitution"] < 1.0:
        return f"A ball that loses energy (coefficient of restitution {t['restitution']:g})"
    if (t["method"], t["rtol"]) != (reference["method"], reference["rtol"]):
        return f"The paper's model integrated by {t['method']} at rtol {t['rtol']:g}"
    return "Another rung"


def findings(ds: xr.Dataset) -> list[str]:
    """The ladder's statements about the paper's thesis, in words, each with the
    numbers behind it (from :func:`thesis`); the wording follows the numbers."""
    ref = reference_index(ds)
    reference = {
        "method": str(ds["method"].values[ref]),
        "rtol": float(ds["rtol"].values[ref]),
    }
    out = []
    for t in thesis(ds):
        text = (
            f"{_label(t, reference)} [{t['rung']}]: {t['survive']} of the paper's "
            f"{t['conclusions']} conclusions survive"
        )
        if t["lost"]:
            text += f"; {len(t['lost'])} are lost ({', '.join(t['lost'])})"
        if t["unanswered"]:
            text += f"; {len(t['unanswered'])} it cannot answer ({', '.join(t['unanswered'])})"
        if t["largest_speed_change_kmh"] is not None:
            text += (
                f"; the claimed ball speeds move by up to {t['largest_speed_change_kmh']:.3g} "
                f"km/h ({t['mean_speed_change_percent']:+.3g} % on average)"
            )
        text += (
            f"; it costs {t['evaluations_vs_reference']:.2f} times the reference's "
            "right-hand-side evaluations."
        )
        out.append(text)
    return out


def verdict(ds: xr.Dataset) -> list[str]:
    """The thesis, tested: one sentence per question the ladder answers, or none where
    the ladder lacks the rung that asks it."""
    by_model = {t["contact_model"]: t for t in thesis(ds)}
    lossy = [t for t in thesis(ds) if t["contact_model"] == "spring" and t["restitution"] < 1]
    speed_ids = set(ds["claim"].values[ds["claim_unit"].values == "km/h"])
    out = []
    cross = by_model.get("swing_omega2")
    if cross:
        if cross["lost"]:
            out.append(
                f"The paper's thesis holds against Cross's criterion: choosing the stroke by "
                f"omega2 at phi = 0 loses {len(cross['lost'])} of the "
                f"{cross['conclusions']} conclusions (listed below): the fastest racket "
                "rotation is not the fastest ball."
            )
        else:
            out.append(
                "Cross's criterion keeps every conclusion it can answer: on these claims "
                "the paper's thesis is not borne out."
            )
    speed = by_model.get("swing_speed")
    if speed:
        answered = speed["conclusions"] - len(speed["unanswered"])
        if not speed["lost"]:
            out.append(
                f"But no collision model is needed for any conclusion the swing can answer: "
                f"scoring the swing by the hitting point's speed at phi = 0 keeps all "
                f"{answered} of them; only the claimed ball speeds themselves need a ball."
            )
        else:
            out.append(
                f"The hitting point's speed alone keeps {speed['survive']} of the "
                f"{answered} conclusions it can answer: the collision model matters for "
                f"{', '.join(speed['lost'])}."
            )
    for t in lossy:
        if set(t["lost"]) <= speed_ids:
            out.append(
                f"The conclusions are about the stroke, not about the elastic ball: with "
                f"a coefficient of restitution of {t['restitution']:g} only the claimed "
                f"speeds change ({t['mean_speed_change_percent']:+.3g} % on average), and "
                "every optimum, trend, threshold and ratio holds."
            )
        else:
            other = sorted(set(t["lost"]) - speed_ids)
            out.append(
                f"A ball that loses energy (e = {t['restitution']:g}) changes conclusions "
                f"beyond the claimed speeds: {', '.join(other)}."
            )
    return out
