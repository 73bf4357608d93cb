"""The package's layers import downwards only: model -> solver -> io -> experiments ->
studies -> inference -> replication -> entry points (the workflow's support and the
CLI), and no two modules import each other, even through others or from inside a
function.  The imports are read by the package's own parser
(:func:`tennis_stroke._imports.imports_of_file`, every import, those inside functions
too): the graph these tests check is the one the workflow's code inputs and the compiled
solver's cache key follow.  Run it alone with ``pytest tests/test_layers.py``."""

import graphlib
from pathlib import Path

import pytest

from tennis_stroke import _imports
from tennis_stroke._imports import PACKAGE, imports_of_file, module_name

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


def _layer(module: str) -> str:
    """The layer of a module (dotted, below the package; "" is the package's start-up)."""
    return module.split(".")[0] or "__init__"


def _upward_imports(path: Path) -> list[str]:
    """What ``path`` (a module of the package) imports from a layer above its own, or
    from no layer."""
    name = module_name(path)
    own = LAYERS[_layer(name)]
    found = []
    for target in sorted(imports_of_file(path)):
        rank = LAYERS.get(_layer(target))
        if rank is None:
            found.append(f"{name} imports {target}, which is in no layer")
        elif rank > own:
            found.append(f"{name} (rank {own}) imports {target} (rank {rank})")
    return found


def _graph() -> dict[str, set[str]]:
    """Module -> the package modules it imports (a subpackage stands for its
    ``__init__``), for the package the parser reads.  The packages a module lies in are
    left out: Python runs their ``__init__`` before the module, not because of it."""
    graph = {}
    for path in sorted(_imports.PACKAGE.rglob("*.py")):
        name = module_name(path)
        graph[name] = {t for t in imports_of_file(path) if not (name + ".").startswith(t + ".")}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str]:
    """One import cycle of ``graph`` (each module imports the next), or [] if none."""
    try:
        graphlib.TopologicalSorter(graph).prepare()
    except graphlib.CycleError as err:
        return err.args[1][::-1]
    return []


MODULES = sorted(PACKAGE.rglob("*.py"))


def test_every_module_belongs_to_a_layer():
    for path in MODULES:
        assert _layer(module_name(path)) in LAYERS, f"{path}: not in a declared layer"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p) or "__init__")
def test_imports_only_go_downwards(path):
    assert not _upward_imports(path)


def test_the_reference_path_shares_the_model_but_not_the_compiled_driver():
    imports = imports_of_file(PACKAGE / "solver" / "reference.py")
    assert "model.dynamics" in imports
    assert not imports & {"solver.stroke", "solver.integrate", "solver._kernels"}


def test_the_registry_is_pure_data():
    """The Snakefile imports it: no package module but the table of result files and the
    parameter table (the units of the inputs a title names), no plotting library."""
    source = (PACKAGE / "replication" / "registry.py").read_text()
    assert imports_of_file(PACKAGE / "replication" / "registry.py") == {
        "experiments",
        "experiments.specs",
        "model",
        "model.params",
    }
    assert "matplotlib" not in source and "xarray" not in source


def test_no_import_cycle_anywhere():
    """No module imports itself through others, lazy imports inside functions included."""
    cycle = _cycle(_graph())
    assert not cycle, "import cycle: " + " -> ".join(cycle)


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A package of the same name in ``tmp_path``, which the parser reads instead of the
    real one while the test runs: ``package({"path": "source", ...})`` writes modules."""
    root = tmp_path / "tennis_stroke"

    def write(files: dict[str, str]) -> Path:
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        return root

    write({"__init__.py": ""})
    monkeypatch.setattr(_imports, "PACKAGE", root)
    imports_of_file.cache_clear()
    yield write
    imports_of_file.cache_clear()


def test_the_cycle_check_sees_a_lazy_cycle(package):
    """The check can fail: two modules importing each other, one inside a function."""
    package(
        {
            "solver/__init__.py": "",
            "solver/a.py": "from .b import x\n",
            "solver/b.py": "def x():\n    from .a import y\n",
        }
    )
    assert _cycle(_graph()) == ["solver.a", "solver.b", "solver.a"]


@pytest.mark.parametrize(
    "by_name",
    [
        'importlib.import_module(".a", __package__)',
        'import_module("tennis_stroke.solver.a")',
        '__import__("tennis_stroke.solver.a")',
    ],
)
def test_the_cycle_check_sees_an_import_by_name(package, by_name):
    """An import by a module's name written out is an import: the solver's compile cache
    once loaded its warm-up so, which imported the cache's callers back, a cycle the
    static imports did not show."""
    package(
        {
            "solver/__init__.py": "",
            "solver/a.py": "from .b import x\n",
            "solver/b.py": f"import importlib\n\ndef x():\n    return {by_name}\n",
        }
    )
    assert _cycle(_graph()) == ["solver.a", "solver.b", "solver.a"]


def test_a_subpackage_importing_its_own_modules_is_no_cycle(package):
    """A folder's ``__init__`` may import its modules: they do not import it back."""
    package({"solver/__init__.py": "from .a import x\n", "solver/a.py": "x = 1\n"})
    assert _graph()["solver.a"] == set()
    assert not _cycle(_graph())


@pytest.mark.parametrize(
    "source",
    [
        "from ..solver.stroke import strike\n",
        "from tennis_stroke.solver.stroke import strike\n",
        "import tennis_stroke.solver.stroke\n",
        "from .. import solver\n",
        "def f():\n    from ..solver import stroke\n",
    ],
)
def test_the_checker_sees_an_upward_import(package, source):
    """The check can fail: a model module importing the solver is caught, however the
    import is written."""
    root = package({"solver/__init__.py": "", "solver/stroke.py": "", "model/bad.py": source})
    assert any("imports solver" in e for e in _upward_imports(root / "model" / "bad.py"))


def test_an_upward_import_through_the_public_api_is_caught(package):
    """The package's own start-up (its lazy table of public names) in a package where
    a model module takes ``strike`` from it: the parser follows the name to
    solver.stroke (_imports.public_api), so the upward import is caught."""
    root = package(
        {
            "__init__.py": (PACKAGE / "__init__.py").read_text(),
            "solver/__init__.py": "",
            "solver/stroke.py": "",
            "model/__init__.py": "",
            "model/bad.py": "from tennis_stroke import strike\n",
        }
    )
    assert _upward_imports(root / "model" / "bad.py")
