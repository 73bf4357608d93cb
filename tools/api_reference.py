"""The API reference: pdoc's HTML of the public modules, from their docstrings.

Usage::

    python tools/api_reference.py            # make api: docs/api/index.html (not in git)
    python tools/api_reference.py OUT        # into the folder OUT

It fails (exit 1, one line a problem, nothing written) where the reference would lie: a
warning of pdoc (a name of a module's ``__all__`` that does not resolve, a docstring it
cannot read) or a cross-reference of a documented docstring (``:func:`name```,
``:class:``, ``:data:``, ``:mod:``, ``:meth:``, ``:attr:``) that names nothing or is
written ``~name`` (Sphinx's short form, which pdoc shows as written).
``tests/test_api_reference.py`` builds it, checks that every public name is in it, and
runs the examples of its docstrings.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import os
import re
import shutil
import sys
import tempfile
import warnings
from collections.abc import Iterable, Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: Where ``make api`` writes the reference (ignored by git: it is generated).
DEFAULT_OUT = ROOT / "docs" / "api"
#: pdoc's templates that differ from its own: the front page lists every module.
TEMPLATES = Path(__file__).resolve().parent / "api_templates"
#: The documented modules: the package's public API (its ``__all__``, each name shown
#: where the package lists it) and the modules those names come from or a user reads
#: beside them (the scipy path, the trajectory dataset, the units table, the parameters,
#: the solver's settings and result fields).
PUBLIC_MODULES = (
    "tennis_stroke",
    "tennis_stroke.solver.reference",
    "tennis_stroke.io.trajectory",
    "tennis_stroke.io.units",
    "tennis_stroke.model.params",
    "tennis_stroke.solver.settings",
    "tennis_stroke.solver.results",
)
#: A Sphinx-style cross-reference in a docstring: its role and its target.
ROLE = re.compile(r":(func|class|data|mod|meth|attr|exc|obj):`(~?[\w.]+)`")


class ApiReferenceError(Exception):
    """The reference cannot be built as it should be: its message says why."""


def resolved_api(package: str = "tennis_stroke") -> None:
    """Import every name of ``package.__all__`` now: the package imports its API lazily
    (PEP 562) and pdoc reads a module's members from its ``__dict__``."""
    module = importlib.import_module(package)
    for name in getattr(module, "__all__", ()):
        getattr(module, name)


def _lookup(dotted: str) -> bool:
    """Whether the dotted name ``dotted`` names a module, or an object (a dataclass field
    included) inside one."""
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            if dataclasses.is_dataclass(obj) and attr in {f.name for f in dataclasses.fields(obj)}:
                return attr == parts[-1]
            if not hasattr(obj, attr):
                return False
            obj = getattr(obj, attr)
        return True
    return False


def resolves(target: str, module: str, cls: str | None = None) -> bool:
    """Whether a cross-reference ``target`` written in a docstring of ``module`` (in the
    class ``cls``) names something: as written, in the module, in the class or in its
    members, or in the package's public API (as Sphinx looks it up)."""
    candidates = [target, f"{module}.{target}", f"tennis_stroke.{target}"]
    if cls:
        candidates.append(f"{module}.{cls}.{target}")
    return any(_lookup(name) for name in candidates)


def _docstrings(module: str) -> Iterator[tuple[str, str, str | None, str]]:
    """``(where, defining module, class, docstring)`` of ``module`` and of each object it
    documents (pdoc's view: its members, and the members of its classes)."""
    import pdoc.doc

    try:
        stack = [pdoc.doc.Module(importlib.import_module(module))]
    except ImportError as err:
        raise ApiReferenceError(f"{module}: {err}") from None
    while stack:
        doc = stack.pop()
        home = doc.taken_from[0] if hasattr(doc, "taken_from") else doc.modulename
        cls = doc.qualname.rsplit(".", 1)[0] if "." in getattr(doc, "qualname", "") else None
        if isinstance(doc, pdoc.doc.Class):
            cls = doc.qualname
        yield doc.fullname, home, cls, doc.docstring
        if isinstance(doc, pdoc.doc.Namespace):
            members = doc.own_members if isinstance(doc, pdoc.doc.Class) else doc.members.values()
            stack.extend(members)


def broken_references(modules: Iterable[str]) -> list[str]:
    """Every cross-reference of the documented docstrings of ``modules`` that names
    nothing, as ``where: :role:`target```."""
    found = []
    for module in modules:
        for where, home, cls, text in _docstrings(module):
            for role, target in ROLE.findall(text):
                if target.startswith("~"):  # Sphinx's short form; pdoc shows the "~"
                    found.append(f"{where}: :{role}:`{target}`: pdoc shows the ~, drop it")
                elif not resolves(target, home, cls):
                    found.append(f"{where}: :{role}:`{target}` names nothing")
    return sorted(set(found))


def build(out: Path, modules: Iterable[str] = PUBLIC_MODULES) -> list[Path]:
    """Write the reference of ``modules`` into the folder ``out`` (replacing it); returns
    the pages written.  Raises :class:`ApiReferenceError` on a broken cross-reference or
    a warning of pdoc, and then leaves ``out`` as it was."""
    import pdoc
    import pdoc.render

    from tennis_stroke import __version__

    modules = list(modules)
    resolved_api()
    pdoc.render.configure(
        docformat="numpy",
        show_source=False,
        footer_text=f"tennis-stroke {__version__}",
        template_directory=TEMPLATES,
    )
    # the package alone, not its submodules, then the other modules
    specs = [modules[0], rf"!{re.escape(modules[0])}\.", *modules[1:]]
    out.parent.mkdir(parents=True, exist_ok=True)
    new = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    umask = os.umask(0)
    os.umask(umask)
    new.chmod(0o777 & ~umask)  # mkdtemp's 0700 would stay after the rename
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            broken = broken_references(modules)
            if broken:
                raise ApiReferenceError("; ".join(broken))
            pdoc.pdoc(*specs, output_directory=new)
        shutil.rmtree(out, ignore_errors=True)
        new.rename(out)
    except Warning as warning:
        raise ApiReferenceError(f"pdoc: {warning}") from None
    finally:
        shutil.rmtree(new, ignore_errors=True)
    return sorted(out.rglob("*.html"))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", type=Path, default=DEFAULT_OUT, help="folder to write")
    args = parser.parse_args(argv)
    try:
        files = build(args.out, PUBLIC_MODULES)
    except ApiReferenceError as err:
        print(f"api_reference: {err}", file=sys.stderr)
        return 1
    print(f"{args.out}: the API reference of {len(PUBLIC_MODULES)} modules, {len(files)} pages")
    return 0


if __name__ == "__main__":
    sys.exit(main())
