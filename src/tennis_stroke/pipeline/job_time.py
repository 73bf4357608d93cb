"""Time of a study's job, estimated before anything runs, and the limit.

A step or a count of a study sets how long its job computes, not how much memory it
holds: ``solver_study.rk4_steps: [1.0e-12]`` passed every memory estimate, was planned,
and its job would have run for hundreds of hours a stroke (issue 56).  Every job of the
solver studies (:func:`study_jobs`: the work-precision table, the stability map, the
model ladder on random strokes), and the model ladder claim by claim, is estimated from
its counts (strokes, repeats, RK4 steps, cases, spring constants, rungs) at the costs
measured in the work-precision study, and the workflow's config check refuses one above
:func:`time_limit` in one line naming the key of its dearest part
(:func:`tennis_stroke.pipeline.config_check.time_errors`).

The maps and the claims' searches need no such estimate: the memory of each of their
batches is bounded (:mod:`tennis_stroke.pipeline.memory`, at least 456 bytes a stroke
held at once) and a compiled stroke costs about 24 µs, so a batch within 16 GiB computes
for about 15 minutes a core at most; a search's later batches halve their step down to
its tolerance, a number of batches logarithmic in it.

The limit, first found wins: the config key ``max_job_hours``, the environment variable
:data:`TIME_ENV` (``TENNIS_STROKE_MAX_JOB_HOURS``), else :data:`DEFAULT_HOURS`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Mapping

from ..studies.methods import parse_method

#: Seconds a stroke of the compiled solver costs on one thread: the dearest compiled row
#: of the work-precision table of 2026-11-30 (6220384, docs/performance.md): DP54 at rtol
#: 1e-8, 24.21 µs (DOP853 at 1e-8: 14.75 µs).
COMPILED_STROKE_SECONDS = 24.21e-6
#: Seconds a stroke of ``solve_ivp`` costs, by method, from the same table: RK45 and
#: DOP853 at rtol 1e-8, LSODA at 1e-8, Radau at 1e-6; a method the table has not measured
#: is taken at the dearest (Radau's).  The work-precision study runs these four.
SCIPY_STROKE_SECONDS = {"RK45": 2.02e-2, "DOP853": 1.166e-2, "LSODA": 1.911e-2, "Radau": 6.233e-2}
#: Seconds one right-hand-side evaluation of fixed-step RK4 costs (its steps are a Python
#: loop): 36590 µs and 9484 evaluations a stroke at a 0.2 ms step, the RK4 row of the
#: same table (docs/changes.md, "RK4's events on the Hermite cubic").
RK4_EVALUATION_SECONDS = 3.659e-2 / 9484
#: Simulated seconds of fixed-step RK4 per stroke (its steps times the step: the swing
#: integrated twice, then the contact), from the same row: 9484 / 4 steps of 0.2 ms.
RK4_STROKE_SPAN = 9484 / 4 * 2e-4
#: Simulated seconds of the stability study's isolated contact at most
#: (:func:`tennis_stroke.studies.stability.isolated_contact`'s ``t_end``).
CONTACT_SPAN = 0.5
#: The strokes a timed batch holds at least (``studies.timing.TIMING_STROKES``, written
#: again here: planning imports no solver, tests/workflow/test_job_imports.py; a test
#: checks the two agree), and the repeats the model ladder on random strokes times
#: (``studies.ladder.ladder``'s default).
TIMING_STROKES, LADDER_REPEATS = 4000, 3
#: Seconds the model ladder's job computes per rung: 1.5 s for the shipped 5 rungs at the
#: shipped search steps (docs/performance.md, the inference jobs, 10164ac).
RUNG_SECONDS = 1.5 / 5
#: Hours a job may take by default: the whole replication runs in minutes, so a job
#: beyond a day is a mistyped step or count.
DEFAULT_HOURS = 24.0
#: Environment variable overriding the default limit (hours).
TIME_ENV = "TENNIS_STROKE_MAX_JOB_HOURS"


class JobTimeError(ValueError):
    """A job would take longer than the limit (message is one line)."""


def rk4_steps(span: float, step: float) -> float:
    """Steps of fixed-step RK4 over ``span`` simulated seconds at ``step`` (s)."""
    return span / step


def case_seconds(method: str, setting: float, span: float) -> tuple[float, str]:
    """Seconds of one run of ``method`` (``family.NAME``) at ``setting`` over ``span``
    simulated seconds (RK4), or one stroke (the others), and what it is."""
    family, name = parse_method(method)
    if family == "fixed":
        steps = rk4_steps(span, setting)
        return 4 * steps * RK4_EVALUATION_SECONDS, f"{_count(steps)} RK4 steps of {setting:g} s"
    if family == "scipy":
        cost = SCIPY_STROKE_SECONDS.get(name, max(SCIPY_STROKE_SECONDS.values()))
        return cost, f"scipy {name} at {setting:g}"
    return COMPILED_STROKE_SECONDS, f"{name} at {setting:g}"


def study_jobs(config: Mapping) -> Iterator[tuple[str, list[tuple[str, str, float]]]]:
    """``(job, parts)`` of each solver study's job, ``parts`` its ``(config key, what,
    seconds)`` estimates (nothing runs)."""
    study = config["solver_study"]
    n, repeats = int(study["strokes"]), int(study["repeats"])
    timed = max(n, TIMING_STROKES)
    reference = n * COMPILED_STROKE_SECONDS
    parts = [("solver_study.strokes", f"the reference of {n} strokes", reference)]
    for i, tol in enumerate(study["compiled_tolerances"]):
        what = f"the compiled methods at {tol:g} ({repeats} x {timed} strokes each)"
        seconds = 2 * repeats * timed * COMPILED_STROKE_SECONDS
        parts.append((f"solver_study.compiled_tolerances.{i}", what, seconds))
    scipy_stroke = sum(SCIPY_STROKE_SECONDS.values())
    for i, tol in enumerate(study["scipy_tolerances"]):
        what = f"solve_ivp's {len(SCIPY_STROKE_SECONDS)} methods at {tol:g} ({n} strokes)"
        parts.append((f"solver_study.scipy_tolerances.{i}", what, n * scipy_stroke))
    for i, step in enumerate(study["rk4_steps"]):
        seconds, what = case_seconds("fixed.RK4", step, RK4_STROKE_SPAN)
        parts.append((f"solver_study.rk4_steps.{i}", f"{n} strokes of {what}", n * seconds))
    yield "the work-precision study", parts
    stability = study["stability"]
    num = int(stability["k_contact"]["num"])
    parts = []
    for i, (method, setting) in enumerate(stability["cases"]):
        seconds, what = case_seconds(method, setting, CONTACT_SPAN)
        what = f"{num} spring constants, each up to {what}"
        parts.append((f"solver_study.stability.cases.{i}", what, num * seconds))
    yield "the stability study", parts
    seconds = 2 * LADDER_REPEATS * timed * COMPILED_STROKE_SECONDS
    yield "the model ladder study", [("solver_study.strokes", f"{timed} strokes", seconds)]
    rungs = len((config.get("model_ladder") or {}).get("rungs") or ())
    if rungs:
        what = f"every claim under {rungs} rungs"
        yield "the model ladder", [("model_ladder.rungs", what, rungs * RUNG_SECONDS)]


def time_limit(explicit: float | int | None = None, source: str = "the given limit"):
    """The limit (seconds) and where it comes from, for messages: ``explicit`` hours
    (from ``source``), else :data:`TIME_ENV`, else :data:`DEFAULT_HOURS`.  A limit that is
    not a positive finite number of hours raises ``ValueError`` naming its source."""
    if explicit is not None:
        return _hours(explicit, source) * 3600.0, source
    env = os.environ.get(TIME_ENV, "").strip()
    if env:
        return _hours(env, TIME_ENV) * 3600.0, TIME_ENV
    return DEFAULT_HOURS * 3600.0, f"the default; change it with {source} or {TIME_ENV}"


def _hours(value, source: str) -> float:
    try:
        hours = float(value) if not isinstance(value, bool) else math.nan
    except (TypeError, ValueError):
        hours = math.nan
    if not (math.isfinite(hours) and hours > 0):
        raise ValueError(
            f"{source}: a job's time limit must be a number of hours > 0, got {value!r}"
        )
    return hours


def check_time(job: str, parts: list[tuple[str, str, float]], limit: tuple[float, str]) -> None:
    """Raise :class:`JobTimeError` (one line: the key of the dearest part, the job's
    estimate and the limit) if the parts of ``job`` add up to more than ``limit``."""
    seconds, source = limit
    total = sum(part[2] for part in parts)
    if total > seconds:
        key, what, dearest = max(parts, key=lambda part: part[2])
        raise JobTimeError(
            f"config key {key!r}: {job} would take about {format_hours(total)} ({what}: "
            f"{format_hours(dearest)}), above the limit of {format_hours(seconds)} ({source})"
        )


def format_hours(seconds: float) -> str:
    """``2.5 h``-style duration (three digits)."""
    return f"{seconds / 3600.0:.3g} h"


def _count(value: float) -> str:
    """A count for a message: exact below a million, else three digits."""
    return f"{value:.0f}" if value < 1e6 else f"{value:.3g}"
