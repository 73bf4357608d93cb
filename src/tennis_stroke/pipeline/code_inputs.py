"""The code inputs of the workflow's jobs: the package modules each job imports.

Snakemake does not see code changes in an imported package, so each rule names as
inputs the modules its job runs (:func:`tennis_stroke._imports.closure` of its script's
imports and the modules it names), and an edit reruns exactly the jobs that run it.
Paths are relative to the working directory: a checkout moved or copied with its
working directory reruns nothing (Snakemake records input paths as given).
"""

from __future__ import annotations

import os
from functools import cache
from pathlib import Path

from .._imports import PACKAGE as INSTALLED
from .._imports import closure
from ..experiments.specs import EXPERIMENTS, Experiment


def checkout_path(path: str | Path) -> str:
    """A file of the checkout as an input path relative to the working directory
    (``workflow.source_path`` would record the absolute path)."""
    return os.path.relpath(path, os.getcwd())


class CodeInputs:
    """The code inputs of the jobs of the workflow whose Snakefile is in ``basedir``."""

    def __init__(self, basedir: str | Path):
        #: The workflow's scripts, and the package as this checkout holds it.
        self.scripts = Path(basedir) / "workflow" / "scripts"
        self.package = Path(basedir) / "src" / "tennis_stroke"
        #: The table of experiments: a simulation job gets its row as params (function,
        #: flags, config values), so editing another row reruns nothing of it.
        self.table = self.package / "experiments" / "specs.py"
        #: The one table of units and long names: a code input only of the jobs that
        #: write its labels into their files, the table's unchunked rows and gather_map
        #: (the chunks of a map leave the labels to it:
        #: tennis_stroke.io.netcdf.relabelled), so editing a long name reruns no chunk
        #: of a map and no inference job (tests/inference/test_labels.py).
        self.units = self.package / "io" / "units.py"
        #: The registry of figures: not a code input of the figure jobs, each of which
        #: gets its entry as a param.
        self.registry = self.package / "replication" / "registry.py"
        self._paths: dict[Path, str] = {}
        #: The modules of the paper experiments' functions (the robustness analysis
        #: runs them).
        self.paper_modules = sorted(
            {e.function.split(":")[0] for e in EXPERIMENTS.values() if e.family == "paper"}
        )

    def __call__(self, script: str, *modules: str, labels: bool = False, leave_out=()) -> list[str]:
        """The package modules a job of ``script`` (in workflow/scripts) runs: those the
        script imports and ``modules`` (dotted, below the package) import, directly or
        through others, as sorted paths relative to the working directory; less
        ``leave_out`` (paths), and less the units table unless the job writes its
        ``labels``."""
        left_out = {checkout_path(p) for p in (*leave_out, *([] if labels else [self.units]))}
        paths = (self._in_checkout(p) for p in closure([self.scripts / script], modules))
        return sorted({p for p in paths if p not in left_out})

    def _in_checkout(self, installed: Path) -> str:
        """The input path of an installed module's file: the same module in this
        checkout (a moved or copied checkout reruns nothing), once per file."""
        if installed not in self._paths:
            self._paths[installed] = checkout_path(self.package / installed.relative_to(INSTALLED))
        return self._paths[installed]

    def simulation(self, experiment: Experiment) -> list[str]:
        """The code inputs of a row's jobs: the generic script and the module of the
        row's function, less the table (the row is in the params) and, for a chunk of a
        map, the units table (gather_map labels the map)."""
        name = experiment.function.split(":")[0]
        return self("simulate.py", name, labels=not experiment.chunks, leave_out=[self.table])

    @cache  # noqa: B019 (one instance per Snakemake run)
    def drawing(self, draw: str, script: str = "figure.py") -> list[str]:
        """The code inputs of a figure job (or of a scenario's comparison, ``script``):
        the script's imports and the figure's own drawing module (figures.py imports it
        by name, so only that drawing's edit reruns the figure), less the registry."""
        return self(script, f"replication.drawing.{draw}", leave_out=[self.registry])

    def template(self, page: str) -> list[str]:
        """A page's template and the style sheet it includes: code of its job too (not
        modules: no import edge)."""
        folder = self.package / "replication" / "templates"
        return [checkout_path(folder / page), checkout_path(folder / "style.css")]

    def checkout_file(self, *parts: str) -> str:
        """A file of the checkout (``docs/assumptions.md``) as an input path."""
        return checkout_path(self.package.parents[1].joinpath(*parts))
