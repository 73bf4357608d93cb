"""Where a figure's claims lie on its axes: the paper's value and ours of each
:class:`~tennis_stroke.replication.registry.Mark`, for the static figure (the paper's
value, a param of its job) and the page's interactive view (both).

Pure data: the Snakefile resolves the paper's marks at parse time without the plotting
libraries.
"""

from __future__ import annotations

from collections.abc import Mapping

from .registry import Figure


def mark_values(
    figure: Figure,
    claims: Mapping[str, Mapping],
    ours: Mapping[str, float] | None = None,
) -> list[dict]:
    """One entry per mark of ``figure``: ``claim``, ``axis``, ``paper`` and ``ours`` (its
    value; ``ours`` None without ``ours``), ``other_paper`` and ``other_ours`` (the other
    coordinate, None for a line).  ``claims``: the declared claims by id
    (``config/claims.yaml``); ``ours``: our values by claim id (the claims table).
    Raises KeyError naming a claim or measure argument that does not exist."""
    ours = ours or {}
    out = []
    for mark in figure.marks:
        claim = _claim(claims, mark.claim, figure.name)
        entry = {
            "claim": mark.claim,
            "axis": mark.axis,
            "paper": float(claim["paper_value"]),
            "ours": _ours(ours, mark.claim),
            "other_paper": None,
            "other_ours": None,
        }
        if mark.at is not None:
            measure = claim["measure"]
            if mark.at not in measure:
                raise KeyError(f"{figure.name}: the measure of {mark.claim} has no {mark.at!r}")
            entry["other_paper"] = entry["other_ours"] = float(measure[mark.at])
        elif mark.other is not None:
            entry["other_paper"] = float(_claim(claims, mark.other, figure.name)["paper_value"])
            entry["other_ours"] = _ours(ours, mark.other)
        out.append(entry)
    return out


def _claim(claims: Mapping[str, Mapping], claim_id: str, figure: str) -> Mapping:
    if claim_id not in claims:
        raise KeyError(f"{figure}: a mark names the claim {claim_id!r}, not in the claims")
    return claims[claim_id]


def _ours(ours: Mapping[str, float], claim_id: str) -> float | None:
    value = ours.get(claim_id)
    return None if value is None else float(value)
