"""The package's layers import downwards only: model -> solver -> files -> experiments ->
studies -> replication -> entry points.  Checked by parsing every import (also those
inside functions) of every module; run it alone with ``pytest tests/test_layers.py``."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "tennis_stroke"

#: Rank of each layer: a module may import from its own rank or below.  Folders are
#: layers; the top-level modules are the file layer (results on disk, chunks, failure
#: counts) or the entry points (start-up, the workflow's adapters, config checks, CLI).
LAYERS = {
    "model": 0,
    "solver": 1,
    "io": 2,
    "chunking": 2,
    "failures": 2,
    "experiments": 3,
    "studies": 4,
    "replication": 5,
    "pipeline": 6,
    "config_check": 6,
    "cli": 6,
    "_version": 0,
    "_cache": 0,  # numba cache location: imports nothing of the package
    "__init__": 6,
}


def _module(path: Path) -> str:
    parts = path.relative_to(PACKAGE).with_suffix("").parts
    return ".".join(parts)


def _layer(module: str) -> str:
    return module.split(".")[0]


def _imports(path: Path) -> set[str]:
    """Modules of the package that ``path`` imports (dotted, relative to the package)."""
    here = _module(path).split(".")
    package = here[:-1]  # a module's package; for __init__ ("x.__init__") the package x
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)]
                target = [*base, *(node.module.split(".") if node.module else [])]
                names = [a.name for a in node.names]
                if not node.module:  # from . import x: x is a module
                    found.update(".".join([*target, n]) for n in names)
                else:
                    found.add(".".join(target))
            elif node.module and node.module.startswith("tennis_stroke"):
                found.add(node.module.removeprefix("tennis_stroke").lstrip(".") or "__init__")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("tennis_stroke"):
                    found.add(alias.name.removeprefix("tennis_stroke").lstrip(".") or "__init__")
    return {m for m in found if m}


MODULES = sorted(PACKAGE.rglob("*.py"))


def test_every_module_belongs_to_a_layer():
    for path in MODULES:
        assert _layer(_module(path)) in LAYERS, f"{path}: not in a declared layer"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: _module(p))
def test_imports_only_go_downwards(path):
    own = LAYERS[_layer(_module(path))]
    for target in _imports(path):
        layer = _layer(target)
        assert layer in LAYERS, f"{_module(path)} imports {target}, which is in no layer"
        assert LAYERS[layer] <= own, (
            f"{_module(path)} (rank {own}) imports {target} (rank {LAYERS[layer]})"
        )


def test_the_reference_path_shares_the_model_but_not_the_compiled_driver():
    imports = _imports(PACKAGE / "solver" / "reference.py")
    assert "model.dynamics" in imports
    assert not imports & {"solver.stroke", "solver.integrate", "solver._kernels"}


def test_the_registry_is_pure_data():
    """The Snakefile imports it: no package module, no plotting library."""
    source = (PACKAGE / "replication" / "registry.py").read_text()
    assert _imports(PACKAGE / "replication" / "registry.py") == set()
    assert "matplotlib" not in source and "xarray" not in source


def test_the_checker_sees_an_upward_import(tmp_path):
    """The check can fail: a model module importing the solver is caught."""
    bad = tmp_path / "model" / "bad.py"
    bad.parent.mkdir()
    bad.write_text("from ..solver.stroke import strike\n")
    global PACKAGE
    saved, PACKAGE = PACKAGE, tmp_path
    try:
        with pytest.raises(AssertionError, match="imports solver.stroke"):
            test_imports_only_go_downwards(bad)
    finally:
        PACKAGE = saved
