"""Every claim across the readings consistent with the paper, and a cause for every
deviation (``config/readings.yaml``: ``multiverse``, ``evidence``).

:func:`tennis_stroke.inference.robustness.evaluate_readings` evaluates every claim of
``config/claims.yaml`` on the paper's
experiments run under each kept reading of the multiverse
(:mod:`tennis_stroke.inference.multiverse`), under every combination of the
claim-level readings (the instant Fig. 11's theta and Table I's omega2 are quoted at,
the figures' curves).  :func:`classify` gives each claim its robustness class and
:func:`evidence` each deviation of the default reading its evidence class, both by the
rules declared in ``config/readings.yaml`` before any result existed.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from ..inference.reading_space import CLAIM_LEVEL, ReadingSpace

#: Robustness classes with their meaning, in the order of config/readings.yaml.
ROBUSTNESS_MEANING = {
    "used_for_fit": "in a fit set: it chose the readings, so it cannot confirm them",
    "robust": "passes under every consistent reading",
    "reading_dependent": "passes under some consistent readings; the deciding unknown is "
    "the one whose choices (or lower and upper half) differ most in pass rate",
    "not_reproduced": "fails under every consistent reading",
}
ROBUSTNESS = tuple(ROBUSTNESS_MEANING)
#: Each robustness class in the words every reader sees (the report, the README).
ROBUSTNESS_WORDS = {
    "used_for_fit": "used for fit",
    "robust": "robust",
    "reading_dependent": "reading-dependent",
    "not_reproduced": "not reproduced under any reading",
}
#: Evidence classes of a deviation (a claim that does not pass under the default
#: reading) with their meaning, in the order of config/readings.yaml.  No evidence class
#: shares a name or a word with a robustness class (:func:`class_words`): a deviation
#: the default reading's choice explains is ``reading_choice``, a claim that passes under
#: some readings and fails under others is ``reading_dependent``.
EVIDENCE_MEANING = {
    "ill_conditioned": "an optimum's location whose objective at the paper's value lies "
    "within the speed tolerance of the optimum: the paper's argument is as good as ours",
    "reading_choice": "the default reading's choice: passes under some other consistent "
    "reading that also passes every claim the default passes (the deciding unknown is "
    "named)",
    "paper_inconsistency": "passes under some consistent readings, but none of them also "
    "passes every claim the default passes",
    "irreducible": "fails under every consistent reading declared before the results (the "
    "best value reached is shown); a reading found after the results does not count: "
    "chosen after seeing them, it would fit the claim it is to test",
}
EVIDENCE = tuple(EVIDENCE_MEANING)
#: Each evidence class in the words every reader sees (the report, the article).
EVIDENCE_WORDS = {
    "ill_conditioned": "ill conditioned",
    "reading_choice": "reading choice",
    "paper_inconsistency": "paper inconsistency",
    "irreducible": "irreducible",
}


def class_words(key: str) -> str:
    """A robustness class or an evidence class in the words every reader sees
    (:data:`ROBUSTNESS_WORDS`, :data:`EVIDENCE_WORDS`; a key of neither: its name with
    spaces).  The two sets share no name and no word, so a term on a page names one
    thing."""
    return {**ROBUSTNESS_WORDS, **EVIDENCE_WORDS}.get(key, key.replace("_", " "))
#: The confidence of every interval and bound on a pass share, and the share below which
#: a claim counts as passing (or failing) under practically no consistent reading.
#: Declared 2026-12-06 (issue 55) before any interval was computed.
CONFIDENCE = 0.95
MARGIN = 0.01
#: Columns :func:`annotate` adds to the claims table.
COLUMNS = (
    "robustness",
    "pass_share",
    "readings",
    "pass_share_low",
    "pass_share_high",
    "class_bound",
    "class_sure",
    "deciding",
    "best_value",
    "best_residual",
    "evidence",
)


def _deciding(ok: np.ndarray, ds: xr.Dataset, space: ReadingSpace) -> str:
    """The unknown whose choices (discrete) or lower/upper half of the range (continuous)
    differ most in pass rate, with the passing and all (reading, variant) cells of each:
    ``name (a 8/8, b 0/472)``."""
    best, text = -1.0, ""
    groups: dict[str, dict[str, np.ndarray]] = {}
    for name in ds.data_vars:
        dims = ds[name].dims
        if dims == ("reading",) and name in space.discrete:
            labels = np.broadcast_to(ds[name].values[:, None], ok.shape)
        elif dims == ("variant",) and name in CLAIM_LEVEL:
            labels = np.broadcast_to(ds[name].values[None, :], ok.shape)
        elif dims == ("reading",) and name in space.continuous:
            u = space.continuous[name].to_unit(ds[name].values)
            half = np.where(u < 0.5, "lower half", "upper half")
            labels = np.broadcast_to(half[:, None], ok.shape)
        else:
            continue
        groups[name] = {str(v): ok[labels == v] for v in np.unique(labels)}
    for name, by_choice in groups.items():
        rates = {k: float(np.mean(v)) for k, v in by_choice.items() if v.size}
        if len(rates) < 2:
            continue
        spread = max(rates.values()) - min(rates.values())
        if spread > best + 1e-12:
            best = spread
            shown = ", ".join(f"{k} {int(by_choice[k].sum())}/{by_choice[k].size}" for k in rates)
            text = f"{name} ({shown})"
    return text


def share_interval(ok: np.ndarray) -> tuple[float, float, float, float]:
    """The pass share of one claim over (reading, variant) cells ``ok`` with its
    uncertainty from the sample of readings: ``(low, high, fail_bound, pass_bound)``.

    The readings are a sample of the consistent set; the claim-level variants are all
    enumerated, each with equal weight.  For each variant the claim passes under ``k`` of
    the ``n`` readings; its exact (Clopper-Pearson) interval at :data:`CONFIDENCE` is
    :func:`scipy.stats.binomtest`'s ``proportion_ci(method="exact")``, and the claim's is
    the mean over the variants of theirs (the pass share is that mean): exact when the
    claim does not depend on the variant, wider than needed when the variants' passes
    are not the same readings.  ``fail_bound`` is the one-sided upper bound of the share
    under which it fails, ``pass_bound`` of the share under which it passes (both at
    :data:`CONFIDENCE`)."""
    from scipy.stats import binomtest

    n = ok.shape[0]
    if n == 0:
        return (float("nan"),) * 4
    cis, above, below = [], [], []
    for k in ok.sum(axis=0).astype(int):
        cis.append(binomtest(int(k), n).proportion_ci(CONFIDENCE, method="exact"))
        above.append(binomtest(int(k), n, alternative="greater").proportion_ci(CONFIDENCE).low)
        below.append(binomtest(int(k), n, alternative="less").proportion_ci(CONFIDENCE).high)
    return (
        float(np.mean([c.low for c in cis])),
        float(np.mean([c.high for c in cis])),
        1.0 - float(np.mean(above)),
        float(np.mean(below)),
    )


def class_bound(cls: str, low: float, high: float, fail_bound: float, pass_bound: float):
    """The bound that states a robustness class, and whether the sample decides the class
    at :data:`MARGIN`: ``robust`` with the upper bound of its failure share (sure when
    below the margin), ``not_reproduced`` with the upper bound of its pass share (the
    same), ``reading_dependent`` with its interval (sure when the interval keeps clear of
    both margins: it passes, and fails, under more than 1 % of the readings)."""
    if cls == "robust":
        return fail_bound, bool(fail_bound <= MARGIN)
    if cls == "not_reproduced":
        return pass_bound, bool(pass_bound <= MARGIN)
    if cls == "reading_dependent":
        return float("nan"), bool(low >= MARGIN and high <= 1.0 - MARGIN)
    return float("nan"), True


def _percent(x) -> str:
    """A share as a percentage with the digits it needs (0.0487 -> '4.9 %')."""
    value = 100 * float(x)
    return f"{value:.0f} %" if value >= 10 or value == 0 else f"{value:.2g} %"


def _number_or_nan(row: Mapping, key: str) -> float:
    try:
        return float(row.get(key, "nan"))
    except (TypeError, ValueError):
        return float("nan")


def across_text(row: Mapping) -> str:
    """A claim's robustness in words, with its confidence (a row of the claims table):
    what the report, the article and ``tennis-stroke claims`` say of it."""
    cls = str(row.get("robustness", "") or "")
    n = _number_or_nan(row, "readings")
    bound = _number_or_nan(row, "class_bound")
    of = f"{n:.0f} readings" if np.isfinite(n) else "the readings"
    level = f"{100 * CONFIDENCE:.0f} %"
    sure = str(row.get("class_sure", "True")) in ("True", "true", "1", "1.0")
    unsure = "" if sure else f"; too few readings to bound it below {_percent(MARGIN)}"
    if cls == "used_for_fit":
        return "used for fit"
    if cls == "robust":
        if not np.isfinite(bound):
            return "robust: passes under every reading"
        return (
            f"robust: passes under all {of}; fails under at most "
            f"{_percent(bound)} ({level}){unsure}"
        )
    if cls == "reading_dependent":
        low, high = _number_or_nan(row, "pass_share_low"), _number_or_nan(row, "pass_share_high")
        text = f"reading-dependent: passes in {_percent(row.get('pass_share'))}"
        if np.isfinite(low) and np.isfinite(high):
            text += f" ({_percent(low)}-{_percent(high)}, {level}, {of})"
        if not sure:
            near = "robust" if high > 1.0 - MARGIN else "not reproduced"
            unsure = f"; too few readings to tell it from {near} at {_percent(MARGIN)}"
        return text + unsure
    if cls == "not_reproduced":
        text = "not reproduced under any reading"
        if np.isfinite(bound):
            text = (
                f"not reproduced under any of {of}; passes under at most "
                f"{_percent(bound)} ({level}){unsure}"
            )
        best = _number_or_nan(row, "best_value")
        return text + (f"; best {best:.4g}" if np.isfinite(best) else "")
    return "-"


def across_short(row: Mapping) -> str:
    """:func:`across_text` in a table cell: ``all 60, fails <= 4.9 %``, ``50 % (37-63 %)``,
    ``none of 60, passes <= 4.9 %``, ``fit``; ``*`` when the sample cannot decide the
    class at :data:`MARGIN`."""
    cls = str(row.get("robustness", "") or "")
    n = _number_or_nan(row, "readings")
    bound = _number_or_nan(row, "class_bound")
    sure = str(row.get("class_sure", "True")) in ("True", "true", "1", "1.0")
    star = "" if sure else " *"
    if cls == "used_for_fit":
        return "fit"
    if cls == "robust" and np.isfinite(bound):
        return f"all {n:.0f}, fails <= {_percent(bound)}{star}"
    if cls == "not_reproduced" and np.isfinite(bound):
        return f"none of {n:.0f}, passes <= {_percent(bound)}{star}"
    if cls == "reading_dependent":
        low, high = _number_or_nan(row, "pass_share_low"), _number_or_nan(row, "pass_share_high")
        return f"{_percent(row.get('pass_share'))} ({_percent(low)}-{_percent(high)}){star}"
    return "-"


def classify(ds: xr.Dataset, space: ReadingSpace, claims: Sequence[Mapping]) -> pd.DataFrame:
    """Robustness class of every claim over the consistent readings (all kept readings x
    all claim-level variants): share passing, the deciding unknown of a
    reading-dependent claim, and the value closest to the paper (with its normalised
    residual)."""
    fit_of = space.fit_of_claim()
    rows = []
    for j, c in enumerate(claims):
        values = ds["value"].values[:, :, j]
        ok = ds["within"].values[:, :, j].astype(bool)
        share = float(ok.mean()) if ok.size else float("nan")
        residual = np.abs(values - c["paper_value"]) / max(c["tolerance"], 1e-300)
        finite = np.isfinite(residual)
        k = int(np.nanargmin(np.where(finite, residual, np.nan))) if finite.any() else None
        best_value = float(values.ravel()[k]) if k is not None else float("nan")
        best_residual = float(residual.ravel()[k]) if k is not None else float("nan")
        if c["tolerance"] == 0:  # qualitative: 0 (holds) or inf (does not)
            best_residual = 0.0 if ok.any() else 1.0
        if c["id"] in fit_of:
            cls = "used_for_fit"
        elif ok.all():
            cls = "robust"
        elif ok.any():
            cls = "reading_dependent"
        else:
            cls = "not_reproduced"
        deciding = _deciding(ok, ds, space) if cls == "reading_dependent" else ""
        low, high, fail_bound, pass_bound = (
            share_interval(ok) if cls != "used_for_fit" else (float("nan"),) * 4
        )
        bound, sure = class_bound(cls, low, high, fail_bound, pass_bound)
        rows.append(
            {
                "id": c["id"],
                "robustness": cls,
                "pass_share": share,
                "readings": int(ok.shape[0]),
                "pass_share_low": low,
                "pass_share_high": high,
                "class_bound": bound,
                "class_sure": sure,
                "deciding": deciding,
                "best_value": best_value,
                "best_residual": best_residual,
            }
        )
    return pd.DataFrame(rows)


def _is_flat(row: Mapping) -> bool:
    """Whether a claims table's row locates an optimum on a flat objective (its ``flat``
    column: :mod:`tennis_stroke.inference.optimum_claims`, the one rule of flatness)."""
    return str(row.get("flat", "")) in ("True", "true", "1", "1.0")


def evidence(table: pd.DataFrame, ds: xr.Dataset) -> pd.DataFrame:
    """Evidence class of every deviation of the default reading (status ``fail`` or
    ``known_deviation`` in ``table``): ``ill_conditioned`` for a claim that locates an
    optimum on a flat objective (``flat``, the rule every optimum claim is judged by:
    :mod:`tennis_stroke.inference.optimum_claims`), else by the readings it passes
    under."""
    passing = [i for i, s in enumerate(table["status"]) if s == "pass"]
    ids = list(ds["claim"].values)
    held = ds["within"].values[:, :, [ids.index(table["id"].iloc[i]) for i in passing]]
    all_default = held.all(axis=-1) if held.size else np.ones(ds["within"].shape[:2], bool)
    rows = []
    for _, row in table.iterrows():
        cls = ""
        if row["status"] in ("fail", "known_deviation"):
            j = ids.index(row["id"])
            ok = ds["within"].values[:, :, j].astype(bool)
            if _is_flat(row):
                cls = "ill_conditioned"
            elif ok.any():
                cls = "reading_choice" if (ok & all_default).any() else "paper_inconsistency"
            else:
                cls = "irreducible"
        rows.append({"id": row["id"], "evidence": cls})
    return pd.DataFrame(rows)


def annotate(
    table: pd.DataFrame,
    ds: xr.Dataset,
    space: ReadingSpace,
    claims: Sequence[Mapping],
) -> pd.DataFrame:
    """The claims table with the robustness and evidence columns (:data:`COLUMNS`)."""
    out = table.merge(classify(ds, space, claims), on="id", how="left")
    return out.merge(evidence(table, ds), on="id", how="left")
