"""The package's layers import downwards only: model -> solver -> io -> experiments ->
studies -> inference -> replication -> entry points (the workflow's support and the
CLI), and no two modules import each other, even through others or from inside a
function.  Checked by parsing every import (also those inside functions) of every
module; run it alone with ``pytest tests/test_layers.py``."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "tennis_stroke"

#: Rank of each layer: a module may import from its own rank or below.  Folders are
#: layers; of the top-level modules, ``_version``, ``_imports`` (the import graph) and
#: ``_cache`` (the compiled code's cache location) import nothing of the package above
#: them, and the CLI and the package's start-up are entry points.
LAYERS = {
    "_version": 0,
    "_cache": 0,
    "_imports": 0,
    "model": 0,
    "solver": 1,
    "io": 2,
    "experiments": 3,
    "studies": 4,
    "inference": 5,
    "replication": 6,
    "pipeline": 7,
    "cli": 7,
    "live": 7,
    "__init__": 7,
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
    """The Snakefile imports it: no package module but the table of result files, no
    plotting library."""
    source = (PACKAGE / "replication" / "registry.py").read_text()
    assert _imports(PACKAGE / "replication" / "registry.py") == {"experiments.specs"}
    assert "matplotlib" not in source and "xarray" not in source


def _graph(package: Path) -> dict[str, set[str]]:
    """Module -> the package modules it imports (a folder's ``__init__`` for a folder)."""
    global PACKAGE
    saved, PACKAGE = PACKAGE, package
    try:
        modules = {_module(p): p for p in sorted(package.rglob("*.py"))}
        graph = {}
        for name, path in modules.items():
            targets = set()
            for target in _imports(path):
                if target in modules:
                    targets.add(target)
                elif f"{target}.__init__" in modules:
                    targets.add(f"{target}.__init__")
            graph[name] = targets - {name}
        return graph
    finally:
        PACKAGE = saved


def _cycle(graph: dict[str, set[str]]) -> list[str]:
    """One import cycle of ``graph`` (its modules in order), or [] when there is none."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return [*stack[stack.index(nxt) :], nxt]
            if nxt not in state and (found := visit(nxt)):
                return found
        stack.pop()
        state[node] = 2
        return []

    for node in sorted(graph):
        if node not in state and (found := visit(node)):
            return found
    return []


def test_no_import_cycle_anywhere():
    """No module imports itself through others, lazy imports inside functions included."""
    cycle = _cycle(_graph(PACKAGE))
    assert not cycle, "import cycle: " + " -> ".join(cycle)


def test_the_cycle_check_sees_a_lazy_cycle(tmp_path):
    """The check can fail: two modules importing each other, one inside a function."""
    (tmp_path / "solver").mkdir()
    (tmp_path / "solver" / "a.py").write_text("from .b import x\n")
    (tmp_path / "solver" / "b.py").write_text("def x():\n    from .a import y\n")
    assert _cycle(_graph(tmp_path)) == ["solver.a", "solver.b", "solver.a"]


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
