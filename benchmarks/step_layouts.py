"""Which layout could run several strokes per core faster: measured on the DOP853 step.

For the lockstep part of the solver issue.  Measures, in one run:

* **interleaved steps**: one generated straight-line kernel that takes the DOP853 steps
  of 2 (or 4) strokes, their stages written one after the other, stage by stage, so that
  the CPU may overlap them; nanoseconds per stroke-step against the solver's own kernel
  (:func:`tennis_stroke.solver._kernels.step_dop853`) on the same strokes;
* **lanes over rows**: the right-hand side for many strokes at once, each state
  component and coefficient a contiguous 1-D row and a loop over the strokes (the
  layout that SIMD needs), nanoseconds per stroke, and whether LLVM vectorized the loop
  (packed divisions ``vdivpd`` in numba's machine code, ``inspect_asm``); a reduced
  right-hand side that reads 12 rows (the pendulum's accelerations only) beside the
  full one that reads 30;
* **lockstep lanes**: a whole DOP853 step of ``L`` strokes at once, every state
  component, stage and coefficient a row of ``L`` numbers in one flat array (row ``r``
  of stroke ``j`` at ``r * L + j``, ``L`` a compile-time constant), generated from the
  same tableau; nanoseconds per stroke-step for ``L`` = 8, 16 and 32, whether LLVM
  vectorized it, its compile time, and how far its ``y_new`` is from the solver's
  kernel (the right-hand side without the elbow force and the lossy ball, which the
  benchmark's strokes do not have);
* **dense output**: the dense-output coefficients at an event (which evaluate the
  step's stages again, and DOP853's 3 extra stages) against the step itself.

Run: ``.venv/bin/python benchmarks/step_layouts.py`` (about a minute, most of it
compiling; nothing is cached).  Timings vary with the machine's load: read the ratios
within one run.
"""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit
from scipy.integrate import DOP853

from tennis_stroke.model import dynamics as D
from tennis_stroke.model.dynamics import coefficients, rhs_trig
from tennis_stroke.model.params import resolve_params
from tennis_stroke.solver._kernels import coefficient_tuple, dense_dop853, step_dop853

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
from generate_kernels import _method, _tableau  # noqa: E402  (the solver's kernel generator)

FAST = {"cache": False, "error_model": "numpy", "fastmath": {"contract", "arcp"}}
ARGS = ("t", "y", "f0", "h", "cf", "c2", "contact")
LOCALS = ("y_new", "e5", "e3", "scale", "d", "n", *(f"k{i}" for i in range(13)))


def interleaved_source(lanes: int) -> str:
    """A DOP853 step of ``lanes`` strokes in one function: the generated kernel's lines,
    renamed per stroke, the stages interleaved and each stroke's error norm after."""
    src = _method("dop853", DOP853)
    start = next(i for i, line in enumerate(src) if line.startswith("def step_dop853"))
    stop = next(i for i, line in enumerate(src) if i > start and line.startswith("_A_"))
    doc_end = next(i for i in range(start + 1, stop) if src[i].rstrip().endswith('"""'))
    body = [line for line in src[doc_end + 1 : stop] if line.strip()]
    body = [line for line in body if "return" not in line and "if e5 == 0.0" not in line]
    names = re.compile(r"\b(" + "|".join(sorted((*ARGS, *LOCALS), key=len, reverse=True)) + r")\b")
    tags = "abcdefgh"[:lanes]

    def rename(line: str, tag: str) -> str:
        return names.sub(lambda m: f"{m.group(1)}_{tag}", line)

    stage = [line for line in body if "rhs_trig" in line or line.lstrip().startswith("k0 =")]
    stage += [line for line in body if line.lstrip().startswith("y_new =")]
    stage.sort(key=body.index)
    norm = [line for line in body if line not in stage]
    params = ", ".join(f"{a}_{tag}" for tag in tags for a in ARGS)
    out = [f"def step_x(rtol, atol, {params}):"]
    out += [rename(line, tag) for line in stage for tag in tags]
    for tag in tags:
        out += [rename(line, tag) for line in norm]
        out.append(
            f"    err_{tag} = 0.0 if e5_{tag} == 0.0 else abs(h_{tag}) * e5_{tag} / "
            f"math.sqrt((e5_{tag} + 0.01 * e3_{tag}) * n_{tag})"
        )
    out.append("    return (" + ", ".join(f"(y_new_{t}, k12_{t}, err_{t})" for t in tags) + ",)")
    return "\n".join(out) + "\n"


def compiled_interleaved(lanes: int):
    namespace = {"math": __import__("math"), "rhs_trig": rhs_trig}
    exec(compile(interleaved_source(lanes), f"<step_x{lanes}>", "exec"), namespace)
    return njit(**FAST)(namespace["step_x"])


def strokes(n: int):
    rows = coefficients(resolve_params({}), np.linspace(80, 110, n), np.linspace(20, 60, n))
    rng = np.random.default_rng(1)
    ang = rng.uniform(0, 3, (2, n))
    y = np.vstack(
        [np.sin(ang[0]), np.cos(ang[0]), np.sin(ang[1]), np.cos(ang[1]), rng.normal(size=(6, n))]
    )
    return rows, y


def best(fn, *args, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn(*args)
        times.append(time.perf_counter() - start)
    return min(times)


@njit(**FAST)
def state(Y, j, r):
    return (Y[0, j], Y[1, j], Y[2, j], Y[3, j], Y[4, j], Y[5, j], Y[6, j], Y[7, j], Y[8, j],
            Y[9, j] + r * 1e-12)  # fmt: skip


@njit(**FAST)
def scalar_steps(rows, Y, reps, contact):
    acc = 0.0
    for r in range(reps):
        for j in range(4):
            cf = coefficient_tuple(rows[j])
            y = state(Y, j, r)
            f = rhs_trig(0.1, y, cf, 0.5, contact)
            y_new, _, err = step_dop853(0.1, y, f, 1e-3, cf, 0.5, 1e-8, 1e-8, contact)
            acc += y_new[4] + err
    return acc


def interleaved_steps(step2, step4):
    @njit(**FAST)
    def two(rows, Y, reps, contact):
        acc = 0.0
        for r in range(reps):
            for j in range(0, 4, 2):
                ca, cb = coefficient_tuple(rows[j]), coefficient_tuple(rows[j + 1])
                ya, yb = state(Y, j, r), state(Y, j + 1, r)
                fa = rhs_trig(0.1, ya, ca, 0.5, contact)
                fb = rhs_trig(0.1, yb, cb, 0.5, contact)
                a, b = step2(
                    1e-8, 1e-8, 0.1, ya, fa, 1e-3, ca, 0.5, contact,
                    0.1, yb, fb, 1e-3, cb, 0.5, contact,
                )  # fmt: skip
                acc += a[0][4] + a[2] + b[0][4] + b[2]
        return acc

    @njit(**FAST)
    def four(rows, Y, reps, contact):
        acc = 0.0
        for r in range(reps):
            ca, cb = coefficient_tuple(rows[0]), coefficient_tuple(rows[1])
            cc, cd = coefficient_tuple(rows[2]), coefficient_tuple(rows[3])
            ya, yb, yc, yd = state(Y, 0, r), state(Y, 1, r), state(Y, 2, r), state(Y, 3, r)
            fa = rhs_trig(0.1, ya, ca, 0.5, contact)
            fb = rhs_trig(0.1, yb, cb, 0.5, contact)
            fc = rhs_trig(0.1, yc, cc, 0.5, contact)
            fd = rhs_trig(0.1, yd, cd, 0.5, contact)
            a, b, c, d = step4(
                1e-8, 1e-8, 0.1, ya, fa, 1e-3, ca, 0.5, contact, 0.1, yb, fb, 1e-3, cb, 0.5,
                contact, 0.1, yc, fc, 1e-3, cc, 0.5, contact, 0.1, yd, fd, 1e-3, cd, 0.5, contact,
            )  # fmt: skip
            acc += a[0][4] + a[2] + b[0][4] + b[2] + c[0][4] + c[2] + d[0][4] + d[2]
        return acc

    return two, four


@njit(**FAST)
def rows_rhs_reduced(Y, CF, F):
    """The pendulum's accelerations without elbow motion or ball: 12 rows read, 2 written."""
    st_, ct_, sp_, cp_, w1_, w2_ = Y[0], Y[1], Y[2], Y[3], Y[4], Y[5]
    m12_, c1, a1, a2, m11_, m22_ = (CF[D.CF_M12], CF[D.CF_C1], CF[D.CF_A1], CF[D.CF_A2],
                                    CF[D.CF_M11], CF[D.CF_M22])  # fmt: skip
    f4, f5 = F[4], F[5]
    for j in range(Y.shape[1]):
        st, ct, sp, cp, w1, w2 = st_[j], ct_[j], sp_[j], cp_[j], w1_[j], w2_[j]
        sd = sp * ct - cp * st
        p = c1[j] - m12_[j] * w2 * w2 * sd + a1[j] * ct
        q = m12_[j] * w1 * w1 * sd + a2[j] * cp
        mc = m12_[j] * (cp * ct + sp * st)
        det = m11_[j] * m22_[j] - mc * mc
        f4[j] = (p * m22_[j] - q * mc) / det
        f5[j] = (q * m11_[j] - p * mc) / det


@njit(**FAST)
def rows_rhs_full(Y, CF, c2, contact, F):
    """:func:`rhs_trig`'s arithmetic (no elbow force, no dashpot) over rows: 30 read, 10
    written; the contact a 0/1 factor per stroke instead of a branch."""
    st_, ct_, sp_, cp_, w1_, w2_, s_, w_ = Y[0], Y[1], Y[2], Y[3], Y[4], Y[5], Y[8], Y[9]
    vx1, vx2, vy1, vy2 = CF[D.CF_VX1], CF[D.CF_VX2], CF[D.CF_VY1], CF[D.CF_VY2]
    m12_, c1, a1, a2, k_, l1, lh = (CF[D.CF_M12], CF[D.CF_C1], CF[D.CF_A1], CF[D.CF_A2],
                                    CF[D.CF_K], CF[D.CF_L1], CF[D.CF_LH])  # fmt: skip
    cpl, mb, m11_, m22_ = CF[D.CF_COUPLING], CF[D.CF_MB], CF[D.CF_M11], CF[D.CF_M22]
    f0, f1, f2, f3, f4, f5, f6, f7, f8, f9 = (F[0], F[1], F[2], F[3], F[4], F[5], F[6], F[7],
                                              F[8], F[9])  # fmt: skip
    t = 0.1
    for j in range(Y.shape[1]):
        st, ct, sp, cp, w1, w2, s, w = st_[j], ct_[j], sp_[j], cp_[j], w1_[j], w2_[j], s_[j], w_[j]
        ax = vx1[j] + 2.0 * vx2[j] * t
        ay = vy1[j] + 2.0 * vy2[j] * t
        sd = sp * ct - cp * st
        cd = cp * ct + sp * st
        p = c1[j] - c2[j] - m12_[j] * w2 * w2 * sd + a1[j] * (ax * ct + ay * st)
        q = c2[j] + m12_[j] * w1 * w1 * sd + a2[j] * (ax * cp + ay * sp)
        fb = -k_[j] * (s - (l1[j] * st + lh[j] * sp)) * contact[j]
        fr = -fb * cpl[j]
        p -= fr * l1[j] * ct
        q -= fr * lh[j] * cp
        mc = m12_[j] * cd
        det = m11_[j] * m22_[j] - mc * mc
        f0[j], f1[j], f2[j], f3[j] = -w1 * ct, w1 * st, -w2 * cp, w2 * sp
        f4[j] = (p * m22_[j] - q * mc) / det
        f5[j] = (q * m11_[j] - p * mc) / det
        f6[j], f7[j] = -w1, -w2
        f8[j] = w * contact[j]
        f9[j] = (fb / mb[j] - ax) * contact[j]


@njit(**FAST)
def rows_loop_reduced(Y, CF, F, reps):
    for _ in range(reps):
        Y[5, 0] += 1e-12
        rows_rhs_reduced(Y, CF, F)
    return F[4, 0]


@njit(**FAST)
def rows_loop_full(Y, CF, c2, contact, F, reps):
    for _ in range(reps):
        Y[5, 0] += 1e-12
        rows_rhs_full(Y, CF, c2, contact, F)
    return F[4, 0]


@njit(**FAST)
def step_and_dense(cf_row, reps, dense, contact):
    """A swing step (and its dense output), the phase flag a run-time value as in the
    solver (a literal ``False`` would compile the kernels without their contact branch)."""
    cf = coefficient_tuple(cf_row)
    acc = 0.0
    for r in range(reps):
        y = (0.8, 0.6, 0.1, 0.99, -5.0, -20.0 + r * 1e-12, 0.9, 0.1, 0.0, 0.0)
        f = rhs_trig(0.1, y, cf, 0.5, contact)
        y_new, f_new, _ = step_dop853(0.1, y, f, 0.01, cf, 0.5, 1e-8, 1e-8, contact)
        acc += y_new[5]
        if dense:
            z = dense_dop853(0.1, y, f, 0.01, cf, 0.5, y_new, f_new, contact)
            acc += z[3][5]
    return acc


def vectorized(fn) -> str:
    asm = next(iter(fn.inspect_asm().values()))
    return "yes" if "vdivpd" in asm else "no"


def lane_source(lanes: int) -> str:
    """A DOP853 step of ``lanes`` strokes in lockstep over flat rows (see the module
    docstring): each stage one loop over the strokes, the stage sums and the right-hand
    side (:func:`rhs_trig`'s arithmetic, the contact a 0/1 factor ``CON[j]``) written
    out in it, so that LLVM can vectorize the loop."""
    a, c = _tableau(DOP853, True)
    ns = DOP853.n_stages

    def row(r: int) -> str:
        return f"{r} * L + j"

    def cf(name: str) -> str:
        return f"CF[{getattr(D, name)} * L + j]"

    def weighted(coeffs, upto: int, i: int) -> str:
        return " + ".join(
            f"{float(coeffs[m])!r} * K[{row(10 * m + i)}]" for m in range(upto) if coeffs[m] != 0.0
        )

    out = [
        f"L = {lanes}",
        "",
        "",
        "def lane_step(T, Y, F0, H, CF, C2, CON, K, YN, ERR, rtol, atol):",
    ]
    out += ["    for i in range(10 * L):", "        K[i] = F0[i]"]  # stage 0: f(t, y), given
    for s in range(1, ns + 1):
        coeffs = a[s] if s < ns else DOP853.B
        out += ["    for j in range(L):", "        h = H[j]"]
        for i in range(10):
            out.append(f"        y{i} = Y[{row(i)}] + h * ({weighted(coeffs, s, i)})")
            if s == ns:
                out.append(f"        YN[{row(i)}] = y{i}")
        t = f"(T[j] + {float(c[s]) if s < ns else 1.0!r} * h)"
        k = [f"K[{row(10 * s + i)}]" for i in range(10)]
        out += [
            f"        ax = {cf('CF_VX1')} + 2.0 * {cf('CF_VX2')} * {t}",
            f"        ay = {cf('CF_VY1')} + 2.0 * {cf('CF_VY2')} * {t}",
            "        sd = y2 * y1 - y3 * y0",
            "        cd = y3 * y1 + y2 * y0",
            f"        m12 = {cf('CF_M12')}",
            f"        p = {cf('CF_C1')} - C2[j] - m12 * y5 * y5 * sd"
            f" + {cf('CF_A1')} * (ax * y1 + ay * y0)",
            f"        q = C2[j] + m12 * y4 * y4 * sd + {cf('CF_A2')} * (ax * y3 + ay * y2)",
            f"        fb = -{cf('CF_K')} * (y8 - ({cf('CF_L1')} * y0 + {cf('CF_LH')} * y2))"
            " * CON[j]",
            f"        fr = -fb * {cf('CF_COUPLING')}",
            f"        p -= fr * {cf('CF_L1')} * y1",
            f"        q -= fr * {cf('CF_LH')} * y3",
            "        mc = m12 * cd",
            f"        det = {cf('CF_M11')} * {cf('CF_M22')} - mc * mc",
            f"        {k[0]}, {k[1]}, {k[2]}, {k[3]} = -y4 * y1, y4 * y0, -y5 * y3, y5 * y2",
            f"        {k[4]} = (p * {cf('CF_M22')} - q * mc) / det",
            f"        {k[5]} = (q * {cf('CF_M11')} - p * mc) / det",
            f"        {k[6]}, {k[7]}, {k[8]} = -y4, -y5, y9 * CON[j]",
            f"        {k[9]} = (fb / {cf('CF_MB')} - ax) * CON[j]",
        ]
    out += ["    for j in range(L):", "        e5 = 0.0", "        e3 = 0.0"]
    for i in range(10):
        on = "" if i < 8 else " * CON[j]"
        out += [
            f"        sc = atol + rtol * max(abs(Y[{row(i)}]), abs(YN[{row(i)}]))",
            f"        d = ({weighted(DOP853.E5, ns + 1, i)}) / sc{on}",
            "        e5 += d * d",
            f"        d = ({weighted(DOP853.E3, ns + 1, i)}) / sc{on}",
            "        e3 += d * d",
        ]
    out.append(
        "        ERR[j] = abs(H[j]) * e5 / math.sqrt((e5 + 0.01 * e3) * (8.0 + 2.0 * CON[j]))"
    )
    return "\n".join(out) + "\n"


def lane_measurement(lanes: int, contact: bool) -> tuple[float, str, float, float, float]:
    """ns per stroke-step, vectorized?, compile seconds, and the largest difference of
    ``y_new`` and of the error norm from the solver's kernel on the same strokes, each
    relative to the larger of the value and 1."""
    namespace = {"math": __import__("math")}
    exec(compile(lane_source(lanes), f"<lane_step{lanes}>", "exec"), namespace)
    step = njit(**FAST)(namespace["lane_step"])

    @njit(**FAST)
    def run(T, Y, F0, H, CF, C2, CON, reps, nudge):
        K = np.zeros(13 * 10 * lanes)
        YN = np.empty(10 * lanes)
        ERR = np.empty(lanes)
        acc = 0.0
        for _ in range(reps):
            Y[5 * lanes] += nudge  # a new input every time (nudge 0 for the check)
            step(T, Y, F0, H, CF, C2, CON, K, YN, ERR, 1e-8, 1e-8)
            acc += YN[4 * lanes] + ERR[lanes - 1]
        return acc, YN, ERR

    rows, y_cols = strokes(lanes)
    CF = np.ascontiguousarray(rows.T).ravel()
    T, H, C2 = np.full(lanes, 0.1), np.full(lanes, 1e-3), np.full(lanes, 0.5)
    CON = np.full(lanes, 1.0 if contact else 0.0)
    refs = [scalar_step(rows[j], y_cols[:, j].copy(), contact) for j in range(lanes)]
    ref = np.array([y_new for y_new, _, _ in refs]).T
    F0 = np.array([f0 for _, f0, _ in refs]).T.ravel().copy()
    ref_err = np.array([err for _, _, err in refs])
    start = time.perf_counter()
    run(T, y_cols.ravel().copy(), F0, H, CF, C2, CON, 0, 0.0)
    compile_s = time.perf_counter() - start
    _, y_new, err = run(T, y_cols.ravel().copy(), F0, H, CF, C2, CON, 1, 0.0)
    # The same step up to the order of its sums: y_new to round-off, the error norm (a
    # difference of stage sums, whose last digits are cancellation) far below the
    # acceptance threshold 1.  A kernel that computes another step fails by far.
    dy = float(np.max(np.abs(y_new.reshape(10, lanes) - ref) / np.maximum(np.abs(ref), 1.0)))
    derr = float(np.max(np.abs(err - ref_err) / np.maximum(ref_err, 1.0)))
    if not (dy <= 1e-12 and derr <= 1e-6):
        raise SystemExit(
            f"the lockstep kernel's step differs from step_dop853's: {dy:.1e}, {derr:.1e}"
        )
    asm = next(iter(step.inspect_asm().values()))
    reps = 400_000 // lanes
    ns = best(run, T, y_cols.ravel().copy(), F0, H, CF, C2, CON, reps, 1e-12) / (reps * lanes) * 1e9
    return ns, "yes" if "vdivpd" in asm else "no", compile_s, dy, derr


@njit(**FAST)
def scalar_step(cf_row, y_col, contact):
    cf = coefficient_tuple(cf_row)
    y = (y_col[0], y_col[1], y_col[2], y_col[3], y_col[4], y_col[5], y_col[6], y_col[7],
         y_col[8], y_col[9])  # fmt: skip
    f = rhs_trig(0.1, y, cf, 0.5, contact)
    y_new, _, err = step_dop853(0.1, y, f, 1e-3, cf, 0.5, 1e-8, 1e-8, contact)
    return np.array(y_new), np.array(f), err


def check_interleaved(step2, step4, rows, y_cols):
    """The interleaved kernels compute what the solver's kernel computes, bit for bit."""

    @njit(**FAST)
    def same(rows, Y, contact):
        cs = (coefficient_tuple(rows[0]), coefficient_tuple(rows[1]),
              coefficient_tuple(rows[2]), coefficient_tuple(rows[3]))  # fmt: skip
        ys = (state(Y, 0, 0), state(Y, 1, 0), state(Y, 2, 0), state(Y, 3, 0))
        fs = (rhs_trig(0.1, ys[0], cs[0], 0.5, contact),
              rhs_trig(0.1, ys[1], cs[1], 0.5, contact),
              rhs_trig(0.1, ys[2], cs[2], 0.5, contact),
              rhs_trig(0.1, ys[3], cs[3], 0.5, contact))  # fmt: skip
        refs = (step_dop853(0.1, ys[0], fs[0], 1e-3, cs[0], 0.5, 1e-8, 1e-8, contact),
                step_dop853(0.1, ys[1], fs[1], 1e-3, cs[1], 0.5, 1e-8, 1e-8, contact),
                step_dop853(0.1, ys[2], fs[2], 1e-3, cs[2], 0.5, 1e-8, 1e-8, contact),
                step_dop853(0.1, ys[3], fs[3], 1e-3, cs[3], 0.5, 1e-8, 1e-8, contact))  # fmt: skip
        two = step2(1e-8, 1e-8, 0.1, ys[0], fs[0], 1e-3, cs[0], 0.5, contact,
                    0.1, ys[1], fs[1], 1e-3, cs[1], 0.5, contact)  # fmt: skip
        four = step4(1e-8, 1e-8, 0.1, ys[0], fs[0], 1e-3, cs[0], 0.5, contact,
                     0.1, ys[1], fs[1], 1e-3, cs[1], 0.5, contact,
                     0.1, ys[2], fs[2], 1e-3, cs[2], 0.5, contact,
                     0.1, ys[3], fs[3], 1e-3, cs[3], 0.5, contact)  # fmt: skip
        return two == (refs[0], refs[1]) and four == refs

    if not (same(rows, y_cols, False) and same(rows, y_cols, True)):
        raise SystemExit("an interleaved kernel differs from step_dop853")


def main() -> int:
    rows, y_cols = strokes(4)
    step2, step4 = compiled_interleaved(2), compiled_interleaved(4)
    check_interleaved(step2, step4, rows, y_cols)
    two, four = interleaved_steps(step2, step4)
    reps = 50_000
    print("| measurement | value |\n|---|---|")
    for contact in (False, True):
        phase = "contact" if contact else "swing"
        for name, fn in (
            ("one stroke", scalar_steps),
            ("2 interleaved", two),
            ("4 interleaved", four),
        ):
            fn(rows, y_cols, 2, contact)
            ns = best(fn, rows, y_cols, reps, contact) / (4 * reps) * 1e9
            print(f"| DOP853 step ({phase}), {name}: ns per stroke-step | {ns:.0f} |")

    for lanes in (8, 64):
        cf_rows, y = strokes(lanes)
        CF = np.ascontiguousarray(cf_rows.T)
        F = np.empty_like(y)
        ones = np.ones(lanes)
        n = 2_000_000 // lanes
        rows_loop_reduced(y.copy(), CF, F, 2)
        rows_loop_full(y.copy(), CF, ones, ones, F, 2)
        reduced = best(rows_loop_reduced, y.copy(), CF, F, n) / (n * lanes) * 1e9
        full = best(rows_loop_full, y.copy(), CF, ones, ones, F, n) / (n * lanes) * 1e9
        print(
            f"| reduced right-hand side over rows (12 read), {lanes} strokes: ns per stroke "
            f"| {reduced:.1f} (vectorized: {vectorized(rows_rhs_reduced)}) |"
        )
        print(
            f"| full right-hand side over rows (30 read), {lanes} strokes: ns per stroke "
            f"| {full:.1f} (vectorized: {vectorized(rows_rhs_full)}) |"
        )

    for lanes in (8, 16, 32):
        for contact in (False, True):
            ns, vec, compile_s, dy, derr = lane_measurement(lanes, contact)
            phase = "contact" if contact else "swing"
            print(
                f"| DOP853 step in lockstep ({phase}), {lanes} strokes over flat rows: ns per "
                f"stroke-step | {ns:.0f} (vectorized: {vec}; compiled in {compile_s:.1f} s; "
                f"y_new within {dy:.1e}, error norm within {derr:.1e} of the solver's kernel's) |"
            )

    step_and_dense(rows[0], 2, True, False)
    step_and_dense(rows[0], 2, False, False)
    step_ns = best(step_and_dense, rows[0], 200_000, False, False) / 200_000 * 1e9
    both_ns = best(step_and_dense, rows[0], 200_000, True, False) / 200_000 * 1e9
    print(f"| DOP853 step alone (swing): ns | {step_ns:.0f} |")
    print(f"| DOP853 dense-output coefficients after it: ns | {both_ns - step_ns:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
