"""The API reference (tools/api_reference.py, ``make api``): pdoc builds it from the
docstrings without a warning, every public name is in it, every cross-reference of a
documented docstring names something, and the examples of the documented modules run
as written."""

import doctest
import importlib
import inspect
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
try:
    import api_reference
    from api_reference import PUBLIC_MODULES, ApiReferenceError, broken_references, build
finally:
    sys.path.remove(str(ROOT / "tools"))


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The reference, built once for this module's tests."""
    out = tmp_path_factory.mktemp("reference") / "api"
    build(out)
    return out


def _page(out: Path, module: str) -> str:
    return (out / f"{module.replace('.', '/')}.html").read_text()


def test_every_public_name_of_the_package_is_documented(built):
    import tennis_stroke

    page = _page(built, "tennis_stroke")
    missing = [name for name in tennis_stroke.__all__ if f'id="{name}"' not in page]
    assert not missing
    assert "solve_stroke" in tennis_stroke.__all__ and "stroke_dataset" in tennis_stroke.__all__


@pytest.mark.parametrize("module", PUBLIC_MODULES[1:])
def test_every_public_function_and_class_of_a_documented_module_is_on_its_page(built, module):
    mod = importlib.import_module(module)
    own = [
        name
        for name, value in vars(mod).items()
        if not name.startswith("_")
        and (inspect.isfunction(value) or inspect.isclass(value))
        and value.__module__ == module
    ]
    page = _page(built, module)
    assert own and not [name for name in own if f'id="{name}"' not in page]


def test_the_index_links_every_documented_module(built):
    index = (built / "index.html").read_text()
    assert all(f'href="{module.replace(".", "/")}.html"' in index for module in PUBLIC_MODULES)


def test_every_cross_reference_of_the_documented_docstrings_names_something():
    assert broken_references(PUBLIC_MODULES) == []


def test_a_cross_reference_that_names_nothing_is_found(tmp_path, monkeypatch):
    """The check can fail: a role naming nothing in a module, a function or a class is
    found; one naming a function, a method, a module or a dataclass field is not."""
    (tmp_path / "fake_api.py").write_text(
        '"""See :func:`good`, :mod:`tennis_stroke.io.units`, :attr:`Thing.size`."""\n'
        "import dataclasses\n\n"
        "def good():\n"
        '    """Not :func:`missing`, nor :mod:`tennis_stroke.nowhere`, nor :func:`~good`."""\n\n'
        "@dataclasses.dataclass\n"
        "class Thing:\n"
        '    """:meth:`go` is here, :data:`gone` is not."""\n\n'
        "    size: list = dataclasses.field(default_factory=list)\n\n"
        "    def go(self):\n"
        '        """Go."""\n'
    )
    monkeypatch.syspath_prepend(tmp_path)
    assert broken_references(["fake_api"]) == [
        "fake_api.Thing: :data:`gone` names nothing",
        "fake_api.good: :func:`missing` names nothing",
        "fake_api.good: :func:`~good`: pdoc shows the ~, drop it",
        "fake_api.good: :mod:`tennis_stroke.nowhere` names nothing",
    ]


def test_a_pdoc_warning_stops_the_build_and_leaves_the_old_reference(tmp_path, monkeypatch):
    """A name of ``__all__`` that resolves to nothing (pdoc warns) is an error naming it,
    and the folder keeps what it held."""
    (tmp_path / "fake_all.py").write_text('"""A module."""\n__all__ = ["ghost"]\n')
    monkeypatch.syspath_prepend(tmp_path)
    out = tmp_path / "api"
    out.mkdir()
    (out / "old.html").write_text("old")
    with pytest.raises(ApiReferenceError, match="ghost"):
        build(out, ["fake_all"])
    assert not list(tmp_path.glob(".api-*"))  # no half-built reference left behind
    assert [p.name for p in out.iterdir()] == ["old.html"]


def test_the_command_says_what_it_wrote_and_refuses_in_one_line(tmp_path, capsys, monkeypatch):
    assert api_reference.main([str(tmp_path / "api")]) == 0
    assert "the API reference of" in capsys.readouterr().out
    monkeypatch.setattr(api_reference, "PUBLIC_MODULES", ("json", "tennis_stroke.nowhere"))
    assert api_reference.main([str(tmp_path / "api")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("api_reference: ")


def test_the_examples_of_the_documented_modules_run():
    """Every ``>>>`` example of a documented module gives the output written under it,
    and there are examples to run."""
    results = {m: doctest.testmod(importlib.import_module(m)) for m in PUBLIC_MODULES}
    assert not {m: r.failed for m, r in results.items() if r.failed}
    assert sum(r.attempted for r in results.values()) >= 5
