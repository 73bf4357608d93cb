"""The workflow's scripts read as source, for the tests and benchmarks (kept out of the
package: every job imports ``tennis_stroke._imports``, so an edit there reruns them all)."""

from __future__ import annotations

import ast
from pathlib import Path


def top_level_imports(path: Path | str) -> str:
    """The import statements at the top level of the file ``path``, as source (what runs
    before a workflow script's job does its work)."""
    tree = ast.parse(Path(path).read_text())
    nodes = [n for n in tree.body if isinstance(n, ast.Import | ast.ImportFrom)]
    return "\n".join(ast.unparse(n) for n in nodes)
