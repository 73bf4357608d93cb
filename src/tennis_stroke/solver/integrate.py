"""Compiled adaptive embedded Runge-Kutta integration with dense output and events.

Two methods, both explicit, adaptive, with local extrapolation and scipy's error norms:

* ``DP54``: Dormand & Prince 5(4) (J. Comput. Appl. Math. 6, 19, 1980) with Shampine's
  4th-order continuous extension (Math. Comp. 46, 135, 1986).
* ``DOP853``: Dormand & Prince 8(5,3) with the 7th-order dense output of Hairer, Norsett
  & Wanner, *Solving ODEs I*, Sec. II.10.

The tableaux are data (scipy's ``RK45``/``DOP853`` coefficients), turned into
straight-line kernels by ``tools/generate_kernels.py`` (:mod:`tennis_stroke.solver._kernels`).
This module holds the dispatch to those kernels, the step-size controller and event
location.  The method is a compile-time constant: the compiled functions that take it
call ``literally(method)`` (or are inlined into one that does), so an entry point is
compiled (and cached) once per method,
and the overloads :func:`method_step`, :func:`method_dense` and :func:`method_dense_eval`
pick that method's kernels while compiling: a run of DOP853 never compiles DP54.  The
phase (swing or contact) is a run-time flag of one kernel per method.  Not closures:
numba caches module-level functions on disk, but recompiles closures in every new
process.  Functions only compiled code calls are compiled without the wrapper that lets
Python call them, and the small ones are inlined into their callers (``inline="always"``):
every compiled function is compiled again, machine code included, in each of its callers'
modules, so fewer levels and no unused wrappers compile faster
(``benchmarks/compile_time.py``).

Contract of a phase integrator ``integrate(t, y, f, t_end, h, h_max, cf, c2, rtol, atol,
max_steps, event_on, stats, history) -> (status, t, y, f, h)``: advance the state tuple
``y`` (and ``f = dy/dt``) from ``t`` towards ``t_end`` (forwards or backwards) without
crossing it, with a constant wrist torque ``c2``.  With ``event_on``, the phase's
terminal event (free swing: ``phi`` falls through 0; contact: the compression falls
through 0) is located by root finding (Illinois) on the dense output, and ``y`` is the
dense output there.  Discontinuities never occur inside a
phase: the caller ends a phase at every switch and starts a new one.

:func:`integrate_phase` takes, besides, ``method`` (``METHOD_DP54`` or
``METHOD_DOP853``, a compile-time literal: ``literally``) and ``contact`` (the phase
kind: free swing, 8 components in the error norm, the ball's state carried over, event
``phi = 0``; or contact, 10 components, event separation) first.  The arguments:
``t`` the start time (s); ``y, f`` tuples of 10 floats, the state and ``rhs_trig(t,
y)``; ``t_end`` the end of the phase (s); ``h, h_max`` the proposed and the largest step
magnitude (s); ``cf`` the stroke's coefficients; ``c2`` the wrist torque during the
phase (N m); ``rtol, atol`` the tolerances of the scaled RMS error norm; ``max_steps``
the largest total number of accepted steps (``stats[ST_NSTEP]``); ``event_on`` whether
to stop at the phase's event; ``stats`` (shape ``(N_STATS,)``) the counters
(evaluations, steps, rejections, running max of omega2), updated; ``history`` (shape
``(capacity + 1, HISTORY_COLS)``) the ring of accepted step starts
(:func:`history_find`; capacity 0 records none).  It returns ``status, t, y, f, h``:
``PHASE_END``, ``PHASE_EVENT`` or ``PHASE_FAIL``, the time reached, the state there, the
derivative at the end of the last step (at an event not the event's: the state is
interpolated, the derivative is not; every caller evaluates its own at a phase start,
``tests/solver/test_integrate.py``) and the proposed next step.
"""

from __future__ import annotations

import functools
import inspect
import math

import numba
import numpy as np
from numba import literally, njit, types
from numba.extending import overload

from ..model.dynamics import JIT, JIT_INNER, N_CONTACT, OMEGA2, compression, swing_event
from . import _kernels

#: Step-size controller constants (Hairer & Wanner; scipy uses the same).
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
#: Floor of the previous step's error norm in the predictive step-size controller
#: (Hairer & Wanner, *Solving ODEs II*, Sec. IV.8, code RADAU5).
PREDICTIVE_ERR_FLOOR = 1e-2
#: Steps shorter than this many ulps of ``t`` count as a failure.
MIN_STEP_ULPS = 10.0
EPS = float(np.finfo(float).eps)
#: Width of the final bracket of an event root, as a fraction of the step.
EVENT_XTOL = 4.0 * np.finfo(float).eps
EVENT_MAX_ITER = 60

PHASE_END, PHASE_EVENT, PHASE_FAIL = 0, 1, 2
# Counters in the ``stats`` array.
ST_NFEV, ST_NSTEP, ST_NREJECT, ST_W2MAX = 0, 1, 2, 3
N_STATS = 4
#: Columns of a history row: start time, step, running max of omega2 before the step,
#: then the state ``y`` and ``f`` at the start.
HISTORY_COLS = 3 + 2 * N_CONTACT


@njit(inline="always", **JIT)
def flag(value):
    """``value`` as a run-time bool.  A constant ``True`` or ``False`` passed to a compiled
    function makes numba compile it, and everything it calls, once per constant (the phase
    integrator was compiled three times; a cold first stroke took about 17 s longer); the
    phase kind and the event switch go through this instead."""
    return bool(value)


@njit(inline="always", **JIT)
def peak_omega2(y0, y1, f0, f1, h, best):
    """Running maximum of omega2 updated with a step ``y0 -> y1`` of size ``h``.

    The step's end counts, and where ``d omega2/dt`` falls through zero inside the step,
    the peak of the cubic Hermite interpolant of ``omega2`` too.
    """
    best = max(best, y1[OMEGA2])
    d0, d1 = h * f0[OMEGA2], h * f1[OMEGA2]
    if d0 > 0.0 and d1 < 0.0:
        p0, p1 = y0[OMEGA2], y1[OMEGA2]
        # H(x) = p0 + d0 x + b x^2 + c x^3 on [0, 1]; H'(x) = d0 + 2 b x + 3 c x^2
        b = 3.0 * (p1 - p0) - 2.0 * d0 - d1
        c = 2.0 * (p0 - p1) + d0 + d1
        qa, qb = 3.0 * c, 2.0 * b
        if qa == 0.0:
            x = -d0 / qb
        else:
            root = math.sqrt(max(qb * qb - 4.0 * qa * d0, 0.0))
            x = (-qb - root) / (2.0 * qa)
            if not 0.0 <= x <= 1.0:
                x = (-qb + root) / (2.0 * qa)
        if 0.0 <= x <= 1.0:
            best = max(best, p0 + x * (d0 + x * (b + x * c)))
    return best


@njit(inline="always", **JIT)
def error_root(err, exponent):
    """``err ** -exponent``, the root of an error norm that the step-size rules take
    (``exponent = -1 / (error order + 1)``).  For DOP853's 1/8 by three square roots:
    ``pow`` was about a tenth of the solver's time (a ``perf`` profile of the bench
    grid), three square roots cost less.  Correctly rounded square roots keep order,
    so there ``error_root(max(a, b)) == max(error_root(a), error_root(b))`` exactly
    (the integrator floors the root, not the norm; for ``pow``, other methods, only
    as far as ``pow`` is monotonic)."""
    if exponent == -0.125:
        return math.sqrt(math.sqrt(math.sqrt(err)))
    return err**-exponent


@njit(inline="always", **JIT)
def step_factor(root, h, h_acc, root_acc):
    """Growth factor of the step after an accepted step of size ``h`` whose error norm
    has the root ``root`` (:func:`error_root`).

    The classical rule ``SAFETY / root``, that is ``SAFETY * err**exponent`` (within
    ``MAX_FACTOR``), and where the phase has a previous accepted step (``h_acc > 0``,
    root of its norm ``root_acc``) the smaller of that and Gustafsson's predictive rule,
    which also extrapolates the change of the error from step to step (Hairer & Wanner,
    *Solving ODEs II*, Sec. IV.8, eq. 8.21 and code RADAU5; never below ``MIN_FACTOR``).
    In an accelerating swing the error grows from step to step faster than the classical
    rule expects, and it rejects about every other step.
    """
    if root == 0.0:
        return MAX_FACTOR
    factor = min(MAX_FACTOR, SAFETY / root)
    if h_acc > 0.0:
        predicted = factor * (h / h_acc) * (root_acc / root)
        factor = min(factor, max(MIN_FACTOR, predicted))
    return factor


@njit(inline="always", **JIT_INNER)
def history_state(row):
    """``(t, step, omega2 max before, y, f)`` of a history row, states as tuples."""
    y = (row[3], row[4], row[5], row[6], row[7], row[8], row[9], row[10], row[11], row[12])
    f = (row[13], row[14], row[15], row[16], row[17], row[18], row[19], row[20], row[21], row[22])
    return row[0], row[1], row[2], y, f


@njit(inline="always", **JIT_INNER)
def history_reset(history):
    """Forget all recorded steps."""
    history[history.shape[0] - 1, 0] = 0.0


@njit(inline="always", **JIT_INNER)
def history_find(history, t):
    """Row of the latest recorded step starting at or before ``t``; -1 if forgotten."""
    capacity = history.shape[0] - 1
    count = int(history[capacity, 0])
    for n in range(count - 1, max(count - capacity, 0) - 1, -1):
        if history[n % capacity, 0] <= t:
            return n % capacity
    return -1


def method_step(method, contact, t, y, f, h, cf, c2, rtol, atol):
    """One step of the compile-time ``method`` (compiled code only; see :func:`rk_step`)."""
    raise NotImplementedError


def method_dense(method, contact, t, y, f, h, cf, c2, y_new, f_new):
    """Dense-output coefficients of the compile-time ``method`` (compiled code only; see
    :func:`dense_coefficients`)."""
    raise NotImplementedError


def method_dense_eval(method, x, y, z):
    """Dense output of the compile-time ``method`` (compiled code only; see
    :func:`dense_value`)."""
    raise NotImplementedError


def _step_impl(step):
    def impl(method, contact, t, y, f, h, cf, c2, rtol, atol):
        return step(t, y, f, h, cf, c2, rtol, atol, contact)

    return impl


def _dense_impl(dense):
    def impl(method, contact, t, y, f, h, cf, c2, y_new, f_new):
        return dense(t, y, f, h, cf, c2, y_new, f_new, contact)

    return impl


def _dense_eval_impl(dense_eval):
    def impl(method, x, y, z):
        return dense_eval(x, y, z)

    return impl


def _overload_kernel(stub, column, make_impl):
    """Compile ``stub`` as a call of the kernel in ``column`` of the method's row of
    :data:`_kernels.KERNELS_BY_ID`, inlined into the caller (no function of its own
    between the driver and the kernels).  ``method`` must be a literal: a caller that
    takes it as an argument calls ``literally(method)`` first (or is inlined into one
    that does)."""

    def typer(method, *args):
        if not isinstance(method, types.IntegerLiteral):
            return None  # numba tries the literal type next, if the caller has one
        if not 0 <= method.literal_value < len(_kernels.KERNELS_BY_ID):
            raise numba.core.errors.TypingError(f"no method with id {method.literal_value}")
        return make_impl(_kernels.KERNELS_BY_ID[method.literal_value][column])

    typer.__signature__ = inspect.signature(stub)  # numba matches it with the impl's
    overload(stub, inline="always")(typer)


_overload_kernel(method_step, 0, _step_impl)
_overload_kernel(method_dense, 1, _dense_impl)
_overload_kernel(method_dense_eval, 2, _dense_eval_impl)


def specialised(dispatcher, method, *args):
    """The machine code of the compiled ``dispatcher`` for the literal ``method`` and the
    types of ``args`` (the arguments after ``method``), loaded or compiled the first
    time, to call from Python with arguments of those types (``method`` bound).  Calling
    the dispatcher itself works too, but goes through numba's literal dispatch every
    time: about 6 ms a call (measured 2026-12-02), where this costs microseconds."""
    entry = dispatcher.compile((types.literal(method), *(numba.typeof(a) for a in args)))
    return functools.partial(entry, method)


@njit(**JIT)
def rk_step(method, contact, t, y, f, h, cf, c2, rtol, atol):
    """One step of ``method`` in the swing or contact phase: ``(y_new, f_new, error norm)``.

    Callable from Python (the tests); the integrator calls :func:`method_step`.
    """
    return method_step(literally(method), contact, t, y, f, h, cf, c2, rtol, atol)


@njit(**JIT)
def dense_coefficients(method, contact, t, y, f, h, cf, c2, y_new, f_new):
    """Dense-output coefficients (7 rows) of the step ``y -> y_new``."""
    return method_dense(literally(method), contact, t, y, f, h, cf, c2, y_new, f_new)


@njit(**JIT)
def dense_value(method, x, y, z):
    """State at the fraction ``x`` of the step from its dense-output coefficients ``z``."""
    return method_dense_eval(literally(method), x, y, z)


@njit(inline="always", **JIT_INNER)
def event_value(contact, y, cf):
    """The phase's terminal event function (model functions of
    :mod:`tennis_stroke.model.dynamics`): ``phi`` in the swing, the compression of the
    strings in the contact."""
    if contact:
        return compression(y, cf)
    return swing_event(y, cf)


@njit(inline="always", **JIT_INNER)
def event_crossed(contact, y0, y1, cf):
    """Whether the phase's event value fell through 0 during the step ``y0 -> y1``."""
    return event_value(contact, y0, cf) > 0.0 and event_value(contact, y1, cf) <= 0.0


@njit(inline="always", **JIT_INNER)
def locate_event(method, contact, y, z, cf):
    """Fraction of the step where the event value falls through 0 (Illinois method)."""
    lo, hi = 0.0, 1.0
    glo = event_value(contact, y, cf)
    ghi = event_value(contact, method_dense_eval(method, 1.0, y, z), cf)
    side = 0
    for _ in range(EVENT_MAX_ITER):
        if hi - lo <= EVENT_XTOL:
            break
        x = lo + (hi - lo) * glo / (glo - ghi)
        if not lo < x < hi:
            x = 0.5 * (lo + hi)
        gx = event_value(contact, method_dense_eval(method, x, y, z), cf)
        if gx > 0.0:
            lo, glo = x, gx
            if side == 1:
                ghi *= 0.5
            side = 1
        else:
            hi, ghi = x, gx
            if side == -1:
                glo *= 0.5
            side = -1
            if gx == 0.0:
                break
    return hi


@njit(inline="always", **JIT_INNER)
def record_step(history, count, capacity, t, dt, w2max, y, f):
    """Record an accepted step's start (time, step, running max of omega2, state and
    derivative) in the ring ``history`` at ``count``; returns the count after it."""
    r = count % capacity
    history[r, 0], history[r, 1], history[r, 2] = t, dt, w2max
    for i in range(N_CONTACT):
        history[r, 3 + i] = y[i]
        history[r, 3 + N_CONTACT + i] = f[i]
    return count + 1


@njit(**JIT)
def integrate_phase(
    method,
    contact,
    t,
    y,
    f,
    t_end,
    h,
    h_max,
    cf,
    c2,
    rtol,
    atol,
    max_steps,
    event_on,
    stats,
    history,
):
    """Advance ``(t, y, f)`` towards ``t_end`` within one phase: the module's contract
    says its arguments and what it returns."""
    n_stages = _kernels.N_STAGES_BY_ID[literally(method)]
    n_extra = _kernels.N_EXTRA_BY_ID[method]
    exponent = -1.0 / (_kernels.ERROR_ORDER_BY_ID[method] + 1)
    # Counters live in locals and reach ``stats`` on return.
    nfev, nstep = stats[ST_NFEV], stats[ST_NSTEP]
    nreject, w2max = stats[ST_NREJECT], stats[ST_W2MAX]
    capacity = history.shape[0] - 1
    count = int(history[capacity, 0]) if capacity > 0 else 0
    direction = 1.0 if t_end >= t else -1.0
    h = min(abs(h), h_max)
    rejected = False
    # The phase's previous accepted step and the root of its error norm (floored).
    h_acc, root_acc = 0.0, 0.0
    root_floor = error_root(PREDICTIVE_ERR_FLOOR, exponent)
    status = PHASE_END
    while direction * (t_end - t) > 0.0:
        if nstep >= max_steps or h < MIN_STEP_ULPS * EPS * max(abs(t), 1e-300):
            status = PHASE_FAIL
            break
        dt = h * direction
        last = direction * (t + dt - t_end) >= 0.0
        if last:
            dt = t_end - t
        y_new, f_new, err = method_step(method, contact, t, y, f, dt, cf, c2, rtol, atol)
        nfev += n_stages
        if not err <= 1.0:  # also NaN
            nreject += 1
            shrink = SAFETY / error_root(err, exponent) if err < np.inf else MIN_FACTOR
            h = abs(dt) * max(MIN_FACTOR, shrink)
            rejected = True
            continue
        root = error_root(err, exponent)
        factor = step_factor(root, abs(dt), h_acc, root_acc)
        h_acc, root_acc = abs(dt), max(root, root_floor)
        h_next = min(abs(dt) * (min(1.0, factor) if rejected else factor), h_max)
        rejected = False
        if capacity > 0:
            count = record_step(history, count, capacity, t, dt, w2max, y, f)
        nstep += 1
        if event_on and event_crossed(contact, y, y_new, cf):
            z = method_dense(method, contact, t, y, f, dt, cf, c2, y_new, f_new)
            nfev += n_stages - 1 + n_extra
            x = locate_event(method, contact, y, z, cf)
            y = method_dense_eval(method, x, y, z)
            w2max = max(w2max, y[OMEGA2])
            t += x * dt
            f = f_new
            h = h_next
            status = PHASE_EVENT
            break
        w2max = peak_omega2(y, y_new, f, f_new, dt, w2max)
        y, f = y_new, f_new
        t = t_end if last else t + dt
        h = h_next
    stats[ST_NFEV], stats[ST_NSTEP] = nfev, nstep
    stats[ST_NREJECT], stats[ST_W2MAX] = nreject, w2max
    if capacity > 0:
        history[capacity, 0] = count
    return status, t, y, f, h
