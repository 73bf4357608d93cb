"""The model ladder read claim by claim (``results/ladder/claims_by_rung.nc``, written by
:mod:`tennis_stroke.inference.ladder`): which rung each claim needs, which rung each
experiment needs, and what the ladder says about the paper's thesis.

* A rung *reproduces* a claim when it can answer it and its value is within the claim's
  tolerance of the paper's.
* The *model rungs* are those integrated as the reference rung is (same method and
  tolerances): they differ in the model only.
* A claim is *scored by the ball* when it reads the ball's rebound speed: the speed, an
  optimum, threshold or trend of it, or its change with the spring constant
  (:func:`tennis_stroke.inference.ladder.scored_by_ball`, declared from the measurement,
  not from the values).  The others describe the swing.
* The paper's *conclusions*: the held-out claims (no fit set) the reference rung
  reproduces.  A conclusion *survives* a rung when the rung reproduces it too; the thesis
  (which stroke the ball's speed picks) is read on the conclusions scored by the ball,
  those that describe the swing counted apart.  A stroke that fails under a rung that
  could answer is counted as failed, neither lost nor kept.
* An *experiment group* is a set of result files that claims read together (a claim
  reading two files ties them): a rung is chosen for a whole group, never file by file,
  so no claim is evaluated on files of two rungs.  A rung *keeps* a group when every
  claim that reads it has the verdict it has under the reference rung; it *may replace*
  the reference, by the rule declared in the config (``model_ladder.adoption_agreement``),
  when every such claim is within that share of its tolerance of the reference rung's
  value (a qualitative claim: the same answer).
* A rung's cost is the right-hand-side evaluations of the compiled solver spent on the
  files; "cheapest" is by that count, measured, not by the rungs' order in the config.
  Of rungs of equal cost (the cheap rungs run the same swing), the later in the config
  is taken (the config lists the rungs in order of model detail, other integrators last).
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


def model_rungs(ds: xr.Dataset) -> np.ndarray:
    """``(rung,)``: the rungs integrated as the reference rung is."""
    ref = reference_index(ds)
    same = np.ones(ds.sizes["rung"], dtype=bool)
    for var in ("method", "rtol", "atol"):
        same &= ds[var].values == ds[var].values[ref]
    return same


def _cheapest(mask: np.ndarray, cost: np.ndarray, names: np.ndarray) -> list[str]:
    """Per column of ``mask`` (``(rung, item)``), the rung of least ``cost`` where true,
    the later one of equal cost ("" where none)."""
    out = []
    for j in range(mask.shape[1]):
        ok = np.flatnonzero(mask[:, j])
        if not ok.size:
            out.append("")
            continue
        least = cost[ok, j].min()
        out.append(str(names[ok[cost[ok, j] == least][-1]]))
    return out


def claims_by_rung(ds: xr.Dataset) -> pd.DataFrame:
    """One row per claim: its value under each rung (``n/a`` where the rung cannot
    answer it; a trailing ``*`` where within tolerance), the paper's value and tolerance,
    whether the ball model can change it, and the cheapest rung that reproduces it."""
    names = ds["rung"].values
    within = ds["within"].values.astype(bool)
    table = pd.DataFrame(index=pd.Index(ds["claim"].values, name="claim"))
    table["fit set"] = ds["fit_set"].values
    for i, rung in enumerate(names):
        cells = []
        for value, ok, answers in zip(
            ds["value"].values[i], within[i], ds["comparable"].values[i], strict=True
        ):
            if not answers:
                cells.append("n/a")
            elif not np.isfinite(value):
                cells.append("failed")
            else:
                cells.append(f"{value:.4g}{' *' if ok else ''}")
        table[str(rung)] = cells
    table["paper"] = [f"{v:g}" for v in ds["paper_value"].values]
    table["tolerance"] = [f"{v:g}" for v in ds["tolerance"].values]
    table["unit"] = ds["claim_unit"].values
    table["reads"] = np.where(ds["scored_by_ball"].values == 1, "ball speed", "swing")
    table["cheapest rung that reproduces it"] = _cheapest(within, claim_cost(ds), names)
    return table


def stored_groups(ds: xr.Dataset) -> list[list[str]]:
    """The experiment groups stored in the ladder file (made by
    :func:`tennis_stroke.inference.ladder.file_groups`): the files of each, in group order."""
    group = ds["file_group"].values
    return [[str(k) for k in ds["file"].values[group == g]] for g in range(group.max() + 1)]


def experiments_by_rung(ds: xr.Dataset) -> pd.DataFrame:
    """One row per experiment group (:func:`stored_groups`): its claims, the cheapest
    rung that keeps all their verdicts, the cheapest rung and the cheapest model rung the
    adoption rule allows, with their cost against the reference rung's."""
    names = ds["rung"].values
    ref = reference_index(ds)
    within = ds["within"].values.astype(bool)
    answers = ds["comparable"].values.astype(bool)
    distance = ds["from_reference"].values
    with np.errstate(invalid="ignore"):
        close = answers & (distance <= ds.attrs["adoption_agreement"] + 1e-12)
    # the reference agrees with itself, also where its value is missing
    close[ref] = True
    same = answers & (within == within[ref])
    evals = ds["rhs_evals"].to_pandas()
    models = model_rungs(ds)
    rows = []
    for g, group in enumerate(stored_groups(ds)):
        reads = ds["claim_group"].values == g
        cost = evals[group].sum(axis=1).values[:, None]
        rule = close[:, reads].all(axis=1)
        keeps = _cheapest(same[:, reads].all(axis=1)[:, None], cost, names)[0]
        allowed = _cheapest(rule[:, None], cost, names)[0]
        model = _cheapest((rule & models)[:, None], cost, names)[0]

        rows.append(
            {
                "files": " + ".join(group),
                "claims": int(reads.sum()),
                "cheapest rung keeping every verdict": keeps,
                "cheapest rung the adoption rule allows": allowed,
                "its cost / the reference's": _ratio(cost[:, 0], names, allowed, ref),
                "cheapest model rung the rule allows": model,
                "its cost / the reference's ": _ratio(cost[:, 0], names, model, ref),
            }
        )
    return pd.DataFrame(rows).set_index("files")


def _ratio(cost: np.ndarray, names: np.ndarray, rung: str, ref: int) -> float:
    """``rung``'s cost over the reference rung's (NaN without a rung)."""
    return float(cost[list(names).index(rung)] / cost[ref]) if rung else np.nan


def conclusions(ds: xr.Dataset) -> np.ndarray:
    """The paper's conclusions: held-out claims the reference rung reproduces."""
    held_out = ds["fit_set"].values == ""
    return held_out & ds["within"].values[reference_index(ds)].astype(bool)


def _finite(values: np.ndarray) -> np.ndarray:
    return values[np.isfinite(values)]


def thesis(ds: xr.Dataset) -> list[dict]:
    """Per rung other than the reference: of the paper's conclusions scored by the ball,
    how many survive it, which are lost, which it cannot answer and which strokes failed
    (those that describe the swing counted apart); how far the claimed ball speeds move
    (the largest change in km/h and the mean change in %, over the speed claims it can
    answer and both rungs give); its cost against the reference's."""
    ref = reference_index(ds)
    kept = conclusions(ds)
    fixed = ds["scored_by_ball"].values == 0
    dependent = kept & ~fixed
    ids = ds["claim"].values
    speeds = ds["claim_unit"].values == "km/h"
    out = []
    for i, rung in enumerate(ds["rung"].values):
        if i == ref:
            continue
        answers = ds["comparable"].values[i].astype(bool)
        within = ds["within"].values[i].astype(bool)
        failed = answers & ~np.isfinite(ds["value"].values[i])
        moved = speeds & answers
        change = _finite(ds["value"].values[i, moved] - ds["value"].values[ref, moved])
        relative = _finite(
            (ds["value"].values[i, moved] - ds["value"].values[ref, moved])
            / ds["value"].values[ref, moved]
        )
        out.append(
            {
                "rung": str(rung),
                "contact_model": str(ds["contact_model"].values[i]),
                "restitution": float(ds["restitution"].values[i]),
                "method": str(ds["method"].values[i]),
                "rtol": float(ds["rtol"].values[i]),
                "model_rung": bool(model_rungs(ds)[i]),
                "conclusions": int(kept.sum()),
                "swing": int((kept & fixed).sum()),
                "scored": int(dependent.sum()),
                "survive": int((dependent & within).sum()),
                "lost": [str(c) for c in ids[dependent & answers & ~failed & ~within]],
                "unanswered": [str(c) for c in ids[dependent & ~answers]],
                "failed": [str(c) for c in ids[dependent & failed]],
                "speed_claims": int(change.size),
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
    if not t["model_rung"]:
        return f"The paper's model integrated by {t['method']} at rtol {t['rtol']:g}"
    if _lossier(t, reference):
        return f"A ball of coefficient of restitution {t['restitution']:g}"
    return "Another rung"


def _lossier(t: dict, reference: dict) -> bool:
    """Whether rung ``t`` is the reference's model with a ball that loses more energy."""
    return (
        t["contact_model"] == "spring"
        and t["model_rung"]
        and t["restitution"] < reference["restitution"]
    )


def _reference(ds: xr.Dataset) -> dict:
    return {"restitution": float(ds["restitution"].values[reference_index(ds)])}


def findings(ds: xr.Dataset) -> list[str]:
    """Each rung's statement about the paper's conclusions, in words, with the numbers
    behind it (from :func:`thesis`); the wording follows the numbers."""
    reference = _reference(ds)
    out = []
    for t in thesis(ds):
        text = (
            f"{_label(t, reference)} [{t['rung']}]: {t['survive']} of the paper's "
            f"{t['scored']} conclusions scored by the ball survive"
        )
        if t["lost"]:
            text += f"; lost: {len(t['lost'])} ({', '.join(t['lost'])})"
        if t["unanswered"]:
            text += f"; no answer: {len(t['unanswered'])} ({', '.join(t['unanswered'])})"
        if t["failed"]:
            text += f"; failed strokes: {len(t['failed'])} ({', '.join(t['failed'])})"
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
    """The thesis, tested: one sentence per question a rung of the ladder asks (none
    where the ladder lacks that rung), written from the numbers."""
    rungs = thesis(ds)
    reference = _reference(ds)
    speed_ids = set(ds["claim"].values[ds["claim_unit"].values == "km/h"])
    out = []
    if rungs:
        t = rungs[0]
        out.append(
            f"Of the paper's {t['conclusions']} conclusions (held-out claims its model "
            f"reproduces), {t['scored']} read the ball's rebound speed (the speed, or an "
            f"optimum, threshold or trend of it) and test the thesis; {t['swing']} "
            "describe the swing."
        )
    for t in rungs:
        answered = t["scored"] - len(t["unanswered"]) - len(t["failed"])
        if t["contact_model"] == "swing_omega2":
            if t["lost"]:
                kept = answered - len(t["lost"])
                out.append(
                    f"The paper's thesis holds against Cross's criterion [{t['rung']}]: "
                    f"choosing the stroke by omega2 at phi = 0 loses {len(t['lost'])} of "
                    f"the {answered} of these conclusions it can answer (and keeps {kept}):"
                    " the fastest racket rotation is not the fastest ball."
                )
            else:
                out.append(
                    f"Cross's criterion [{t['rung']}] keeps every one of these conclusions "
                    f"it can answer ({answered}): on these claims the paper's thesis is not "
                    "borne out."
                )
        elif t["contact_model"] == "swing_speed":
            if not t["lost"]:
                out.append(
                    f"But no collision model is needed to reproduce the {answered} of them "
                    f"a swing can answer: scoring it by the hitting point's speed at phi = 0"
                    f" [{t['rung']}] reproduces every one; the {len(t['unanswered'])} it "
                    "cannot answer quote ball speeds, their ratio or the spring constant."
                )
            else:
                out.append(
                    f"The hitting point's speed alone [{t['rung']}] reproduces {t['survive']}"
                    f" of the {answered} of them it can answer: the collision model matters "
                    f"for {', '.join(t['lost'])}."
                )
        elif _lossier(t, reference):
            speed_lost = [c for c in t["lost"] if c in speed_ids]
            other = [c for c in t["lost"] if c not in speed_ids]
            if not other:
                out.append(
                    f"The conclusions are about the stroke, not about an elastic ball: with "
                    f"a coefficient of restitution of {t['restitution']:g} [{t['rung']}] "
                    f"the conclusions that fail are the {len(speed_lost)} that quote a ball "
                    "speed; every other conclusion holds."
                )
            else:
                out.append(
                    f"A ball of coefficient of restitution {t['restitution']:g} "
                    f"[{t['rung']}] changes conclusions beyond the quoted ball speeds: "
                    f"{', '.join(other)}."
                )
    return out
