"""The reading space of the paper (``config/readings.yaml``), loaded and checked.

The file declares, before any fit, every choice the paper leaves open: the discrete
readings of the model (:data:`tennis_stroke.model.params.READINGS`), the instant each
quoted angle or angular velocity is read at, how the figures' curves are computed, and
the continuous unknowns with the range the paper supports.  It also fixes the fit sets,
the rule that picks the defaults, the rule that makes a reading consistent with the
paper and the sampling design of the robustness analysis.  :func:`load_reading_space`
validates it against its schema (``readings.schema.yaml``, package data beside this
module) and against the package (every choice, parameter and claim it names must
exist); each error is one line.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..experiments.specs import merged
from ..io.config_files import (
    ConfigFileError,
    dotted_key,
    load_yaml,
    non_finite_numbers,
    schema_errors,
)
from ..model.params import PARAMETERS, READINGS, ParameterError, resolve_params

#: The schema of the file, beside the workflow's config schema.
SCHEMA = Path(__file__).with_name("readings.schema.yaml")
_DEFS = load_yaml(SCHEMA)["$defs"]
#: The fit sets, in the order they are fitted: an enum of the schema, read from it.
FIT_SETS: tuple[str, ...] = tuple(_DEFS["fit_set"]["enum"])
MODEL_FIT, ELBOW_FIT = FIT_SETS
#: Continuous unknowns that are not model parameters but settings of one experiment.
EXPERIMENT_UNKNOWNS = ("table1_tau_F", "fig6_L1_max")


#: The claim-level readings: each kept reading is evaluated under all their combinations.
CLAIM_LEVEL = ("fig11_theta", "table1_omega", "figure_curves")
#: Result files whose curves depend on ``figure_curves``.
CURVE_FILES = ("fig4", "delay")
#: Config keys the robustness analysis sets itself for every reading (the workflow does
#: not pass them: changing them reruns none of its jobs).
MULTIVERSE_SETS = ("figure_curves",)


class ReadingSpaceError(ValueError):
    """``config/readings.yaml`` is malformed (message is one line, naming the key)."""


@dataclass(frozen=True)
class Unknown:
    """A continuous unknown: its declared ``range`` (and wider ``exploratory`` range) in
    ``unit``, fitted and sampled in log or linear ``scale``."""

    name: str
    unit: str
    low: float
    high: float
    scale: str
    exploratory: tuple[float, float] | None = None

    def to_unit(self, value, exploratory: bool = False):
        """The fit variable in [0, 1] of ``value`` over the (exploratory) range."""
        lo, hi = self.bounds(exploratory)
        f = np.log if self.scale == "log" else np.asarray
        return (f(value) - f(lo)) / (f(hi) - f(lo))

    def from_unit(self, u, exploratory: bool = False):
        """The value at the fit variable ``u`` in [0, 1] (inverse of :meth:`to_unit`)."""
        lo, hi = self.bounds(exploratory)
        u = np.asarray(u, dtype=float)
        if self.scale == "log":
            return np.exp(np.log(lo) + u * (np.log(hi) - np.log(lo)))
        return lo + u * (hi - lo)

    def bounds(self, exploratory: bool = False) -> tuple[float, float]:
        """The declared range, or the exploratory one (the declared one if none)."""
        if exploratory and self.exploratory is not None:
            return self.exploratory
        return (self.low, self.high)


@dataclass(frozen=True)
class FitSet:
    """Claims fitted together, the discrete readings enumerated and the unknowns fitted."""

    name: str
    claims: tuple[str, ...]
    discrete: tuple[str, ...]
    unknowns: tuple[str, ...]
    starts: int
    given: str | None = None


@dataclass(frozen=True)
class ReadingSpace:
    """The validated declaration (``raw``: the file as read)."""

    raw: dict
    discrete: dict[str, tuple[str, ...]]
    continuous: dict[str, Unknown]
    fits: dict[str, FitSet]

    def fitted(self) -> frozenset[str]:
        """The model parameters and readings whose default is fitted (a fit set's
        unknowns and discrete readings that are model readings): the one declaration
        ``tennis-stroke params``, the report and the explorer mark as fitted."""
        names = {n for f in self.fits.values() for n in (*f.unknowns, *f.discrete)}
        return frozenset(n for n in names if n in PARAMETERS or n in READINGS)

    def fit_of_claim(self) -> dict[str, str]:
        """Claim id -> the name of the fit set that uses it."""
        return {c: f.name for f in self.fits.values() for c in f.claims}

    def quoting_of_claim(self) -> dict[str, str]:
        """Claim id -> the quoting group (``fig4_theta`` ...) that decides its variable."""
        return {c: g for g, spec in self.raw["quoting"].items() for c in spec.get("claims", [])}

    def at_resolution(self, config: Mapping) -> dict:
        """The workflow ``config`` at the multiverse's resolution: its ``angle_maps`` and
        ``mass_length`` merged over their sections, ``fig7_tau`` as Fig. 7's ``tau``
        (a config pruned to what one job reads may lack that section)."""
        resolution = dict(self.raw["multiverse"]["resolution"])
        fig7_tau = resolution.pop("fig7_tau", None)
        cfg = merged(config, resolution)
        if fig7_tau is not None and "fig7" in cfg.get("torque_delay", {}):
            cfg["torque_delay"]["fig7"]["tau"] = dict(fig7_tau)
        return cfg


def _check(condition: bool, message: str) -> None:
    if not condition:
        raise ReadingSpaceError(message)


def load_reading_space(
    path: str | Path = "config/readings.yaml",
    claim_ids: Iterable[str] | None = None,
    schema: str | Path = SCHEMA,
) -> ReadingSpace:
    """Read, validate and cross-check the reading space.

    Parameters
    ----------
    path : path of ``readings.yaml``
    claim_ids : ids of ``config/claims.yaml`` (when given, every claim named must exist)
    schema : the JSON schema

    Raises
    ------
    ReadingSpaceError
        The first problem, one line naming the key.
    """
    try:
        raw = load_yaml(path)
    except ConfigFileError as exc:
        raise ReadingSpaceError(str(exc)) from None
    errors = schema_errors(raw, load_yaml(schema), "readings")
    if errors:
        raise ReadingSpaceError(errors[0])
    for parts, value in non_finite_numbers(raw):
        raise ReadingSpaceError(
            f"readings key {dotted_key(parts)!r}: {value} is not a finite number (rule: finite)"
        )

    discrete = _discrete(raw)
    continuous = _continuous(raw)
    fits = _fit_sets(raw, discrete, continuous)
    if claim_ids is not None:
        _check_claims(raw, fits, set(claim_ids))
    return ReadingSpace(raw, discrete, continuous, fits)


def _discrete(raw: dict) -> dict[str, tuple[str, ...]]:
    """The discrete readings: the model's (each a known reading with known choices), the
    quoting instants' and the figure curves'."""
    discrete: dict[str, tuple[str, ...]] = {}
    for name, spec in raw["model"].items():
        _check(name in READINGS, f"readings key 'model.{name}': not a model reading")
        bad = sorted(set(spec["choices"]) - set(READINGS[name].choices))
        _check(not bad, f"readings key 'model.{name}': unknown choice {bad[:1]}")
        discrete[name] = tuple(spec["choices"])
    for name, spec in raw["quoting"].items():  # the schema checks the instants
        discrete[name] = tuple(spec["choices"])
    discrete["figure_curves"] = tuple(raw["figure_curves"]["choices"])
    return discrete


def _continuous(raw: dict) -> dict[str, Unknown]:
    """The continuous unknowns, each range checked: ordered, finite, positive on a log
    scale, inside the exploratory range, and within the parameter's bounds."""
    continuous: dict[str, Unknown] = {}
    for name, spec in raw["continuous"].items():
        lo, hi = (float(x) for x in spec["range"])
        _check(lo < hi, f"readings key 'continuous.{name}.range': low must be below high")
        explo = tuple(float(x) for x in spec["exploratory"]) if "exploratory" in spec else None
        if explo is not None:
            _check(
                explo[0] <= lo and hi <= explo[1],
                f"readings key 'continuous.{name}.exploratory': must contain the range",
            )
        _check(
            math.isfinite(lo) and math.isfinite(hi),
            f"readings key 'continuous.{name}.range': must be finite",
        )
        if spec["scale"] == "log":
            _check(lo > 0, f"readings key 'continuous.{name}': a log scale needs a positive range")
        if name in PARAMETERS:
            for value in (lo, hi, *(explo or ())):
                try:
                    resolve_params({name: value})
                except ParameterError as exc:
                    raise ReadingSpaceError(f"readings key 'continuous.{name}': {exc}") from None
        else:
            _check(
                name in EXPERIMENT_UNKNOWNS,
                f"readings key 'continuous.{name}': neither a model parameter nor one of "
                f"{', '.join(EXPERIMENT_UNKNOWNS)}",
            )
        continuous[name] = Unknown(name, spec["unit"], lo, hi, spec["scale"], explo)
    return continuous


def _fit_sets(raw: dict, discrete: Mapping, continuous: Mapping) -> dict[str, FitSet]:
    """The fit sets of :data:`FIT_SETS`, each naming known readings and unknowns and,
    through ``given``, an earlier fit."""
    fits: dict[str, FitSet] = {}
    for name in FIT_SETS:
        spec = raw["fits"][name]
        for d in spec["discrete"]:
            _check(d in discrete, f"readings key 'fits.{name}.discrete': unknown reading {d!r}")
        for u in spec["unknowns"]:
            _check(u in continuous, f"readings key 'fits.{name}.unknowns': unknown {u!r}")
        given = spec.get("given")
        _check(
            given is None or given in fits,
            f"readings key 'fits.{name}.given': must name an earlier fit",
        )
        fits[name] = FitSet(
            name,
            tuple(spec["claims"]),
            tuple(spec["discrete"]),
            tuple(spec["unknowns"]),
            int(spec["starts"]),
            given,
        )
    return fits


def _check_claims(raw: dict, fits: Mapping[str, FitSet], known: set[str]) -> None:
    """Every claim the file names is a claim of ``config/claims.yaml``."""
    named = [
        *(("fits." + f.name, c) for f in fits.values() for c in f.claims),
        *(("quoting." + g, c) for g, s in raw["quoting"].items() for c in s.get("claims", [])),
        *(("figure_curves", c) for c in raw["figure_curves"].get("claims", [])),
        *(
            (f"continuous.{u}", c)
            for u, s in raw["continuous"].items()
            for c in s.get("claims", [])
        ),
    ]
    for where, claim in named:
        _check(claim in known, f"readings key {where!r}: unknown claim {claim!r}")


def literal_rank(name: str, choice: str) -> int:
    """0 for a reading's literal choice (the paper word for word), else 1."""
    reading = READINGS.get(name)
    return 0 if reading is not None and reading.literal == choice else 1


def claims_and_readings(claims_path, readings_path):
    """The declared claims and the reading space (``config/claims.yaml``,
    ``config/readings.yaml``) of an inference job, checked against each other."""
    from .claims import load_claims

    claims = load_claims(claims_path)
    return claims, load_reading_space(readings_path, [c["id"] for c in claims])
