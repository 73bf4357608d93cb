"""The import graph read from the source (tennis_stroke._imports): what the workflow's
code inputs and the compiled solver's cache key follow."""

from pathlib import Path

from tennis_stroke import _imports
from tennis_stroke._cache import compiled_sources
from tennis_stroke._imports import PACKAGE, closure, compiled_modules, imports_of_file

ROOT = Path(__file__).resolve().parents[1]


def _names(paths):
    return {str(p.relative_to(PACKAGE)) for p in paths}


def test_the_compiled_modules_are_those_importing_numba():
    """solver.compiled holds no compiled function but imports numba's event API (it
    refuses compiles while loading the cache); it was in the cache key's closure already,
    through solver.stroke.  solver.rk4 compiles its fixed steps (the solver studies)."""
    assert set(compiled_modules()) == {
        "model.dynamics",
        "model.impact",
        "solver._kernels",
        "solver.compiled",
        "solver.curves",
        "solver.integrate",
        "solver.rk4",
        "solver.stroke",
    }


def test_the_cache_key_covers_the_compiled_code_and_what_it_imports_only():
    names = _names(compiled_sources())
    assert {"model/dynamics.py", "model/params.py", "solver/stroke.py"} <= names
    assert {"solver/integrate.py", "solver/_kernels.py", "solver/results.py"} <= names
    # metadata, files, inference and the scipy path recompile nothing
    for other in ("io/units.py", "io/netcdf.py", "solver/reference.py", "__init__.py"):
        assert other not in names
    assert not any(n.startswith(("inference/", "replication/", "experiments/")) for n in names)


def test_lazy_and_relative_imports_are_followed(tmp_path, monkeypatch):
    """An import inside a function counts; ``from . import x`` names module x; a
    subpackage's ``__init__`` runs first; the package's own ``__init__`` is left out."""
    pkg = tmp_path / "tennis_stroke"
    (pkg / "a").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a" / "__init__.py").write_text("")
    (pkg / "a" / "x.py").write_text("def f():\n    from .y import g\n")
    (pkg / "a" / "y.py").write_text("from . import z\n")
    (pkg / "a" / "z.py").write_text("import os\n")
    (pkg / "b.py").write_text("from tennis_stroke.a.x import (\n    f,\n)\n")
    monkeypatch.setattr(_imports, "PACKAGE", pkg)
    imports_of_file.cache_clear()
    try:
        got = {str(p.relative_to(pkg)) for p in closure(modules=["b"])}
        assert got == {"b.py", "a/__init__.py", "a/x.py", "a/y.py", "a/z.py"}
        script = tmp_path / "script.py"
        script.write_text("from tennis_stroke.a.z import nothing\n")
        assert {str(p.relative_to(pkg)) for p in closure(files=[script])} == {
            "a/__init__.py",
            "a/z.py",
        }
    finally:
        imports_of_file.cache_clear()


def test_a_workflow_script_depends_on_what_it_imports():
    """The claims job runs the claims table and the inference, never the figures."""
    names = _names(closure(files=[ROOT / "workflow" / "scripts" / "claims.py"]))
    assert {"replication/claims.py", "inference/claims.py", "inference/measures.py"} <= names
    assert "replication/figures.py" not in names and "replication/report.py" not in names
