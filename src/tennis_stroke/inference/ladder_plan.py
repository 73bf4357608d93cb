"""What the model ladder's config section means (``model_ladder``: its rungs, each a
model and solver settings over the config's), without running it: the workflow's config
check reads these without loading the solver (:mod:`tennis_stroke.inference.ladder`
runs the ladder)."""

from __future__ import annotations

from collections.abc import Mapping

from ..solver.settings import SolverSettings


class LadderError(ValueError):
    """The ladder section of the config is inconsistent (one line)."""


def check_ladder(ladder: Mapping) -> None:
    """Refuse a ladder whose rung names repeat or whose reference is not a rung."""
    names = [r["name"] for r in ladder["rungs"]]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise LadderError(f"model_ladder: rung name {repeated[0]!r} is used twice")
    if ladder["reference"] not in names:
        raise LadderError(
            f"model_ladder.reference {ladder['reference']!r} is not a rung "
            f"(rungs: {', '.join(names)})"
        )


def rung_model(model: Mapping[str, object], rung: Mapping) -> dict[str, object]:
    """The model overrides of ``rung`` over the config's ``model`` (a rung that names no
    restitution keeps the config's ball)."""
    out = {**model, "contact_model": rung["contact_model"]}
    if "restitution" in rung:
        out["restitution"] = float(rung["restitution"])
    return out


def rung_settings(solver: Mapping[str, object], rung: Mapping) -> SolverSettings:
    """The solver settings of ``rung`` over the config's ``solver`` section."""
    return SolverSettings(**{**solver, **rung.get("solver", {})})
