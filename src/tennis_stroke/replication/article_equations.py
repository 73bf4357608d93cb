"""The model's equations as the article prints them, read from the code that computes
them: the statements of :func:`~tennis_stroke.model.dynamics.rhs_trig` (the equations of
motion), :func:`~tennis_stroke.model.dynamics.elbow_pulse` (the elbow force of Sec. VI)
and the constants :func:`~tennis_stroke.model.dynamics.coefficients` packs, parsed from
``model/dynamics.py`` (never imported: the article's job loads no numba) and written as
Typst math.

Only the notation is written here (:data:`NAMES`, :data:`COEFFICIENTS`,
:data:`PARAMETERS`: what each name of the code stands for); the equations themselves are
the code's.  A name, a condition or a statement without a notation raises
:class:`EquationError`, so the printed equations can never drift from the code
(``tests/replication/test_article_equations.py`` renders them).
"""

from __future__ import annotations

import ast
import re
from collections.abc import Sequence
from functools import cache
from pathlib import Path

from .._imports import module_path

#: The module the equations are read from.
SOURCE = module_path("model.dynamics")

#: The local names of the rendered functions (their state, forces and shorthands).
NAMES = {
    "t": "t",
    "st": "sin theta",
    "ct": "cos theta",
    "sp": "sin phi",
    "cp": "cos phi",
    "sd": "sin(phi - theta)",
    "cd": "cos(phi - theta)",
    "w1": "omega_1",
    "w2": "omega_2",
    "s": "s",
    "w": "w",
    "c2": "C_2",
    "ax": "a_x",
    "ay": "a_y",
    "px": "p_x",
    "py": "p_y",
    "u": "u",
    "pulse": "g",
    "p": "P",
    "q": "Q",
    "m11": "M_11",
    "m22": "M_22",
    "m12": "M_12",
    "mc": "M_12 cos(phi - theta)",
    "det": "D",
    "force_on_ball": "F_b",
    "force_on_racket": "F_r",
    "ds": "dot(s)",
    "dw": "dot(w)",
    "h1": "h_1",
    "h2": "h_2",
    "psi": "psi_F",
}
#: Shorthands: names the code gives an expression of others, substituted where they are
#: used rather than printed as an equation of their own.
SHORTHANDS = ("sd", "cd", "m11", "m22", "m12", "mc")
#: The per-stroke constants (``cf[CF_*]``).
COEFFICIENTS = {
    "CF_L1": "L_1",
    "CF_LH": "ell_H",
    "CF_M11": "M_11",
    "CF_M22": "M_22",
    "CF_M12": "M_12",
    "CF_A1": "A_1",
    "CF_A2": "A_2",
    "CF_C1": "C_1",
    "CF_K": "k",
    "CF_MB": "m_b",
    "CF_COUPLING": "kappa",
    "CF_DAMP": "c",
    "CF_VX1": "v_(x 1)",
    "CF_VX2": "v_(x 2)",
    "CF_VY1": "v_(y 1)",
    "CF_VY2": "v_(y 2)",
    "CF_FX": "f_x",
    "CF_FY": "f_y",
    "CF_TF": "t_F",
    "CF_TD": "t_d",
}
#: The model's parameters (``g["..."]`` in :func:`coefficients`).
PARAMETERS = {
    "L1": "L_1",
    "L2": "L_2",
    "M1": "M_1",
    "M2": "M_2",
    "I1_cm": "I_1",
    "I2_cm": "I_2",
    "h_hit": "h_H",
    "F0": "F_0",
    "elbow_force_mass": "m_E",
}
#: Functions of the math module, as Typst writes them.
FUNCTIONS = {"exp": "exp", "sin": "sin", "cos": "cos", "sqrt": "sqrt"}
#: The conditions of the code's branches, in words.
CONDITIONS = {
    "contact": "during the contact (the ball on the strings)",
    "cf[CF_FORCE_ON] != 0.0": "with the extra elbow force of Sec. VI",
    "cf[CF_DAMP] != 0.0": "for a ball that loses energy (restitution below 1; the paper's "
    "ball is elastic, c = 0)",
}
#: The functions rendered, each with what its returned values are (by position; a
#: position left out is not printed: the sines' and cosines' rates follow from theta's
#: and phi's) and a title.
FUNCTIONS_SHOWN = {
    "rhs_trig": (
        "the equations of motion (rhs_trig)",
        {4: "dot(omega)_1", 5: "dot(omega)_2", 6: "dot(theta)", 7: "dot(phi)"},
    ),
    "elbow_pulse": ("the elbow force's pulse, Eq. 14 (elbow_pulse)", {0: "p_x", 1: "p_y"}),
}
#: The constants of :func:`coefficients` printed (the others are parameters themselves).
CONSTANTS_SHOWN = ("CF_M11", "CF_M22", "CF_M12", "CF_A1", "CF_A2", "CF_LH", "CF_FX", "CF_FY")

_ADD, _MUL, _UNARY, _POW, _ATOM = range(5)


class EquationError(KeyError):
    """The code holds a name, condition or statement the article has no notation for."""

    def __str__(self) -> str:
        return str(self.args[0])


def _atom(text: str) -> tuple[str, int]:
    """A notation as an operand: a symbol or a function of something (``sin(phi -
    theta)``) binds tightest, symbols side by side (``sin theta``) as a product."""
    return text, _MUL if " " in re.sub(r"\([^()]*\)", "", text) else _ATOM


def _wrapped(part: tuple[str, int], least: int) -> str:
    text, level = part
    return f"({text})" if level < least else text


class _Math:
    """An expression of the code as Typst math."""

    def __init__(self, names: dict[str, str]):
        self.names = names

    def __call__(self, node: ast.AST) -> tuple[str, int]:
        method = getattr(self, f"_{type(node).__name__}", None)
        if method is None:
            raise EquationError(f"no notation for {ast.unparse(node)!r} in {SOURCE.name}")
        return method(node)

    def _Constant(self, node: ast.Constant) -> tuple[str, int]:
        if isinstance(node.value, bool) or not isinstance(node.value, int | float):
            raise EquationError(f"no notation for the constant {node.value!r}")
        return f"{node.value:g}", _ATOM

    def _Name(self, node: ast.Name) -> tuple[str, int]:
        if node.id not in self.names:
            raise EquationError(f"no notation for {node.id!r} of {SOURCE.name}")
        return _atom(self.names[node.id])

    def _Subscript(self, node: ast.Subscript) -> tuple[str, int]:
        key = node.slice
        if isinstance(key, ast.Name) and key.id in COEFFICIENTS:
            return _atom(COEFFICIENTS[key.id])
        if isinstance(key, ast.Constant) and key.value in PARAMETERS:
            return _atom(PARAMETERS[key.value])
        raise EquationError(f"no notation for {ast.unparse(node)!r} of {SOURCE.name}")

    def _Call(self, node: ast.Call) -> tuple[str, int]:
        func = node.func.attr if isinstance(node.func, ast.Attribute) else ast.unparse(node.func)
        if func not in FUNCTIONS or len(node.args) != 1:
            raise EquationError(f"no notation for {ast.unparse(node)!r} of {SOURCE.name}")
        return f"{FUNCTIONS[func]}({self(node.args[0])[0]})", _ATOM

    def _UnaryOp(self, node: ast.UnaryOp) -> tuple[str, int]:
        if not isinstance(node.op, ast.USub):
            raise EquationError(f"no notation for {ast.unparse(node)!r}")
        return f"-{_wrapped(self(node.operand), _MUL)}", _UNARY

    def _product(self, node: ast.BinOp) -> tuple[str, int]:
        """A product's factors in the code's order, a factor repeated written once with
        its power (``m12 * w2 * w2`` is ``M_12 omega_2^2``)."""
        factors: list[ast.expr] = []
        stack, negative = [node], False
        while stack:
            item = stack.pop()
            if isinstance(item, ast.BinOp) and isinstance(item.op, ast.Mult):
                stack += [item.right, item.left]
            elif isinstance(item, ast.UnaryOp) and isinstance(item.op, ast.USub):
                negative = not negative  # -u * u is -(u u): the sign in front
                stack.append(item.operand)
            else:
                factors.append(item)
        counts: dict[str, list] = {}
        for factor in factors:
            counts.setdefault(ast.dump(factor), [factor, 0])[1] += 1
        parts = []
        for factor, n in counts.values():
            part = self(factor)
            if n > 1:
                parts.append(f"{_wrapped(part, _ATOM)}^{n}")
            else:
                parts.append(_wrapped(part, _MUL))
        if negative:
            return "-" + " ".join(parts), _UNARY
        return " ".join(parts), _MUL

    def _BinOp(self, node: ast.BinOp) -> tuple[str, int]:
        if isinstance(node.op, ast.Mult):
            return self._product(node)
        left, right = self(node.left), self(node.right)
        if isinstance(node.op, ast.Add | ast.Sub):
            sign = "+" if isinstance(node.op, ast.Add) else "-"
            term = f"({right[0]})" if right[1] in (_ADD, _UNARY) else right[0]
            return f"{left[0]} {sign} {term}", _ADD
        if isinstance(node.op, ast.Div):
            return f"({left[0]})/({right[0]})", _ATOM
        if isinstance(node.op, ast.Pow):
            return f"{_wrapped(left, _ATOM)}^({right[0]})", _POW
        raise EquationError(f"no notation for {ast.unparse(node)!r}")


@cache
def _tree() -> ast.Module:
    return ast.parse(Path(SOURCE).read_text(encoding="utf-8"))


def _function(name: str) -> ast.FunctionDef:
    for node in _tree().body:
        if isinstance(node, ast.FunctionDef) and node.name == name:
            return node
    raise EquationError(f"{SOURCE.name} defines no function {name!r}")


def _targets(node: ast.expr) -> list[str]:
    items = node.elts if isinstance(node, ast.Tuple) else [node]
    return [ast.unparse(t) for t in items]


class _Statements:
    """The equations of one function's statements, in order, grouped by the conditions
    they hold under; a quantity set again is written ``X <- ...`` (it replaces or adds
    to the value above under the group's condition)."""

    def __init__(self, returns: dict[int, str]):
        self.math = _Math(NAMES)
        self.returns = returns
        self.groups: list[dict] = []
        self.set: set[str] = set()

    def _line(self, lhs: str, rhs: str, when: Sequence[str], again: bool) -> None:
        words = ", ".join(CONDITIONS[c] for c in when) or "always"
        if not self.groups or self.groups[-1]["when"] != words:
            self.groups.append({"when": words, "lines": []})
        self.groups[-1]["lines"].append(f"{lhs} {'<-' if again else '='} {rhs}")

    def _assign(self, name: str, value: ast.expr, when: Sequence[str]) -> None:
        if name in SHORTHANDS:
            return
        if name not in NAMES:
            raise EquationError(f"no notation for {name!r} of {SOURCE.name}")
        self._line(NAMES[name], self.math(value)[0], when, name in self.set)
        self.set.add(name)

    def walk(self, body: Sequence[ast.stmt], when: tuple[str, ...] = ()) -> None:
        for node in body:
            self._statement(node, when)

    def _statement(self, node: ast.stmt, when: tuple[str, ...]) -> None:
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
            return  # the docstring
        if isinstance(node, ast.If):
            test = ast.unparse(node.test)
            if test not in CONDITIONS or node.orelse:
                raise EquationError(f"no words for the condition {test!r} of {SOURCE.name}")
            self.walk(node.body, (*when, test))
        elif isinstance(node, ast.Assign) and len(node.targets) == 1:
            self._assignment(node.targets[0], node.value, when)
        elif isinstance(node, ast.AugAssign):
            name = ast.unparse(node.target)
            self._assign(name, ast.BinOp(node.target, node.op, node.value), when)
        elif isinstance(node, ast.Return) and isinstance(node.value, ast.Tuple):
            for i, value in enumerate(node.value.elts):
                if i in self.returns:
                    self._line(self.returns[i], self.math(value)[0], when, False)
        else:
            raise EquationError(f"no notation for the statement {ast.unparse(node)!r}")

    def _assignment(self, target: ast.expr, value: ast.expr, when: tuple[str, ...]) -> None:
        names = _targets(target)
        if isinstance(value, ast.Name) and value.id == "y":
            return  # the state unpacked: the names are the notation's
        if isinstance(value, ast.Call) and ast.unparse(value.func) in FUNCTIONS_SHOWN:
            return  # a rendered function's values: its own group
        values = value.elts if isinstance(value, ast.Tuple) else [value]
        if len(values) != len(names):
            raise EquationError(f"no notation for the statement {ast.unparse(value)!r}")
        for name, item in zip(names, values, strict=True):
            self._assign(name, item, when)


def function_equations(name: str) -> list[dict]:
    """The equations of rendered function ``name`` (:data:`FUNCTIONS_SHOWN`): groups
    ``{"when": words, "lines": [Typst math, ...]}`` in the code's order."""
    _, returns = FUNCTIONS_SHOWN[name]
    statements = _Statements(returns)
    statements.walk(_function(name).body)
    return statements.groups


def constant_equations() -> list[str]:
    """The constants of the equations (:data:`CONSTANTS_SHOWN`) as :func:`coefficients`
    computes them, and the rods' centres they use."""
    function = _function("coefficients")
    math = _Math(NAMES)
    lines = []
    for node in function.body:
        if not isinstance(node, ast.Assign):
            continue
        target = node.targets[0]
        if _targets(target) == ["h1", "h2"] and isinstance(node.value, ast.Tuple):
            for name, value in zip(("h1", "h2"), node.value.elts, strict=True):
                lines.append(f"{NAMES[name]} = {math(value)[0]}")
        if ast.unparse(target) == "cols" and isinstance(node.value, ast.Dict):
            pairs = zip(node.value.keys, node.value.values, strict=True)
            found = {ast.unparse(k): v for k, v in pairs}
            missing = [c for c in CONSTANTS_SHOWN if c not in found]
            if missing:
                raise EquationError(f"coefficients() of {SOURCE.name} sets no {missing[0]}")
            lines += [f"{COEFFICIENTS[c]} = {math(found[c])[0]}" for c in CONSTANTS_SHOWN]
    return lines


def equations() -> list[dict]:
    """What the article prints of the model: ``{"title", "groups"}`` for the constants
    and each rendered function."""
    constants = {"when": "always", "lines": constant_equations()}
    out = [{"title": "the constants (coefficients)", "groups": [constants]}]
    for name, (title, _) in FUNCTIONS_SHOWN.items():
        out.append({"title": title, "groups": function_equations(name)})
    return out
