"""A figure's claims measured from the files it is drawn from, and the inputs its strokes
share: what ``tennis-stroke whatif --figure`` prints beside the figure's path, so that a
scenario's answer is said in numbers, not only in a legend (issue 66, case 21).

The claims are the figure's on the report's page (:func:`~.registry.claim_figure`) that
read only its files, each measured as the claims job measures it on the maps
(:func:`tennis_stroke.inference.claims.measure`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from ..inference.claims import claim_files, measure
from ..io.netcdf import load_result
from .registry import Figure, claim_figure


def figure_claims(figure: Figure, claims: Sequence[Mapping]) -> list[Mapping]:
    """The declared ``claims`` about ``figure`` that read only the files it is drawn
    from, in their order."""
    drawn = set(figure.files)
    return [c for c in claims if claim_figure(c) == figure.key and set(claim_files(c)) <= drawn]


def figure_numbers(
    figure: Figure, claims: Sequence[Mapping], files: Mapping[str, str | Path]
) -> tuple[str, list[dict]]:
    """What ``figure`` says in numbers, drawn from ``files`` (result files by key): the
    inputs its strokes share (:meth:`~.registry.Figure.fixed_text`, plain spaces) and one
    row per claim of :func:`figure_claims`: ``id``, ``quantity``, ``value`` (ours, from
    these files), ``unit``, ``paper`` (the paper's value)."""
    datasets = {key: load_result(files[key]) for key in figure.files}
    try:
        shared = figure.fixed_text(datasets[figure.files[0]].attrs).replace("\u00a0", " ")
        rows = [
            {
                "id": c["id"],
                "quantity": c["quantity"],
                "value": measure(c["measure"], datasets),
                "unit": c["unit"],
                "paper": float(c["paper_value"]),
            }
            for c in figure_claims(figure, claims)
        ]
    finally:
        for ds in datasets.values():
            ds.close()
    return shared, rows
