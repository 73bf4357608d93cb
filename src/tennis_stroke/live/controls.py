"""The live explorer's controls (``tennis-stroke explore``): each with its units, bounds
and the paper's value, generated from the model's parameters and readings, and the
configuration a setting of them gives.

A setting is a scenario's overrides (:mod:`tennis_stroke.pipeline.scenarios`): the
paper's configuration (``config/config.yaml``) with ``model``, ``solver``,
``angle_maps`` and ``torque_delay`` values changed, so what a reader finds can be saved
as a scenario and computed whole by the workflow (:mod:`tennis_stroke.live.compute`
computes each view at it).
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass

import numpy as np

from ..experiments.specs import merged
from ..io.config_files import value_at
from ..model.listing import origin
from ..model.params import CHOICES, INITIAL_ANGLES, PARAMETERS
from ..solver.settings import METHOD_IDS, SolverSettings
from .compute import FIGURES

#: The solver tolerances offered (rtol = atol), loosest first; the paper's 5e-8 among them.
TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7, 5e-8, 1e-8, 1e-9, 1e-10)


class ExplorerError(ValueError):
    """A setting the explorer cannot compute (one line)."""


@dataclass(frozen=True)
class Control:
    """One control: the dotted config ``key`` it sets, its label and unit, its value in
    the paper's configuration (``paper``) and where that value comes from (``origin``,
    :data:`tennis_stroke.model.listing.ORIGINS`: the paper, fitted, derived, ours), its
    bounds (None: unbounded; a number control refuses what is outside), or its
    ``choices``."""

    key: str
    label: str
    unit: str
    paper: float | str
    low: float | None = None
    high: float | None = None
    choices: tuple[str, ...] = ()
    note: str = ""
    origin: str = "paper"


def _control_step(value: float) -> float:
    """About a hundredth of ``value``, a power of ten (the margin above an exclusive
    lower bound)."""
    return 10.0 ** np.floor(np.log10(abs(value)) - 2) if value else 0.01


def _bounds(spec) -> tuple[float | None, float | None]:
    """A parameter's bounds for an input that refuses what is outside them: an exclusive
    lower bound becomes the smallest step above it."""
    low = spec.lower
    if low is not None and spec.strict:
        low = low + _control_step(spec.default or 1.0)
    return low, spec.upper


#: Parameters a view sets itself (their controls are the figures' values below), and
#: those derived from others (shown, not set: their reading is the control).
_SET_BY_VIEWS = ("L1",)


def controls(config: Mapping, figure: str, fitted: Collection[str] = ()) -> list[Control]:
    """Every control, in the order the page shows them: the model's parameters (less
    the derived ones and ``L1``, which each figure sets), the readings and model
    options, the solver, then the figures' own values (the map's ``L1``; Fig. 9's arm,
    initial angles and wrist torque).  ``fitted``: the names whose default is fitted
    (their ``origin``)."""
    out = []
    for name, spec in PARAMETERS.items():
        if spec.derived or name in _SET_BY_VIEWS:
            continue
        low, high = _bounds(spec)
        note = "Figs. 2-3; Fig. 9 sets its own" if name in ("C2", "tau") else ""
        out.append(
            Control(
                f"model.{name}",
                name,
                spec.unit,
                spec.default,
                low,
                high,
                note=note or spec.description,
                origin=origin(name, fitted),
            )
        )
    for name, reading in CHOICES.items():
        out.append(
            Control(
                f"model.{name}",
                name,
                "",
                reading.default,
                choices=reading.choices,
                note=f"{reading.description} (the paper's words: {reading.literal})",
                origin=origin(name, fitted),
            )
        )
    solver = SolverSettings(**config["solver"])
    out.append(
        Control(
            "solver.method", "method", "", solver.method, choices=tuple(METHOD_IDS), origin="ours"
        )
    )
    out.append(
        Control(
            "solver.rtol",
            "rtol = atol",
            "1",
            f"{solver.rtol:g}",
            choices=tuple(f"{t:g}" for t in TOLERANCES),
            origin="ours",
        )
    )
    fig, index = FIGURES[figure]
    l1 = PARAMETERS["L1"]
    out.append(
        Control(
            f"angle_maps.L1.{index}",
            f"L1 of the {fig} map",
            l1.unit,
            value_at(config, f"angle_maps.L1.{index}"),
            *_bounds(l1),
            note=l1.description,
        )
    )
    theta0, delta0 = INITIAL_ANGLES["theta0"], INITIAL_ANGLES["delta0"]
    for key, label, unit, low, high in (  # values the paper states (Sec. V)
        ("torque_delay.L1", "L1 of Fig. 9", "m", *_bounds(l1)),
        ("torque_delay.theta0", "theta0 of Fig. 9", theta0.unit, *_bounds(theta0)),
        ("torque_delay.base_stroke.delta0", "delta0 of Fig. 9", delta0.unit, *_bounds(delta0)),
        ("torque_delay.base_stroke.C2", "C2 of Figs. 8-14", "N m", None, None),
    ):
        out.append(Control(key, label, unit, value_at(config, key), low, high))
    return out


def overrides(config: Mapping, values: Mapping[str, object]) -> dict:
    """A scenario's overrides (nested, in the shape of the config) from control values
    by dotted key, keeping only those that differ from ``config``'s; ``solver.rtol``
    sets ``atol`` too."""
    out: dict = {}
    for key, value in values.items():
        if key == "solver.rtol":
            value = float(value)
        paper = config_value(config, key)
        if _same(paper, value):
            if key != "solver.rtol" or _same(config_value(config, "solver.atol"), value):
                continue
        parts = key.split(".")
        if parts[0] == "angle_maps" and parts[1] == "L1":  # a list: set whole
            current = list(value_at(config, "angle_maps.L1"))
            base = out.setdefault("angle_maps", {}).get("L1", current)
            base[int(parts[2])] = float(value)
            out["angle_maps"]["L1"] = base
            continue
        node = out
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = value
        if key == "solver.rtol":
            node["atol"] = value
    return out


def config_value(config: Mapping, key: str):
    """The value a configuration gives the control ``key`` (a model parameter's or
    reading's default where the config leaves it out)."""
    section, _, name = key.partition(".")
    if section == "model":
        model = config.get("model") or {}
        if name in model:
            return model[name]
        return PARAMETERS[name].default if name in PARAMETERS else CHOICES[name].default
    return value_at(config, key)


def _same(a, b) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return str(a) == str(b)
    return bool(np.isclose(float(a), float(b), rtol=1e-12, atol=0.0))


def configuration(paper: Mapping, values: Mapping[str, object]) -> dict:
    """The configuration at control values: the paper's with :func:`overrides`."""
    return merged(paper, overrides(paper, values))


#: A number as a person types it: an optional sign, digits with a decimal point or a
#: decimal comma, an optional exponent ("7800", "-0.5", "0,35", ".3", "1e-5", "2E3").
_NUMBER = re.compile(r"[-+]?(?:\d+(?:[.,]\d*)?|[.,]\d+)(?:[eE][-+]?\d+)?")
#: A comma that may separate thousands ("7,800"): read neither way.
_THOUSANDS = re.compile(r"[-+]?[1-9]\d{0,2},\d{3}")


def read_number(text: str) -> float:
    """The number a person typed in a field (surrounding spaces and a typographic minus
    allowed, a decimal comma read as a point); a ValueError naming why for anything
    else, and for a comma that may separate thousands ("7,800")."""
    if not isinstance(text, str):
        raise ValueError(f"{text!r} is not a number")
    typed = text.strip().replace("\u2212", "-")
    if not _NUMBER.fullmatch(typed):
        raise ValueError(f"{text.strip()!r} is not a number" if typed else "no value")
    if _THOUSANDS.fullmatch(typed):
        raise ValueError(f"{typed!r} is ambiguous: write it without the comma or with a point")
    value = float(typed.replace(",", "."))
    if not np.isfinite(value):
        raise ValueError(f"{typed!r} is not a finite number")
    return value


def number_text(value: float) -> str:
    """A number control's text: the shortest that reads back as ``value``."""
    return repr(float(value)).removesuffix(".0")


def refusal(control: Control, value) -> str | None:
    """Why ``value`` cannot be ``control``'s (a one-line reason), or None: a choice must
    be one of the control's, a number finite and within its bounds.  The page's widgets
    offer no other, but a page can send any value (a select's ``null`` too)."""
    if value is None:
        return "no value"
    if control.choices:
        if not isinstance(value, str) or value not in control.choices:
            return f"{value!r} is not one of {', '.join(control.choices)}"
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or not np.isfinite(value):
        return f"{value!r} is not a finite number"
    if (control.low is not None and value < control.low) or (
        control.high is not None and value > control.high
    ):
        return f"{number_text(value)} is outside [{control.low}, {control.high}]"
    return None
