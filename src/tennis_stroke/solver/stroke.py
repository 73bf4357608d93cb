"""One stroke, phase by phase, and many strokes in parallel (the compiled path).

A stroke follows the paper's procedure (Sec. II):

1. *Swing*: from rest at ``theta0``, ``phi0 = theta0 + delta0`` at ``t = 0``, integrate the
   pendulum without the ball until ``phi`` falls through 0 at ``t0`` (event).  The wrist
   torque switches on at ``tau`` and off at ``C2_off``; each switch ends a phase.
2. *Contact start*: ``t_c = t0 - contact_lead``.  The state at ``t_c`` is recomputed by one
   step from the last recorded swing step that starts before ``t_c``.  The ball is put at
   the hitting point (zero compression) with velocity ``+ball_speed``.
3. *Contact*: integrate pendulum and ball with the spring until the compression falls
   through 0 (separation event).  ``v_out`` is the ball's speed towards ``-x`` then.
   The cheap rungs of the model ladder (``contact_model`` other than ``spring``) skip
   steps 2-3: the ball meets the racket at ``t0`` in no time
   (:func:`tennis_stroke.model.impact.instant_contact`), so the contact start and the
   separation are both ``t0``.
4. *Follow-through* (optional): the free swing continues for ``follow_through`` seconds so
   that ``omega2_max`` covers the whole stroke.

Failures are statuses (:data:`STATUS_NAMES`), never exceptions.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Mapping
from concurrent.futures import ThreadPoolExecutor, wait
from functools import partial

import numba
import numpy as np
from numba import literally, njit

from ..model.dynamics import (
    BALL_S,
    BALL_W,
    CF_CONTACT_MODEL,
    CF_LEAD,
    CF_PHI0,
    CF_THETA0,
    COS_PH,
    COS_TH,
    JIT,
    JIT_INNER,
    OMEGA1,
    OMEGA2,
    PHI,
    SIN_PH,
    SIN_TH,
    SPRING,
    SWING_COLUMNS,
    THETA,
    approach_rate,
    coefficients,
    contact_duration,
    incoming_ball,
    next_switch,
    rebound_speed_kmh,
    rhs_trig,
    to_angles,
    to_trig,
    wrist_torque,
)
from ..model.impact import instant_contact
from ..model.params import ParameterError, initial_angles, one_stroke, resolve_params
from ._kernels import N_STAGES_BY_ID, coefficient_tuple
from .compiled import ensure_compiled
from .integrate import (
    HISTORY_COLS,
    N_STATS,
    PHASE_END,
    PHASE_EVENT,
    PHASE_FAIL,
    ST_NFEV,
    ST_NSTEP,
    ST_W2MAX,
    flag,
    history_find,
    history_reset,
    history_state,
    integrate_phase,
    method_step,
    peak_omega2,
    specialised,
)
from .results import (
    EARLY_CONTACT,
    LEAD_TOO_LONG,
    N_OUT,
    NO_APPROACH,
    NO_PHI_ZERO,
    NO_RELEASE,
    O_NFEV,
    O_NSTEP,
    O_STATUS,
    O_T_CONTACT,
    O_T_PHI0,
    O_T_SEP,
    O_THETA_CONTACT,
    O_THETA_PHI0,
    O_VOUT,
    O_W1_CONTACT,
    O_W1_PHI0,
    O_W2_CONTACT,
    O_W2_MAX,
    O_W2_PHI0,
    OK,
    STATUS_NAMES,
    STEP_FAILURE,
    results_from_output,
)
from .settings import (
    METHOD_IDS,
    S_ATOL,
    S_CONTACT_STEPS,
    S_FIRST_STEP,
    S_FOLLOW,
    S_MAX_STEPS,
    S_RTOL,
    S_TMAX,
    SolverSettings,
    solver_settings,
    thread_count,
)


@njit(**JIT)
def run_phases(method, contact, t, y, t_stop, h, h_max, cf, event_on, st, stats, history):
    """Integrate one phase kind through the torque switches until an event or ``t_stop``."""
    method = literally(method)  # compiled per method (solver/integrate.py)
    while True:
        t_seg = next_switch(t, cf, t_stop)
        c2 = wrist_torque(t, t_seg, cf)
        f = rhs_trig(t, y, cf, c2, contact)
        stats[ST_NFEV] += 1
        status, t, y, f, h = integrate_phase(
            method,
            contact,
            t,
            y,
            f,
            t_seg,
            h,
            h_max,
            cf,
            c2,
            st[S_RTOL],
            st[S_ATOL],
            st[S_MAX_STEPS],
            event_on,
            stats,
            history,
        )
        if status != PHASE_END or t >= t_stop:
            return status, t, y, h


@njit(inline="always", **JIT_INNER)
def restart_at(method, t_c, row, cf, st, stats):
    """Swing state at ``t_c`` by one step from a recorded step start (``row``)."""
    t_i, h_i, w2max, y, f = history_state(row)
    stats[ST_W2MAX] = w2max
    dt = t_c - t_i
    if dt <= 0.0:
        return y
    c2 = wrist_torque(t_i, t_i + h_i, cf)
    rtol, atol = st[S_RTOL], st[S_ATOL]
    y_new, f_new, _ = method_step(method, flag(False), t_i, y, f, dt, cf, c2, rtol, atol)
    stats[ST_NFEV] += N_STAGES_BY_ID[method]
    stats[ST_W2MAX] = peak_omega2(y, y_new, f, f_new, dt, w2max)
    return y_new


@njit(inline="always", **JIT_INNER)
def contact_start(t_c, y, cf, out):
    """Record the swing's state at the contact start ``t_c`` and put the ball at the
    hitting point: ``(approaches, s, w)``, whether the racket closes in on the ball and
    the ball's state."""
    s_th, c_th, s_ph, c_ph = y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH]
    w1, w2 = y[OMEGA1], y[OMEGA2]
    out[O_T_CONTACT] = t_c
    out[O_THETA_CONTACT] = y[THETA]
    out[O_W1_CONTACT] = w1
    out[O_W2_CONTACT] = w2
    s, w = incoming_ball(t_c, s_th, s_ph, cf)
    return approach_rate(s_th, c_th, s_ph, c_ph, w1, w2, w, cf) > 0.0, s, w


@njit(inline="always", **JIT_INNER)
def contact_phase(method, t_c, y, h, cf, st, out, stats, history):
    """Ball contact from ``t_c`` to separation, then the follow-through; returns a status."""
    approaches, s, w = contact_start(t_c, y, cf, out)
    if not approaches:
        return NO_APPROACH
    s_th, c_th, s_ph, c_ph = y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH]
    y = (s_th, c_th, s_ph, c_ph, y[OMEGA1], y[OMEGA2], y[THETA], y[PHI], s, w)
    h_max = contact_duration(s_th, c_th, s_ph, c_ph, cf) / st[S_CONTACT_STEPS]
    no_history = history[:1]
    h = min(h, h_max)
    status, t, y, h = run_phases(
        method, flag(True), t_c, y, st[S_TMAX], h, h_max, cf, flag(True), st, stats, no_history
    )
    if status == PHASE_FAIL:
        return STEP_FAILURE
    if status == PHASE_END:
        return NO_RELEASE
    out[O_T_SEP] = t
    out[O_VOUT] = rebound_speed_kmh(t, y[BALL_W], cf)
    return follow_through(method, t, y, h, cf, st, out, stats, no_history)


@njit(inline="always", **JIT_INNER)
def follow_through(method, t, y, h, cf, st, out, stats, no_history):
    """The free swing after the ball has left, for ``omega2_max``; returns a status."""
    if st[S_FOLLOW] > 0.0:
        t_stop = t + st[S_FOLLOW]
        status, t, y, h = run_phases(
            method, flag(False), t, y, t_stop, h, np.inf, cf, flag(False), st, stats, no_history
        )
        if status == PHASE_FAIL:
            return STEP_FAILURE
    out[O_W2_MAX] = stats[ST_W2MAX]
    return OK


@njit(inline="always", **JIT_INNER)
def instant_phase(method, t, y, h, cf, st, out, stats, history):
    """The cheap rungs' collision at ``phi = 0`` (time ``t``, state ``y``), then the
    follow-through from the rods' new angular velocities; returns a status."""
    if not contact_start(t, y, cf, out)[0]:
        return NO_APPROACH
    v_out, w1, w2 = instant_contact(t, y, cf)
    out[O_T_SEP] = t
    out[O_VOUT] = v_out
    s_th, c_th, s_ph, c_ph = y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH]
    y = (s_th, c_th, s_ph, c_ph, w1, w2, y[THETA], y[PHI], y[BALL_S], y[BALL_W])
    return follow_through(method, t, y, h, cf, st, out, stats, history[:1])


#: Where :func:`stroke_row` keeps the free swing's outcome for the next row: status, t,
#: step, the 10 state components and the solver statistics.
SW_STATUS, SW_T, SW_H, SW_Y = 0, 1, 2, 3
SW_STATS = SW_Y + 10
SWING_LEN = SW_STATS + N_STATS


@njit(inline="always", **JIT_INNER)
def same_swing(cf_a, cf_b):
    """Whether two coefficient rows swing alike: the same bits in every column the free
    swing reads (:data:`tennis_stroke.model.dynamics.SWING_COLUMNS`; NaN is never the
    same, 0.0 and -0.0 are not)."""
    for c in SWING_COLUMNS:
        a, b = cf_a[c], cf_b[c]
        if a != b or math.copysign(1.0, a) != math.copysign(1.0, b):
            return False
    return True


@njit(inline="always", **JIT_INNER)
def free_swing(method, cf, st, stats, history, swing, reuse):
    """The swing from rest to ``phi = 0`` (or its failure): ``(status, t, y, h)``, with
    ``stats`` and ``history`` as it leaves them.  With ``reuse`` the previous row's
    swing, kept in ``history`` and ``swing``, is taken as it is (the caller has checked
    the rows swing alike: the same numbers come out, without the steps)."""
    if reuse:
        for i in range(N_STATS):
            stats[i] = swing[SW_STATS + i]
        y = (
            swing[SW_Y], swing[SW_Y + 1], swing[SW_Y + 2], swing[SW_Y + 3], swing[SW_Y + 4],
            swing[SW_Y + 5], swing[SW_Y + 6], swing[SW_Y + 7], swing[SW_Y + 8], swing[SW_Y + 9],
        )  # fmt: skip
        return int(swing[SW_STATUS]), swing[SW_T], y, swing[SW_H]
    th0, ph0 = cf[CF_THETA0], cf[CF_PHI0]
    y = (math.sin(th0), math.cos(th0), math.sin(ph0), math.cos(ph0), 0.0, 0.0, th0, ph0, 0.0, 0.0)
    history_reset(history)
    h = st[S_FIRST_STEP]
    status, t, y, h = run_phases(
        method, flag(False), 0.0, y, st[S_TMAX], h, np.inf, cf, flag(True), st, stats, history
    )
    swing[SW_STATUS], swing[SW_T], swing[SW_H] = status, t, h
    for i in range(10):
        swing[SW_Y + i] = y[i]
    for i in range(N_STATS):
        swing[SW_STATS + i] = stats[i]
    return status, t, y, h


@njit(**JIT)
def stroke_row(method, cf_row, st, out, history, stats, swing, reuse):
    """Simulate one stroke (coefficient row ``cf_row``); write the ``O_*`` columns of ``out``.
    ``swing``: the free swing's outcome, kept for the next row; ``reuse``: this row swings
    as the previous one did (:func:`same_swing`), so its swing is not integrated again."""
    method = literally(method)  # compiled per method (solver/integrate.py)
    cf = coefficient_tuple(cf_row)
    out[:] = np.nan
    stats[:] = 0.0
    status, t, y, h = free_swing(method, cf, st, stats, history, swing, reuse)
    code = OK
    if status == PHASE_FAIL:
        code = STEP_FAILURE
    elif status == PHASE_END:
        code = NO_PHI_ZERO
    else:
        out[O_T_PHI0] = t
        out[O_THETA_PHI0] = y[THETA]
        out[O_W1_PHI0] = y[OMEGA1]
        out[O_W2_PHI0] = y[OMEGA2]
        t_c = t - cf[CF_LEAD]
        if cf[CF_CONTACT_MODEL] != SPRING:
            t_c = t
        row = history_find(history, t_c)
        if t_c < 0.0:
            code = EARLY_CONTACT
        elif cf[CF_CONTACT_MODEL] != SPRING:
            code = instant_phase(method, t, y, h, cf, st, out, stats, history)
        elif row < 0:
            code = LEAD_TOO_LONG
        else:
            y = restart_at(method, t_c, history[row], cf, st, stats)
            code = contact_phase(method, t_c, y, h, cf, st, out, stats, history)
    out[O_STATUS] = code
    out[O_NFEV] = stats[ST_NFEV]
    out[O_NSTEP] = stats[ST_NSTEP]


@njit(nogil=True, **JIT)
def solve_rows(method, cf_rows, order, share, st, out, start, stop, history_capacity, halt):
    """Solve the strokes ``order[start:stop]`` of ``cf_rows`` into the same rows of ``out``
    (releases the GIL: threads run such ranges side by side); returns the swings it
    integrated.  Before each stroke it looks at ``halt[0]``: set (by the caller, on a
    signal) it returns at once, the rows not yet solved left as they were.  With
    ``share``, a row that swings as the one before it (:func:`same_swing`: they differ
    only in the ball, the spring or the contact's timing) starts from that row's swing;
    every row's numbers, its counts of evaluations and steps included, are those of the
    stroke computed alone."""
    method = literally(method)  # compiled per method (solver/integrate.py)
    history = np.zeros((history_capacity + 1, HISTORY_COLS))
    stats = np.zeros(N_STATS)
    swing = np.zeros(SWING_LEN)
    swings = 0
    for i in range(start, stop):
        if halt[0] != 0:
            return swings
        row = order[i]
        reuse = share and i > start and same_swing(cf_rows[order[i - 1]], cf_rows[row])
        swings += not reuse
        stroke_row(method, cf_rows[row], st, out[row], history, stats, swing, reuse)
    return swings


@njit(**JIT)
def swing_keys(bits):
    """A hash of each row's swing columns (``bits``: the coefficient rows viewed as
    ``uint64``): rows that swing alike have the same key (rows with the same key need not
    swing alike; :func:`same_swing` decides)."""
    keys = np.empty(bits.shape[0], dtype=np.uint64)
    for i in range(bits.shape[0]):
        h = np.uint64(14695981039346656037)
        for c in SWING_COLUMNS:
            h = (h ^ bits[i, c]) * np.uint64(1099511628211)
        keys[i] = h
    return keys


def swing_order(cf_rows: np.ndarray) -> np.ndarray:
    """An order of the rows in which rows that swing alike are next to each other (so
    :func:`solve_rows` swings once for each run of them); the rows as they come when no
    two share a swing key."""
    n = cf_rows.shape[0]
    if n > 1:
        keys = swing_keys(cf_rows.view(np.uint64))
        order = np.argsort(keys, kind="stable")
        ranked = keys[order]
        if np.any(ranked[1:] == ranked[:-1]):
            return order
    return np.arange(n)


#: Right-hand-side evaluations of every stroke this process has run through
#: :func:`solve_coefficients` (:func:`rhs_evaluations`).
_EVALUATIONS = [0]
#: Strokes given to :func:`solve_coefficients` in this process, and the swings it
#: integrated for them (:func:`swings_integrated`).
_SWINGS = {"strokes": 0, "swings": 0}


def rhs_evaluations() -> int:
    """Right-hand-side evaluations of the compiled solver in this process so far: the
    cost of a computation that does not depend on the machine (the difference before and
    after it).  Each stroke counts its whole cost, its swing's evaluations included where
    the swing was shared with the row before it (:func:`swings_integrated`)."""
    return _EVALUATIONS[0]


def swings_integrated() -> tuple[int, int]:
    """``(strokes, swings)``: the strokes the compiled solver was given in this process
    so far and the swings it integrated for them (fewer where rows that swing alike
    shared one, :func:`swing_order`)."""
    return _SWINGS["strokes"], _SWINGS["swings"]


#: Ranges per thread: a thread that finishes early takes another range, so strokes of
#: unequal cost (failures stop early) even out.
RANGES_PER_THREAD = 4
#: Strokes per call of the compiled solver when a progress bar is shown.
PROGRESS_BLOCK = 8192


def default_threads() -> int:
    """Threads used when none are asked for: numba's thread count (all cores, or the
    environment's ``NUMBA_NUM_THREADS``)."""
    return int(numba.config.NUMBA_NUM_THREADS)


#: The worker threads of this process, by thread count (:func:`_pool`).
_POOLS: dict[tuple[int, int], ThreadPoolExecutor] = {}


def _pool(n_threads: int) -> ThreadPoolExecutor:
    """The ``n_threads`` worker threads of this process, started at its first batch of
    more than one stroke and kept for the next (a search calls the solver hundreds of
    times: starting a thread each time was a seventh of a robustness chunk's time); a
    forked child starts its own (its parent's threads do not exist in it)."""
    key = (os.getpid(), n_threads)
    if key not in _POOLS:
        _POOLS[key] = ThreadPoolExecutor(n_threads, thread_name_prefix="tennis-stroke-solver")
    return _POOLS[key]


def _solve_block(method, cf_rows, order, share, block, st, out, history, n_threads, pool, halt):
    """The strokes ``order[start:stop]`` (``block``) of ``cf_rows`` into ``out``: ranges
    of strokes (one range on one thread) on ``pool``'s threads while this thread waits
    for them, where a signal is handled (it sets ``halt`` and waits for the ranges to
    stop); without ``pool`` (a single stroke) in this thread.  Returns the swings
    integrated."""
    start, stop = block
    n = stop - start
    n_ranges = min(max(n, 1), RANGES_PER_THREAD * n_threads) if n_threads > 1 else 1
    bounds = [(start + c * n // n_ranges, start + (c + 1) * n // n_ranges) for c in range(n_ranges)]
    args = (cf_rows, order, share, st, out)
    solve = specialised(solve_rows, method, *args, start, stop, history, halt)
    if pool is None:
        return sum(solve(*args, a, b, history, halt) for a, b in bounds)
    jobs = [pool.submit(solve, *args, a, b, history, halt) for a, b in bounds]
    try:
        return sum(job.result() for job in jobs)
    except BaseException:
        halt[0] = 1  # the threads stop at their next stroke
        wait(jobs)
        raise


def solve_coefficients(
    cf_rows: np.ndarray,
    settings: SolverSettings | None = None,
    threads: int | None = None,
    progress: bool = False,
    share_swings: bool = True,
) -> np.ndarray:
    """Run the compiled solver on prepared coefficient rows; returns ``(n, N_OUT)``.

    Every stroke's numbers are its own, the same bits as computed alone, so the result
    does not depend on the number of threads or on how the strokes are split among them
    or shared.  Rows that swing alike (they
    differ only in the ball, the spring or the contact's timing) are solved one after
    another, so the swing is integrated once for each run of them (:func:`swing_order`,
    :func:`solve_rows`): the numbers are the same.  ``share_swings=False`` integrates
    every row's swing (what a timing of a stroke's cost needs: copies of one stroke
    would otherwise share theirs).

    A signal (Ctrl-C, or SIGTERM where it raises) stops the computation at the next
    stroke of every thread: more than one stroke run on worker threads while this one
    waits, where Python handles the signal; the exception then raised here sets the
    ranges' ``halt`` flag, waits for the threads (each within one stroke, itself bounded
    by ``settings.max_steps``) and propagates.  A single stroke runs in this thread.

    Parameters
    ----------
    cf_rows : ndarray, shape (n, N_CF)
        From :func:`tennis_stroke.model.dynamics.coefficients`.
    settings : SolverSettings, optional
    threads : int, optional
        Threads to use (default :func:`default_threads`; at most that many).
    progress : bool
        Show a tqdm progress bar (in blocks of :data:`PROGRESS_BLOCK` strokes).
    share_swings : bool
        Let rows that swing alike share one swing (default).
    """
    settings = solver_settings(settings)
    n_threads = (
        default_threads() if threads is None else min(thread_count(threads), default_threads())
    )
    ensure_compiled(f"batch:{settings.method}", partial(exercise_batch, settings.method))
    method = METHOD_IDS[settings.method]
    st = settings.as_array()
    cf_rows = np.ascontiguousarray(cf_rows, dtype=float)
    n = cf_rows.shape[0]
    order = swing_order(cf_rows) if share_swings else np.arange(n)
    out = np.empty((n, N_OUT))
    swings = 0
    halt = np.zeros(1, dtype=np.int64)  # set on a signal: every range stops
    with contextlib.ExitStack() as stack:
        pool = _pool(n_threads) if n > 1 else None
        try:
            blocks = [(0, n)]
            if progress and n > PROGRESS_BLOCK:
                from tqdm import tqdm

                bar = stack.enter_context(tqdm(total=n, unit="stroke", leave=False))
                blocks = [(a, min(a + PROGRESS_BLOCK, n)) for a in range(0, n, PROGRESS_BLOCK)]
            for a, b in blocks:
                rest = (st, out, settings.history, n_threads, pool, halt)
                swings += _solve_block(method, cf_rows, order, share_swings, (a, b), *rest)
                if len(blocks) > 1:
                    bar.update(b - a)
        except BaseException:
            halt[0] = 1  # the threads stop at their next stroke (_solve_block waits for them)
            raise
    _EVALUATIONS[0] += int(out[:, O_NFEV].sum())
    _SWINGS["strokes"] += n
    _SWINGS["swings"] += swings
    return out


def strike_batch(
    theta0_deg,
    delta0_deg,
    params: Mapping[str, object] | None = None,
    settings: SolverSettings | None = None,
    threads: int | None = None,
    progress: bool = False,
    share_swings: bool = True,
) -> dict[str, np.ndarray]:
    """Simulate many strokes; every input broadcasts against the others.

    Parameters
    ----------
    theta0_deg, delta0_deg : array_like
        Initial angles ``theta(0)`` and ``delta(0) = phi(0) - theta(0)`` (degrees), by
        the rule of :data:`tennis_stroke.model.params.INITIAL_ANGLES` (each within a
        turn, the racket less than a turn before the hit).
    params : mapping, optional
        Parameter overrides (scalars or arrays) and readings; see
        :func:`tennis_stroke.model.params.resolve_params`.
    settings : SolverSettings, optional
    threads : int, optional
    progress : bool
    share_swings : bool
        As :func:`solve_coefficients`'s (the numbers do not depend on it).

    Returns
    -------
    dict of ndarray
        The fields of :data:`tennis_stroke.solver.results.RESULT_FIELDS`, each of the
        broadcast shape.
    """
    resolved = resolve_params(params)
    th, de = initial_angles(theta0_deg, delta0_deg)
    shapes = [
        th.shape,
        de.shape,
        *(np.shape(v) for v in resolved.values() if not isinstance(v, str)),
    ]
    try:
        shape = np.broadcast_shapes(*shapes)
    except ValueError:
        raise ParameterError(
            f"the initial angles and parameter arrays do not broadcast to one shape: {shapes}"
        ) from None
    cf_rows = coefficients(resolved, th, de)
    out = solve_coefficients(cf_rows, settings, threads, progress, share_swings)
    return results_from_output(out, shape)


def strike(
    theta0_deg: float,
    delta0_deg: float,
    params: Mapping[str, object] | None = None,
    settings: SolverSettings | None = None,
) -> dict[str, object]:
    """Simulate one stroke; returns the result fields as Python scalars plus ``status_name``.

    The initial angles and parameters are one value each (:func:`strike_batch` takes
    arrays): an array is a :class:`tennis_stroke.model.params.ParameterError`."""
    one_stroke("strike", resolve_params(params), theta0_deg, delta0_deg)
    res = strike_batch(theta0_deg, delta0_deg, params, settings, threads=1)
    out: dict[str, object] = {k: v.item() for k, v in res.items()}
    out["status_name"] = STATUS_NAMES[out["status"]]
    return out


def solve_contact(
    cf_row: np.ndarray, y_angles: np.ndarray, t_end: float, settings: SolverSettings
) -> tuple[bool, float, np.ndarray]:
    """The contact phase alone, from a given state, with the compiled integrator.

    Parameters
    ----------
    cf_row : ndarray, shape (N_CF,)
        Stroke coefficients (:func:`tennis_stroke.model.dynamics.coefficients`).
    y_angles : ndarray, shape (6,)
        Start state in the angle layout (pendulum and ball).
    t_end : float
        Time (s) by which the ball must have left.
    settings : SolverSettings
        Method and tolerances; contact steps are capped at the two-body contact time over
        ``settings.contact_min_steps``.

    Returns
    -------
    separated, t, y
        Whether the ball left before ``t_end``, the time reached (s) and the state there
        (angle layout).
    """
    ensure_compiled(f"contact:{settings.method}", partial(exercise_contact, settings.method))
    cf = coefficient_tuple(cf_row)
    y = to_trig(y_angles)
    st = settings.as_array()
    h_max = contact_duration(y[SIN_TH], y[COS_TH], y[SIN_PH], y[COS_PH], cf) / st[S_CONTACT_STEPS]
    args = (True, 0.0, y, t_end, min(settings.first_step, h_max), h_max, cf, True, st)
    args += (np.zeros(N_STATS), np.zeros((1, HISTORY_COLS)))
    method = METHOD_IDS[settings.method]
    status, t, y, _ = specialised(run_phases, method, *args)(*args)
    return status == PHASE_EVENT, t, to_angles(y)


def exercise_batch(method: str) -> None:
    """The calls that compile (or load) the stroke batch's entry points for ``method``
    (:func:`tennis_stroke.solver.compiled.ensure_compiled`)."""
    strike_batch(np.array([90.0, 120.0]), 45.0, settings=SolverSettings(method=method), threads=1)


def exercise_contact(method: str) -> None:
    """The calls that compile (or load) the contact phase's entry point for ``method``."""
    cf_row = coefficients(resolve_params({}), 120.0, 81.5)[0]
    state = np.array([1.0, 0.0, 10.0, 30.0, 0.0, 20.0])
    solve_contact(cf_row, state, 0.01, SolverSettings(method=method))
