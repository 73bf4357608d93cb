"""Generate ``src/tennis_stroke/solver/_kernels.py``: unrolled Runge-Kutta kernels from tableaux.

The Butcher tableaux of Dormand-Prince 5(4) and 8(5,3) (scipy's ``RK45`` and ``DOP853``
classes carry the published coefficients) are written out as straight-line code on
tuples, one step function per method for both phases (a run-time ``contact`` flag: the
ball's spring acts, and the error norm covers its 2 components besides the pendulum's
8; in the free swing the ball's derivatives are 0, so its state is carried over
exactly), all calling :func:`tennis_stroke.model.dynamics.rhs_trig`.  One function for
both phases instead of one each halves the largest part of the cold compilation, at no
measured cost per stroke.  States are tuples, not
arrays, so numba passes them by value (no reference counting per call) and LLVM keeps
them in registers; zero coefficients disappear.  This makes a step several times faster
than loops over padded tableau arrays.  The dense output, needed only at an event (twice a
stroke), is the exception: loops over the tableau, one function per method for both
phases, because its straight-line form cost more compile time than anything else.  The
output is committed; a test checks that it is up to date.

Usage: ``python tools/generate_kernels.py [--check]``
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from scipy.integrate import DOP853, RK45

ROOT = Path(__file__).resolve().parents[1]
TARGET = ROOT / "src" / "tennis_stroke" / "solver" / "_kernels.py"
DYNAMICS = ROOT / "src" / "tennis_stroke" / "model" / "dynamics.py"
N_STATE = 10  # trig layout with the ball; see tennis_stroke.model.dynamics
N_SWING = 8  # components integrated in the free swing (the pendulum)


def _combo(coeffs, rows, var: str, i: int) -> str:
    terms = [f"{float(coeffs[j])!r} * {var}{j}[{i}]" for j in rows if coeffs[j] != 0.0]
    return " + ".join(terms) if terms else "0.0"


def _state(n: int, expr) -> str:
    """Tuple of ``N_STATE`` components: ``expr(i)`` for the first ``n``, ``y[i]`` after."""
    return "(" + ", ".join(expr(i) if i < n else f"y[{i}]" for i in range(N_STATE)) + ")"


def _stages(a, c, first: int, last: int, n: int, contact: str) -> list[str]:
    out = []
    for s in range(first, last):
        arg = _state(n, lambda i, s=s: f"y[{i}] + h * ({_combo(a[s], range(s), 'k', i)})")
        out.append(f"    k{s} = rhs_trig(t + {float(c[s])!r} * h, {arg}, cf, c2, {contact})")
    return out


def _tableau(cls, extra: bool):
    a = [list(r) for r in cls.A]
    c = list(cls.C)
    if extra:  # stage n_stages is f(t+h, y_new) (FSAL), then the dense-output stages
        a += [list(cls.B)] + [list(r) for r in cls.A_EXTRA]
        c += [1.0] + list(cls.C_EXTRA)
    return a, c


def _method(name: str, cls) -> list[str]:
    extra = name == "dop853"
    ns = cls.n_stages
    a, c = _tableau(cls, extra)
    e5 = cls.E5 if extra else cls.E
    y_new = _state(N_STATE, lambda i: f"y[{i}] + h * ({_combo(cls.B, range(ns), 'k', i)})")
    out = [
        "",
        "",
        "@njit(**JIT_FAST_INNER)",
        f"def step_{name}(t, y, f0, h, cf, c2, rtol, atol, contact):",
        f'    """{name.upper()} step: ``(y_new, f(t+h, y_new), error)``; ``contact``: the ball',
        f"    spring acts and the error norm covers {N_STATE} components, else {N_SWING}",
        '    (the ball\'s derivatives are then 0, so its state is carried over exactly)."""',
        "    k0 = f0",
    ]
    out += _stages(a, c, 1, ns, N_STATE, "contact")
    out += [
        f"    y_new = {y_new}",
        f"    k{ns} = rhs_trig(t + h, y_new, cf, c2, contact)",
        "    e5 = 0.0",
    ]
    if extra:
        out.append("    e3 = 0.0")

    def norm_terms(i: int, indent: str) -> list[str]:
        lines = [
            f"{indent}scale = atol + rtol * max(abs(y[{i}]), abs(y_new[{i}]))",
            f"{indent}d = ({_combo(e5, range(ns + 1), 'k', i)}) / scale",
            f"{indent}e5 += d * d",
        ]
        if extra:
            lines += [
                f"{indent}d = ({_combo(cls.E3, range(ns + 1), 'k', i)}) / scale",
                f"{indent}e3 += d * d",
            ]
        return lines

    for i in range(N_SWING):
        out += norm_terms(i, "    ")
    out += [f"    n = {float(N_SWING)!r}", "    if contact:", f"        n = {float(N_STATE)!r}"]
    for i in range(N_SWING, N_STATE):
        out += norm_terms(i, "        ")
    if extra:
        out += [
            "    if e5 == 0.0:",
            f"        return y_new, k{ns}, 0.0",
            f"    return y_new, k{ns}, abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)",
        ]
    else:
        out.append(f"    return y_new, k{ns}, abs(h) * math.sqrt(e5 / n)")
    return out + _dense(name, cls)


def _array(name: str, rows) -> list[str]:
    """A module-level float array (numba compiles it in as a constant)."""
    body = ",\n    ".join("[" + ", ".join(repr(float(v)) for v in row) + "]" for row in rows)
    return [f"{name} = np.array([\n    {body},\n])"]


def _dense(name: str, cls) -> list[str]:
    """Dense-output coefficients of one method for both phases, as loops over the tableau.

    Called only at an event (twice a stroke), so compile time counts more than speed
    here: straight-line dense output was the largest part of the cold compilation
    (``benchmarks/compile_time.py``).
    """
    extra = name == "dop853"
    ns = cls.n_stages
    a, c = _tableau(cls, extra)
    n_k = len(c) if extra else ns + 1
    tag = name.upper()
    lines = ["", ""]
    lines += _array(f"_A_{tag}", [[*row, *[0.0] * (n_k - len(row))] for row in a])
    lines += [f"_C_{tag} = np.array([{', '.join(repr(float(v)) for v in c)}])"]
    if extra:
        lines += _array(f"_D_{tag}", [list(r) for r in cls.D])
    else:
        lines += _array(f"_P_{tag}", [list(cls.P[:, col]) for col in range(cls.P.shape[1])])
    comps = range(N_STATE)

    def sums(coeffs: str, row: str, stop: str, indent: str) -> list[str]:
        """``a{i} = sum over m < stop of coeffs[row, m] * k[m, i]``, in the order of ``m``,
        one accumulator per component: independent sums that the CPU overlaps (a loop
        over the components outside the loop over the stages made one dependent chain
        of multiply-adds per component).  The same operations in the same order: alone,
        the function gives the same bits as before; compiled into the stroke, the
        multiply-adds may be fused differently, which moves last bits."""
        return [
            indent + " = ".join(f"a{i}" for i in comps) + " = 0.0",
            f"{indent}for m in range({stop}):",
            f"{indent}    c = {coeffs}[{row}, m]",
            *(f"{indent}    a{i} += c * k[m, {i}]" for i in comps),
        ]

    y_stage = ", ".join(
        f"y[{i}] + h * a{i}" if i < N_SWING else f"y[{i}] + h * a{i} if contact else y[{i}]"
        for i in comps
    )
    lines += [
        "",
        "",
        "@njit(**JIT_FAST_INNER)",
        f"def dense_{name}(t, y, f0, h, cf, c2, y_new, f_new, contact):",
        '    """Dense-output coefficients (7 rows) of the step ``y -> y_new`` (``contact``:',
        '    10 integrated components, else 8)."""',
        f"    k = np.zeros(({n_k + (cls.D.shape[0] if extra else cls.P.shape[1])}, {N_STATE}))",
        f"    for i in range({N_STATE}):",
        "        k[0, i] = f0[i]",
        f"        k[{ns}, i] = f_new[i]",
        f"    for s in range(1, {n_k}):",
        f"        if s == {ns}:",
        "            continue",
        *sums(f"_A_{tag}", "s", "s", "        "),
        f"        ks = rhs_trig(t + _C_{tag}[s] * h, ({y_stage}), cf, c2, contact)",
        f"        for i in range({N_STATE}):",
        "            k[s, i] = ks[i]",
    ]
    zero = "(" + ", ".join("0.0" for _ in comps) + ")"

    def row(expr) -> str:
        """A row of z: ``expr(i)`` for the integrated components, 0 for the ball's in the
        swing."""
        return (
            "("
            + ", ".join(expr(i) if i < N_SWING else f"{expr(i)} if contact else 0.0" for i in comps)
            + ")"
        )

    if extra:
        lines += [
            "    z0 = " + row(lambda i: f"y_new[{i}] - y[{i}]"),
            "    z1 = " + row(lambda i: f"h * k[0, {i}] - (y_new[{i}] - y[{i}])"),
            "    z2 = "
            + row(lambda i: f"2.0 * (y_new[{i}] - y[{i}]) - h * (k[{ns}, {i}] + k[0, {i}])"),
        ]
        first = 3
    else:
        first = 0
    n_rows = cls.D.shape[0] if extra else cls.P.shape[1]
    coeffs = f"_D_{tag}" if extra else f"_P_{tag}"
    # The interpolant's rows from the weighted sums go below the stages in ``k``.
    lines += [f"    for r in range({n_rows}):"]
    lines += sums(coeffs, "r", str(n_k), "        ")
    lines += [f"        k[{n_k} + r, {i}] = h * a{i}" for i in range(N_SWING)]
    lines += [
        f"        k[{n_k} + r, {i}] = h * a{i} if contact else 0.0" for i in range(N_SWING, N_STATE)
    ]
    rows = [f"z{r}" for r in range(first)]
    rows += ["(" + ", ".join(f"k[{n_k + r}, {i}]" for i in comps) + ")" for r in range(n_rows)]
    rows += [zero] * (7 - first - n_rows)
    lines.append("    return (" + ", ".join(rows) + ")")
    return lines


def _dense_evals() -> list[str]:
    dp54 = ",\n            ".join(
        f"y[{i}] + x * (z[0][{i}] + x * (z[1][{i}] + x * (z[2][{i}] + x * z[3][{i}])))"
        for i in range(N_STATE)
    )
    dop853 = []
    for i in range(N_STATE):
        acc = f"z[6][{i}] * x"
        for m in range(5, -1, -1):
            acc = f"({acc} + z[{m}][{i}]) * {'u' if m % 2 else 'x'}"
        dop853.append(f"y[{i}] + {acc}")
    return [
        "",
        "",
        "@njit(**JIT_FAST_INNER)",
        "def dense_eval_dp54(x, y, z):",
        '    """Shampine\'s 4th-order interpolant at the fraction ``x`` of the step."""',
        f"    return ({dp54})",
        "",
        "",
        "@njit(**JIT_FAST_INNER)",
        "def dense_eval_dop853(x, y, z):",
        '    """The 7th-order DOP853 interpolant at the fraction ``x`` of the step."""',
        "    u = 1.0 - x",
        "    return (" + ",\n            ".join(dop853) + ")",
    ]


def render() -> str:
    spec = importlib.util.spec_from_file_location("dynamics", DYNAMICS)
    dynamics = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dynamics)  # the layout only; not the package (it imports us)
    N_CF = dynamics.N_CF  # noqa: N806

    cf = ", ".join(f"row[{i}]" for i in range(N_CF))
    lines = [
        '"""Unrolled Runge-Kutta kernels. GENERATED by tools/generate_kernels.py: do not edit."""',
        "",
        "import math",
        "",
        "import numpy as np",
        "from numba import njit",
        "",
        "from ..model.dynamics import JIT_FAST, JIT_FAST_INNER, rhs_trig",
        "",
        "# Indexed by method id (0: DP54, 1: DOP853).",
        f"N_STAGES_BY_ID = ({RK45.n_stages}, {DOP853.n_stages})",
        f"N_EXTRA_BY_ID = (0, {len(DOP853.C_EXTRA)})",
        f"ERROR_ORDER_BY_ID = ({RK45.error_estimator_order}, {DOP853.error_estimator_order})",
        "",
        "",
        "@njit(**JIT_FAST)",
        "def coefficient_tuple(row):",
        '    """A row of stroke coefficients as a tuple (passed by value, no reference count)."""',
        f"    return ({cf})",
    ]
    lines += _dense_evals()
    lines += _method("dp54", RK45)
    lines += _method("dop853", DOP853)
    lines += [
        "",
        "",
        "#: The kernels of each method id: (step, dense-output coefficients, dense-output",
        "#: evaluation); chosen when the solver is compiled.",
        "KERNELS_BY_ID = (",
    ]
    for tag in ("dp54", "dop853"):
        lines.append(f"    (step_{tag}, dense_{tag}, dense_eval_{tag}),")
    lines.append(")")
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    text = render()
    if "--check" in argv:
        if TARGET.read_text() != text:
            print(f"{TARGET} is out of date: run python tools/generate_kernels.py")
            return 1
        return 0
    TARGET.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
