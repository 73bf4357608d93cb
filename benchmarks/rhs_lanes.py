"""The right-hand side's throughput when evaluations do not wait for each other: for the
lockstep-lanes part of the solver issue, which layout to build.

Measures nanoseconds per evaluation of the model's right-hand side (no elbow force) in
the free swing and in the contact, for 8 different strokes evaluated over and over:

* scalar: :func:`tennis_stroke.model.dynamics.rhs_trig` on tuples, as the solver calls
  it, one stroke after the other (independent evaluations, so the CPU overlaps them);
* lanes: the same arithmetic in a structure-of-arrays layout, a loop over 8 lanes that
  LLVM may vectorize;

and nanoseconds per DOP853 step (the generated kernel, fixed step, the contact flag a
run-time value as in the solver) of one stroke, against steps of two strokes taken one
after the other in the same loop.

Compare with the solver's cost per evaluation inside a stroke (``make bench``: µs per
stroke over evaluations per stroke), where each stage waits for the one before.

Run: ``.venv/bin/python benchmarks/rhs_lanes.py`` (a few seconds; timings vary with the
machine's load).
"""

import time

import numpy as np
from numba import njit

from tennis_stroke.model import dynamics as D
from tennis_stroke.model.dynamics import coefficients, rhs_trig
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver._kernels import coefficient_tuple, step_dop853

FAST = {"cache": False, "error_model": "numpy", "fastmath": {"contract", "arcp"}}


@njit(**FAST)
def scalar_loop(cf_rows, Y, c2, n_rep, contact):
    acc = 0.0
    L = Y.shape[1]
    for r in range(n_rep):
        for j in range(L):
            cf = coefficient_tuple(cf_rows[j])
            y = (
                Y[0, j],
                Y[1, j],
                Y[2, j],
                Y[3, j],
                Y[4, j],
                Y[5, j],
                Y[6, j],
                Y[7, j],
                Y[8, j],
                Y[9, j] + r * 1e-9,
            )
            f = rhs_trig(0.1, y, cf, c2, contact)
            acc += f[4] + f[5] + f[9]
    return acc


@njit(**FAST)
def lanes_rhs(t, Y, CF, c2, contact, F):
    L = Y.shape[1]
    for j in range(L):
        st = Y[0, j]
        ct = Y[1, j]
        sp = Y[2, j]
        cp = Y[3, j]
        w1 = Y[4, j]
        w2 = Y[5, j]
        s = Y[8, j]
        w = Y[9, j]
        ax = CF[D.CF_VX1, j] + 2.0 * CF[D.CF_VX2, j] * t
        ay = CF[D.CF_VY1, j] + 2.0 * CF[D.CF_VY2, j] * t
        sd = sp * ct - cp * st
        cd = cp * ct + sp * st
        m12 = CF[D.CF_M12, j]
        p = CF[D.CF_C1, j] - c2[j] - m12 * w2 * w2 * sd + CF[D.CF_A1, j] * (ax * ct + ay * st)
        q = c2[j] + m12 * w1 * w1 * sd + CF[D.CF_A2, j] * (ax * cp + ay * sp)
        fb = -CF[D.CF_K, j] * (s - (CF[D.CF_L1, j] * st + CF[D.CF_LH, j] * sp)) * contact
        fr = -fb * CF[D.CF_COUPLING, j]
        p -= fr * CF[D.CF_L1, j] * ct
        q -= fr * CF[D.CF_LH, j] * cp
        m11 = CF[D.CF_M11, j]
        m22 = CF[D.CF_M22, j]
        mc = m12 * cd
        det = m11 * m22 - mc * mc
        F[0, j] = -w1 * ct
        F[1, j] = w1 * st
        F[2, j] = -w2 * cp
        F[3, j] = w2 * sp
        F[4, j] = (p * m22 - q * mc) / det
        F[5, j] = (q * m11 - p * mc) / det
        F[6, j] = -w1
        F[7, j] = -w2
        F[8, j] = w * contact
        F[9, j] = (fb / CF[D.CF_MB, j] - ax) * contact


@njit(**FAST)
def lanes_loop(CF, Y, c2, n_rep, contact):
    F = np.empty_like(Y)
    acc = 0.0
    for _ in range(n_rep):
        Y[9, 0] += 1e-9
        lanes_rhs(0.1, Y, CF, c2, contact, F)
        acc += F[4, 0] + F[5, -1] + F[9, 3]
    return acc


if __name__ != "__main__":
    raise SystemExit("a benchmark: run it as a script")
L = 8
th = np.linspace(80, 110, L)
de = np.linspace(20, 60, L)
rows = coefficients(resolve_params({}), th, de)
rng = np.random.default_rng(1)
ang = rng.uniform(0, 3, (2, L))
Y = np.vstack(
    [np.sin(ang[0]), np.cos(ang[0]), np.sin(ang[1]), np.cos(ang[1]), rng.normal(size=(6, L))]
)
CF = np.ascontiguousarray(rows.T)
c2 = np.full(L, 1.0)
for contact in (0.0, 1.0):
    n = 200000
    scalar_loop(rows, Y, 1.0, 10, contact != 0.0)
    lanes_loop(CF, Y.copy(), c2, 10, contact)
    ts = []
    for _ in range(3):
        t = time.perf_counter()
        scalar_loop(rows, Y, 1.0, n, contact != 0.0)
        ts.append(time.perf_counter() - t)
    tl = []
    for _ in range(3):
        Yc = Y.copy()
        t = time.perf_counter()
        lanes_loop(CF, Yc, c2, n, contact)
        tl.append(time.perf_counter() - t)
    scalar_ns, lanes_ns = (min(x) / (n * L) * 1e9 for x in (ts, tl))
    phase = "contact" if contact else "swing"
    print(f"{phase}: scalar {scalar_ns:.1f} ns per evaluation, {L} lanes {lanes_ns:.1f} ns")


Y0 = (1.0, 0.0, 0.5, 0.8, 0.0, 0.0, 1.5, 0.8, 0.0, 0.0)


@njit(**FAST)
def one_stroke(cfa, n, h, contact):
    ya, t = Y0, 0.0
    fa = rhs_trig(0.0, ya, cfa, 0.0, False)
    for _ in range(n):
        ya, fa, _ = step_dop853(t, ya, fa, h, cfa, 0.0, 1e-8, 1e-8, contact)
        t += h
        if t > 0.2:
            ya, t = Y0, 0.0
            fa = rhs_trig(0.0, ya, cfa, 0.0, False)
    return ya[4]


@njit(**FAST)
def two_strokes(cfa, cfb, n, h, contact):
    ya, yb, t = Y0, Y0, 0.0
    fa, fb = rhs_trig(0.0, ya, cfa, 0.0, False), rhs_trig(0.0, yb, cfb, 0.0, False)
    for _ in range(n):
        ya, fa, _ = step_dop853(t, ya, fa, h, cfa, 0.0, 1e-8, 1e-8, contact)
        yb, fb, _ = step_dop853(t, yb, fb, h, cfb, 0.0, 1e-8, 1e-8, contact)
        t += h
        if t > 0.2:
            ya, yb, t = Y0, Y0, 0.0
            fa, fb = rhs_trig(0.0, ya, cfa, 0.0, False), rhs_trig(0.0, yb, cfb, 0.0, False)
    return ya[4] + yb[4]


cfa, cfb = coefficient_tuple(rows[0]), coefficient_tuple(rows[1])
one_stroke(cfa, 10, 0.01, False)
two_strokes(cfa, cfb, 10, 0.01, False)
n = 200000
t1, t2 = [], []
for _ in range(3):
    t = time.perf_counter()
    one_stroke(cfa, n, 0.01, False)
    t1.append(time.perf_counter() - t)
    t = time.perf_counter()
    two_strokes(cfa, cfb, n, 0.01, False)
    t2.append(time.perf_counter() - t)
one_ns, two_ns = min(t1) / n * 1e9, min(t2) / n * 1e9
print(f"DOP853 step: one stroke {one_ns:.0f} ns; two strokes in one loop {two_ns:.0f} ns")
