"""The package's import graph, read from the source text (nothing is imported).

Two things follow the code through it: the workflow's rules declare as code inputs the
modules their jobs import (:func:`closure` of a script's imports), and the compiled
solver's cache is keyed by the modules that hold compiled functions and what they
import (:mod:`tennis_stroke._cache`).  Every import counts, those inside functions too:
a job may run them.  Standard library only, so the package's start-up can use it.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from functools import cache
from pathlib import Path

#: The package's folder.
PACKAGE = Path(__file__).resolve().parent
NAME = PACKAGE.name
#: An import of numba.
_NUMBA = re.compile(r"^[ \t]*(?:import[ \t]+numba\b|from[ \t]+numba[ \t.])", re.M)


@cache
def module_path(module: str) -> Path | None:
    """The source file of package module ``module`` (dotted, below the package; ``""``
    for the package itself), or None if it is not one (looked up once per process)."""
    base = PACKAGE.joinpath(*module.split(".")) if module else PACKAGE
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    return None


def module_name(path: Path) -> str:
    """The dotted name (below the package) of the module at ``path``."""
    parts = path.resolve().relative_to(PACKAGE).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


#: An import statement at the start of a line (also inside a function); a docstring line
#: that reads like one only adds a dependency, never hides one.
_FROM = re.compile(r"^[ \t]*from[ \t]+([.\w]+)[ \t]+import[ \t]+(\([^)]*\)|[^\n#;]*)", re.M)
_IMPORT = re.compile(r"^[ \t]*import[ \t]+([^\n#;]+)", re.M)
#: An import by name of a module written out (``importlib.import_module(".warmup",
#: __package__)``, ``__import__("tennis_stroke.x")``): an import as any other.
_BY_NAME = re.compile(r"""\b(?:import_module|__import__)\(\s*(["'])([.\w]+)\1""")


def _absolute(source: str, module: str, is_package: bool) -> str | None:
    """The module ``from SOURCE import`` names, below the package, or None if outside."""
    level = len(source) - len(source.lstrip("."))
    name = source.lstrip(".")
    if level == 0:
        if name != NAME and not name.startswith(NAME + "."):
            return None
        return name.removeprefix(NAME).lstrip(".")
    parts = module.split(".") if module else []
    package = parts if is_package else parts[:-1]
    if level - 1 > len(package):
        return None
    base = package[: len(package) - (level - 1)]
    return ".".join([*base, *([name] if name else [])])


_API_ENTRY = re.compile(r'^\s*"(\w+)":\s*"\.([.\w]+)",?\s*$', re.M)


def public_api() -> dict[str, str]:
    """The package's lazy public API (``_API`` of its ``__init__``, read as text): each
    name and the module below the package that defines it, so that ``from tennis_stroke
    import strike`` counts as importing ``solver.stroke``."""
    path = PACKAGE / "__init__.py"
    return _api_of(path, path.stat().st_mtime_ns) if path.is_file() else {}


@cache
def _api_of(path: Path, mtime_ns: int) -> dict[str, str]:
    text = path.read_text()
    block = text.split("_API = {", 1)[1].split("}", 1)[0] if "_API = {" in text else ""
    return dict(_API_ENTRY.findall(block))


@cache
def imports_of_file(path: Path) -> frozenset[str]:
    """Package modules that the Python file ``path`` imports (anywhere in it), and the
    subpackages they lie in (a package's ``__init__`` runs first).  The package's own
    ``__init__`` (start-up: the cache location and the lazy API) is left out: it runs in
    every process and changes no result.  Read as text (an import statement starts a
    line; an import by a module's name written out counts too), which is fast enough for
    the package's start-up."""
    inside = PACKAGE in path.resolve().parents
    module = module_name(path) if inside else ""
    is_package = path.name == "__init__.py"
    text = path.read_text()
    found: set[str] = set()
    for source, names in _FROM.findall(text):
        if source.startswith(".") and not inside:
            continue
        target = _absolute(source, module, is_package)
        if target is None:
            continue
        found.add(target)
        for alias in names.strip("()").replace("\n", " ").split(","):
            alias = alias.split(" as ")[0].strip()
            sub = f"{target}.{alias}" if target else alias
            if alias and module_path(sub) is not None:  # "from . import x": a module
                found.add(sub)
            elif not target and alias in public_api():  # the lazy API: its module
                found.add(public_api()[alias])
    for _, source in _BY_NAME.findall(text):
        target = _absolute(source, module, is_package) if inside or source[0] != "." else None
        if target is not None:
            found.add(target)
    for names in _IMPORT.findall(text):
        for alias in names.split(","):
            alias = alias.split(" as ")[0].strip()
            if alias == NAME or alias.startswith(NAME + "."):
                found.add(alias.removeprefix(NAME).lstrip("."))
    out = set()
    for name in found:
        parts = name.split(".") if name else []
        out.update(".".join(parts[:i]) for i in range(1, len(parts) + 1))
    return frozenset(m for m in out if module_path(m) is not None)


def closure(files: Iterable[Path | str] = (), modules: Iterable[str] = ()) -> list[Path]:
    """Source files of the package that run when ``files`` (any Python files: a
    workflow script, a package module) and ``modules`` (dotted, below the package) are
    imported: themselves if they are the package's, and every package module they import,
    directly or through others, sorted."""
    todo = [module_path(m) for m in modules]
    seen: set[Path] = set()
    outside = []
    for f in files:
        path = Path(f).resolve()
        (todo if PACKAGE in path.parents else outside).append(path)
    for path in outside:
        todo.extend(module_path(m) for m in imports_of_file(path))
    for path in todo:
        if path is not None:
            seen.update(_closure_of(path))
    return sorted(seen)


@cache
def _closure_of(start: Path) -> frozenset[Path]:
    """The package's source files that run when the module at ``start`` is imported."""
    todo, seen = [start], set()
    while todo:
        path = todo.pop()
        if path is None or path in seen:
            continue
        seen.add(path)
        todo.extend(module_path(m) for m in imports_of_file(path))
    return frozenset(seen)


def compiled_modules() -> list[str]:
    """The package modules that hold compiled (numba) functions: those importing numba."""
    return [
        module_name(path)
        for path in sorted(PACKAGE.rglob("*.py"))
        if _NUMBA.search(path.read_text())
    ]
