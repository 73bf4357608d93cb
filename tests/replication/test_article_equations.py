"""The article's equations, rendered from the code that computes them
(:mod:`tennis_stroke.replication.article_equations`): every statement of the equations of
motion printed, a name without a notation refused, and every line valid Typst math."""

import shutil

import pytest

from tennis_stroke.replication import article_equations
from tennis_stroke.replication.article_equations import EquationError, equations


def _lines(parts):
    return [line for part in parts for group in part["groups"] for line in group["lines"]]


def test_the_equations_of_motion_are_the_code_s_statements():
    parts = equations()
    titles = [p["title"] for p in parts]
    assert titles[0] == "the constants (coefficients)" and len(parts) == 3
    motion = next(p for p in parts if "rhs_trig" in p["title"])
    when = [g["when"] for g in motion["groups"]]
    assert when[0] == "always" and any(w.startswith("during the contact") for w in when)
    lines = _lines([motion])
    # the solved 2x2 system, the torques' sides and the contact's forces, as computed
    assert "dot(omega)_1 = (P M_22 - Q M_12 cos(phi - theta))/(D)" in lines
    assert "D = M_11 M_22 - (M_12 cos(phi - theta))^2" in lines
    assert "F_b = -k (s - (L_1 sin theta + ell_H sin phi))" in lines
    assert "P <- P - F_r L_1 cos theta" in lines
    assert "dot(theta) = -omega_1" in lines
    constants = _lines(parts[:1])
    assert "M_11 = I_1 + M_1 h_1^(2) + M_2 L_1^(2)" in constants
    assert "h_1 = (L_1)/(2)" in constants


def test_a_name_of_the_code_without_a_notation_is_refused(tmp_path, monkeypatch):
    """A new quantity in rhs_trig that the article cannot name stops it in one line,
    never a silently incomplete set of equations."""
    source = tmp_path / "dynamics.py"
    shutil.copy(article_equations.SOURCE, source)
    text = source.read_text()
    marker = "    m11, m22 = cf[CF_M11], cf[CF_M22]\n"
    assert marker in text
    source.write_text(text.replace(marker, marker + "    spin = 2.0 * w1\n"))
    monkeypatch.setattr(article_equations, "SOURCE", source)
    article_equations._tree.cache_clear()
    try:
        with pytest.raises(EquationError, match="no notation for 'spin'"):
            equations()
    finally:
        article_equations._tree.cache_clear()


def test_every_line_typesets_as_typst_math(tmp_path):
    typst = pytest.importorskip("typst")
    lines = _lines(equations())
    body = "\n".join(f"$ {line} $" for line in lines)
    (tmp_path / "eq.typ").write_text(body)
    assert typst.compile(str(tmp_path / "eq.typ"))[:5] == b"%PDF-"
