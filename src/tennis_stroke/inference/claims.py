"""The paper's claims: what each one is and how its value is measured on the result files.

``config/claims.yaml`` lists every claim: ``id``, ``source``, ``quantity``, ``unit``,
``paper_value``, ``tolerance`` (absolute, in the claim's unit), ``expectation``
(``reproduce`` or ``known_deviation`` with a ``reason``) and ``measure``: how to compute
the reproduced value from the results, either a variable of a file
(``{file, var, sel, abs}``) or a named measurement of :data:`MEASUREMENTS`
(``{function, file, ...}``); no other key.  The ``unit`` is the one the measure gives
(:func:`measure_unit`: the file's variable's, or the measurement's).  Qualitative claims
are measurements returning 1 (true) or 0 (false), unit ``"1"``, with ``paper_value`` 1
or 0 and ``tolerance: 0``.

:func:`measure` computes a claim's value from the files (:func:`measure_stacks`: under
many readings at once), :func:`within` compares it with
the paper's; :func:`tennis_stroke.replication.claims.evaluate` makes the table written to
``results/claims.csv``.

:func:`claim_errors` checks a claims file before any job runs (the workflow calls it when
it parses the Snakefile): a bad entry is one line naming the claim, not a failure of the
``claims`` job after every simulation.
"""

from __future__ import annotations

import inspect
import math
import typing
from collections.abc import Collection, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..experiments.specs import EXPERIMENTS, PAPER_RESULTS
from ..io.config_files import (
    ConfigFileError,
    did_you_mean,
    dotted_key,
    load_yaml,
    non_finite_numbers,
)
from ..io.units import unit_of
from .measures import (
    AXIS_TOLERANCE,
    MEASUREMENTS,
    QUALITATIVE_UNIT,
    OnAxis,
    Stack,
    measurement_unit,
    off_axis,
    per_reading,
    pick,
)

if TYPE_CHECKING:  # its annotations only: the planning checks the claims without xarray
    import xarray as xr

EXPECTATIONS = ("reproduce", "known_deviation")
#: The fields every claim has.
REQUIRED = (
    "id",
    "source",
    "quantity",
    "unit",
    "paper_value",
    "tolerance",
    "expectation",
    "measure",
)
#: The fields a claim may have besides :data:`REQUIRED` (a known deviation's reason).
OPTIONAL = ("reason",)
#: The keys of a measure that reads one variable of a file (no ``function``).
VARIABLE_MEASURE = ("file", "var", "sel", "abs")


class ClaimError(ValueError):
    """A claim definition is malformed (message is one line)."""


def claim_files(claim: Mapping) -> list[str]:
    """The result files a claim reads (keys of :data:`PAPER_RESULTS`), in its order."""
    names = claim["measure"]["file"]
    return list(names) if isinstance(names, list) else [names]


def within(value, paper, tolerance):
    """True where ``value`` is finite and within ``tolerance`` of ``paper`` (the rule of
    every claim; a rounding margin of 1e-12)."""
    value = np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.isfinite(value) & (np.abs(value - paper) <= np.asarray(tolerance) + 1e-12)


#: How a searched value is compared with the same measurement on the full maps
#: (tennis_stroke.inference.validation, and results/claims.csv's map_cause).
#: Agreement asked of a targeted value: within this share of the claim's tolerance of the
#: map's (issue 21); a qualitative claim must give the same answer.
AGREEMENT = 0.1


def difference(targeted, mapped, tolerance) -> np.ndarray:
    """|targeted - map| in tolerances (a qualitative claim, tolerance 0: 0 if the same
    answer, else 1; NaN where either is missing)."""
    t, m = np.asarray(targeted, float), np.asarray(mapped, float)
    tol = np.asarray(tolerance, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(tol > 0, np.abs(t - m) / np.where(tol > 0, tol, 1.0), np.abs(t - m))


def agrees(targeted, mapped, tolerance) -> np.ndarray:
    """Whether a targeted value agrees with the map's (:data:`AGREEMENT`)."""
    d = difference(targeted, mapped, tolerance)
    with np.errstate(invalid="ignore"):
        return np.where(np.asarray(tolerance) > 0, d <= AGREEMENT + 1e-12, d == 0)


#: Measurements that read a grid point of a map (its coordinate ``coord``), and the one
#: that reads the midpoint between two grid rows (``C2``): their map value is limited by
#: the grid, to half its step.
GRID_POINT = {"optimum": None, "minimum": None, "delay_threshold": "C2"}


def grid_half_step(claim: Mapping, maps: Mapping[str, xr.Dataset]) -> float:
    """Half the step of the map grid a claim's map value is read on (its resolution, in
    the claim's unit; 0 where the value is refined between grid points or is no
    location)."""
    spec = claim["measure"]
    name = spec.get("function")
    if name not in GRID_POINT:
        return 0.0
    coord = GRID_POINT[name] or spec["coord"]
    values = np.asarray(maps[spec["file"]][coord].values, float)
    return 0.5 * float(np.max(np.abs(np.diff(values)))) if values.size > 1 else 0.0


def cause(targeted, mapped, tolerance, half_step) -> np.ndarray:
    """Why a targeted value differs from the map's: ``agrees`` (:func:`agrees`),
    ``grid_step`` (the map's value is a grid point, and the two differ by no more than
    half its step plus the agreement: the targeted value is the finer estimate), else
    ``unexplained``."""
    ok = agrees(targeted, mapped, tolerance)
    gap = np.abs(np.asarray(targeted, float) - np.asarray(mapped, float))
    with np.errstate(invalid="ignore"):
        grid = (np.asarray(half_step) > 0) & (
            gap <= np.asarray(half_step) + AGREEMENT * np.asarray(tolerance) + 1e-12
        )
    return np.where(ok, "agrees", np.where(grid, "grid_step", "unexplained"))


def measure(spec: Mapping, files: Mapping[str, xr.Dataset]) -> float:
    """The value a claim's ``measure`` computes from the result files (by key) of one
    reading: :func:`measure_stacks` of that one reading."""
    names = spec["file"] if isinstance(spec["file"], list) else [spec["file"]]
    return float(measure_stacks(spec, {n: Stack([files[n]]) for n in names})[0])


def measure_stacks(spec: Mapping, files: Mapping[str, Stack]) -> np.ndarray:
    """The values a claim's ``measure`` computes from the result files (by key) under
    ``n`` readings, each file a :class:`~tennis_stroke.inference.measures.Stack`: one
    value per reading."""
    spec = dict(spec)
    if "function" in spec:
        name = spec.pop("function")
        fn = MEASUREMENTS.get(name)
        if fn is None:
            raise ClaimError(f"unknown measurement {name!r}")
        names = spec.pop("file")
        names = names if isinstance(names, list) else [names]
        return np.asarray(fn(*(files[n] for n in names), **spec), dtype=float)
    stack, var = files[spec["file"]], spec["var"]
    value, dims = stack[var], list(stack.dims(var))
    if "sel" in spec:
        for dim, index in selection(stack, var, spec["sel"], spec["file"]).items():
            value = pick(value, 1 + dims.index(dim), index)
            dims.remove(dim)
    value = per_reading(value).astype(float)
    return np.abs(value) if spec.get("abs") else value


#: How close a ``sel`` value must be to a coordinate value (relative to the axis' span,
#: or absolute on a one-point axis): what a decimal number in YAML can say of it.
SEL_TOLERANCE = AXIS_TOLERANCE


def selection(stack: Stack, var: str, sel: Mapping, file: str = "") -> dict[str, np.ndarray]:
    """A claim's ``sel`` as positions along the dimensions of variable ``var``, one per
    reading of ``stack``: an integer is a position, a decimal number (``delta0: 52.5``) a
    value of the dimension's coordinate, which must hold it (within
    :data:`SEL_TOLERANCE`); raises :class:`ClaimError` naming the nearest value
    otherwise."""
    out = {}
    for dim, value in sel.items():
        if dim not in stack.dims(var):
            raise ClaimError(f"{file}: {var} has no dimension {dim!r}")
        if isinstance(value, int):
            out[dim] = np.full(stack.n, value)
            continue
        if dim not in stack:
            raise ClaimError(f"{file}: dimension {dim!r} has no coordinate to find {value} in")
        axis = np.asarray(stack[dim], float).reshape(stack.n, -1)
        span = np.ptp(axis, axis=1) if axis.shape[1] > 1 else np.ones(stack.n)
        i = np.argmin(np.abs(axis - value), axis=1)
        nearest = axis[np.arange(stack.n), i]
        far = np.abs(nearest - value) > SEL_TOLERANCE * np.maximum(span, 1.0)
        if far.any():
            shown = nearest[np.argmax(far)]
            raise ClaimError(f"{file}: no {dim} = {value:g} on its axis (nearest {shown:g})")
        out[dim] = i
    return out


def _number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _bare(annotation):
    """A parameter's type without its ``Annotated`` metadata (:class:`OnAxis`)."""
    if typing.get_origin(annotation) is typing.Annotated:
        return typing.get_args(annotation)[0]
    return annotation


def axis_arguments(name: str) -> dict[str, str]:
    """The arguments of measurement ``name`` that are values of a coordinate of its file
    (annotated :class:`~tennis_stroke.inference.measures.OnAxis`): argument ->
    coordinate."""
    signature = inspect.signature(MEASUREMENTS[name], eval_str=True)
    return {
        key: meta.coord
        for key, parameter in signature.parameters.items()
        if typing.get_origin(parameter.annotation) is typing.Annotated
        for meta in parameter.annotation.__metadata__
        if isinstance(meta, OnAxis)
    }


def _fits(value, annotation) -> bool:
    """True if an argument ``value`` fits a measurement parameter's ``annotation``."""
    annotation = _bare(annotation)
    if typing.get_origin(annotation) is typing.Literal:
        return value in typing.get_args(annotation) and not isinstance(value, bool)
    if annotation is float:
        return _number(value)
    if annotation is int:
        return isinstance(value, int) and not isinstance(value, bool)
    if annotation in (str, bool):
        return isinstance(value, annotation)
    return True


def _argument_errors(name: str, n_files: int, args: Mapping) -> Iterator[str]:
    """Problems of calling measurement ``name`` with ``n_files`` datasets and ``args``."""
    signature = inspect.signature(MEASUREMENTS[name], eval_str=True)
    try:
        bound = signature.bind(*[None] * n_files, **args)
    except TypeError as exc:
        yield f"measurement {name!r} with {n_files} file(s) and arguments {dict(args)}: {exc}"
        return
    for key, value in bound.arguments.items():
        annotation = _bare(signature.parameters[key].annotation)
        if key in args and annotation is Stack:
            yield f"measurement {name!r}: {key!r} is a file (give it in 'file'), not an argument"
        elif key in args and not _fits(value, annotation):
            wanted = (
                f"one of {typing.get_args(annotation)}"
                if typing.get_origin(annotation) is typing.Literal
                else f"a {annotation.__name__}"
            )
            yield f"measurement {name!r}: argument {key!r} = {value!r} is not {wanted}"
        elif key not in args and annotation is not Stack:
            yield f"measurement {name!r}: {key!r} is an argument, not a file"


def _measure_errors(spec, files: Collection[str]) -> Iterator[str]:
    if not isinstance(spec, Mapping):
        yield f"measure must be a mapping, got {spec!r}"
        return
    names = spec.get("file", [])
    names = names if isinstance(names, list) else [names]
    if not names:
        yield "measure lacks 'file' (the result file it reads)"
    for key in names:
        if key not in files:
            yield f"unknown result file {key!r} (known: {', '.join(sorted(files))})"
    if "function" in spec:
        name = spec["function"]
        if not isinstance(name, str) or name not in MEASUREMENTS:
            yield f"unknown measurement {name!r} (known: {', '.join(sorted(MEASUREMENTS))})"
            return
        args = {k: v for k, v in spec.items() if k not in ("function", "file")}
        yield from _argument_errors(name, len(names), args)
        return
    unknown = sorted(set(spec) - set(VARIABLE_MEASURE))
    if unknown:
        yield (
            f"measure has unknown keys {unknown} (a variable of a file takes "
            f"{', '.join(VARIABLE_MEASURE)}; a named measurement takes 'function')"
        )
    var = spec.get("var")
    if not isinstance(var, str):
        yield "measure lacks 'var' (the variable of the file) or 'function'"
    elif len(names) == 1 and names[0] in EXPERIMENTS and var not in EXPERIMENTS[names[0]].variables:
        shown = ", ".join(sorted(EXPERIMENTS[names[0]].variables))
        yield f"file {names[0]!r} has no variable {var!r} (its variables: {shown})"
    if len(names) != 1:
        yield f"a variable is read from one file, got {names}"
    sel = spec.get("sel", {})
    if not isinstance(sel, Mapping) or not all(
        isinstance(i, int | float) and not isinstance(i, bool) and np.isfinite(i)
        for i in sel.values()
    ):
        yield (
            "sel must map dimensions to integer positions or coordinate values "
            f"(a decimal number: delta0: 52.5), got {sel!r}"
        )
    if not isinstance(spec.get("abs", False), bool):
        yield f"abs must be true or false, got {spec['abs']!r}"


def measure_unit(spec: Mapping) -> str | None:
    """The unit of the value a claim's ``measure`` gives (checked by the claims' check):
    its variable's in the one table of units, or its measurement's
    (:func:`~tennis_stroke.inference.measures.measurement_unit`); None if unknown."""
    if "function" in spec:
        args = {k: v for k, v in spec.items() if k not in ("function", "file")}
        return measurement_unit(spec["function"], args)
    try:
        return unit_of(spec.get("var"))
    except (KeyError, TypeError):  # TypeError: a var that is not a name
        return None


def _claim_errors(claim, files: Collection[str]) -> Iterator[str]:
    """Problems of one claim (without its id)."""
    for key in REQUIRED:
        if key not in claim:
            yield f"lacks {key!r}"
    for key in sorted(set(claim) - {*REQUIRED, *OPTIONAL}, key=str):
        known = (*REQUIRED, *OPTIONAL)
        yield (
            f"unknown key {key!r}{did_you_mean(str(key), known)} (a claim takes {', '.join(known)})"
        )
    numbers = {k: v for k, v in claim.items() if k not in ("paper_value", "tolerance")}
    for parts, value in non_finite_numbers(numbers):  # paper_value's, tolerance's below
        yield f"{dotted_key(parts)} must be a finite number, got {value}"
    if claim.get("expectation", EXPECTATIONS[0]) not in EXPECTATIONS:
        yield f"expectation must be one of {EXPECTATIONS}, got {claim['expectation']!r}"
    if claim.get("expectation") == "known_deviation" and not claim.get("reason"):
        yield "a known deviation needs a reason"
    for key in ("paper_value", "tolerance"):
        if key in claim and not (_number(claim[key]) and math.isfinite(claim[key])):
            yield f"{key} must be a finite number, got {claim[key]!r}"
    tolerance = claim.get("tolerance")
    if _number(tolerance) and tolerance < 0:
        yield f"tolerance must be >= 0, got {tolerance}"
    elif tolerance == 0 and claim.get("unit") != QUALITATIVE_UNIT:
        yield (
            f"tolerance must be > 0 (0 only for a qualitative claim, unit "
            f"{QUALITATIVE_UNIT!r}; unit here {claim.get('unit')!r})"
        )
    if "measure" in claim:
        measure_errors = list(_measure_errors(claim["measure"], files))
        yield from measure_errors
        unit = None if measure_errors else measure_unit(claim["measure"])
        if unit is not None and "unit" in claim and str(claim["unit"]) != unit:
            yield (
                f"unit {claim['unit']!r} is not the unit its measure gives, {unit!r} (a "
                "claim's value is compared in its measure's unit)"
            )
        if unit == QUALITATIVE_UNIT:
            if claim.get("paper_value") not in (0, 1) or isinstance(claim.get("paper_value"), bool):
                yield (
                    "a qualitative claim (its measure gives 1, true, or 0, false) has "
                    f"paper_value 1 or 0, got {claim.get('paper_value')!r}"
                )
            if claim.get("tolerance") != 0:
                yield (
                    "a qualitative claim (its measure gives 1 or 0) has tolerance 0, got "
                    f"{claim.get('tolerance')!r}"
                )


def claim_errors(path: str | Path, files: Collection[str] = tuple(PAPER_RESULTS)) -> list[str]:
    """Every problem of the claims file ``path`` as one-line messages naming the file and
    the claim (empty: the claims are good).

    Checked without any result file: the required fields and no other (:data:`OPTIONAL`
    aside), unique ids, the expectation (a known deviation with its reason), finite
    numbers, tolerances (> 0; 0 only for a qualitative claim, unit ``"1"``), the unit
    (the one the measure gives, :func:`measure_unit`), a qualitative claim's paper value
    (1 or 0) and tolerance (0), the result files (``files``: the keys a measure may
    name, by default those of :data:`~tennis_stroke.experiments.specs.PAPER_RESULTS`),
    and the measurement: a function of :data:`MEASUREMENTS` called with its files and
    arguments as its signature says (names, count, annotated types and choices), or one
    variable of one file.
    """
    try:
        raw = load_yaml(path)
    except ConfigFileError as exc:
        return [str(exc)]
    return _claims_file_errors(raw, path, files)


def _claims_file_errors(raw: object, path: str | Path, files: Collection[str]) -> list[str]:
    """:func:`claim_errors` of the contents ``raw`` of the claims file ``path``."""
    claims = raw.get("claims") if isinstance(raw, Mapping) else None
    if not isinstance(claims, list) or not claims:
        return [f"{path}: no list of claims (key 'claims')"]
    errors, seen = [], set()
    for i, claim in enumerate(claims):
        if not isinstance(claim, Mapping):
            errors.append(f"{path}: claim {i + 1} is not a mapping: {claim!r}")
            continue
        cid = claim.get("id")
        if not isinstance(cid, str) or not cid:
            if "id" in claim:
                errors.append(f"{path}: claim {i + 1}: id must be a name, got {cid!r}")
            cid = f"number {i + 1}"
        elif cid in seen:
            errors.append(f"{path}: duplicate claim id {cid!r}")
        seen.add(cid)
        errors.extend(f"{path}: claim {cid!r}: {e}" for e in _claim_errors(claim, files))
    return errors


def claim_axis_errors(
    claims: list[Mapping], config: Mapping, path: str | Path, where: str = ""
) -> list[str]:
    """The claims (checked by :func:`claim_errors`) whose measurement reads a value of a
    file's coordinate (an :class:`~tennis_stroke.inference.measures.OnAxis` argument,
    ``theta0: 120.0``) beyond the ends of that file's axis under the workflow
    ``config`` (its grid in the table of experiments,
    :meth:`~tennis_stroke.experiments.specs.Experiment.axis_ends`): one line each naming
    the claim, the argument and the axis (``where``: which configuration, said after
    it).  The measurement refuses such a value too when it reads the file; a value
    between two grid points is read at the nearer one."""
    errors = []
    for claim in claims:
        spec = claim["measure"]
        if "function" not in spec:
            continue
        for argument, coord in axis_arguments(spec["function"]).items():
            value = spec[argument]
            for name in claim_files(claim):
                ends = EXPERIMENTS[name].axis_ends(config, coord) if name in EXPERIMENTS else None
                if ends is not None and off_axis(ends[0], ends[1], value):
                    errors.append(
                        f"{path}: claim {claim['id']!r}: {argument} = {value:g} lies off the "
                        f"{coord} axis of file {name!r}, {ends[0]:g} to {ends[1]:g} (config "
                        f"key {ends[2]!r}{where}): a measurement reads a value on its axis, "
                        "never beyond"
                    )
    return errors


def load_claims(path: str | Path, files: Collection[str] = tuple(PAPER_RESULTS)) -> list[dict]:
    """Read ``claims.yaml``, checked by :func:`claim_errors` (``files``: the result file
    keys a measure may name); raises :class:`ClaimError` with the first problem."""
    try:
        raw = load_yaml(path)
    except ConfigFileError as exc:
        raise ClaimError(str(exc)) from None
    errors = _claims_file_errors(raw, path, files)
    if errors:
        raise ClaimError(errors[0])
    return raw["claims"]
