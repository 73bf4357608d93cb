"""What a what-if asks of the workflow: the scenario checked as the workflow will check
it, the files it ends in, and the Snakemake command line that makes them
(:func:`plan_whatif`).  ``tennis-stroke whatif`` runs the plan; anything else that starts
a scenario's run (the workflow's tools, the explorer) can plan it the same way.

A declared scenario (``config/scenarios.yaml``) is run by name, so that the workflow reads
its declaration; a new one is given as ``--set KEY=VALUE`` overrides and passed to
Snakemake as ``--config scenarios={NAME: {...}}``.  Every refusal is one line
(:class:`~tennis_stroke.pipeline.scenarios.ScenarioError`), before Snakemake runs.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from ..io.config_files import ConfigFileError
from ..replication.registry import paper_figure
from .config_check import load_schema
from .scenarios import (
    SCENARIOS_FILE,
    SCHEMA_FILE,
    ScenarioError,
    folder,
    load_scenarios,
    override_from,
    scenario_reach,
    scenario_results,
)


@dataclass(frozen=True)
class WhatIf:
    """A planned what-if: scenario ``name``, its ``overrides`` as the command line gave
    them (None for a declared scenario, which the workflow reads from its declaration),
    the ``targets`` Snakemake is asked for (its figures, or its page and article), and
    what a figure asked for is drawn from."""

    name: str
    overrides: dict | None
    targets: tuple[str, ...]
    #: The figures asked for (registry names; none: the page and article) and the
    #: result files of the scenario by key, its own and the paper's it reads.
    figures: tuple[str, ...] = ()
    files: Mapping[str, str] = field(default_factory=dict)

    def snakemake_args(self, cores: int, dry_run: bool = False) -> list[str]:
        """Snakemake's arguments for the run (what follows ``snakemake``): the targets on
        ``cores`` cores, the log of ``make report`` (one line per job), the jobs an
        interrupted run left incomplete run again (``--rerun-incomplete``, as ``make
        report`` does: Snakemake refuses to start otherwise), a new scenario's overrides
        as ``--config``, and ``-n`` for a dry run."""
        args = ["--cores", str(cores), *self.targets, "--quiet", "rules", "--rerun-incomplete"]
        if self.overrides is not None:
            flow = yaml.safe_dump({self.name: self.overrides}, default_flow_style=True, width=10**6)
            args += ["--config", f"scenarios={flow.strip()}"]
        if dry_run:
            args.append("-n")
        return args


def plan_whatif(
    name: str, sets: Sequence[str] = (), figures: Sequence[str] = (), root: str | Path = "."
) -> WhatIf:
    """The what-if run of scenario ``name`` in the project at ``root``: declared in its
    ``config/scenarios.yaml``, or new with the overrides ``sets`` (``KEY=VALUE``), and only
    ``figures`` of the paper (names as :func:`~tennis_stroke.replication.registry.paper_figure`
    reads them; none: the scenario's page and article).  Checked as the workflow will
    check it: a bad value, an unknown figure, a figure that nothing of the overrides
    reaches, ``sets`` for a declared name, an undeclared name without ``sets``: each
    raises :class:`ScenarioError` (one line)."""
    root = Path(root)
    try:
        others: dict = {}  # another scenario's error does not stop this one
        declared = load_scenarios(root / SCENARIOS_FILE, errors=others)
        if sets and (name in declared or name in others):
            # its folder holds the declared scenario's files: --set would replace them
            raise ScenarioError(
                f"scenario {name!r} is declared in config/scenarios.yaml: --set would "
                "replace its overrides and its files; give the new scenario another name "
                "(or change the declaration)"
            )
        try:
            top_level = load_schema(root / SCHEMA_FILE).get("properties", {})
        except (OSError, ConfigFileError) as exc:
            raise ScenarioError(f"{root / SCHEMA_FILE}: {exc}") from None
        overrides = override_from(sets, top_level) if sets else None
        if overrides is None and name in others:
            raise ScenarioError(others[name])
        if overrides is None and name not in declared:
            known = ", ".join(sorted(declared)) or "none"
            raise ScenarioError(
                f"scenario {name!r} is not declared in config/scenarios.yaml "
                f"(declared: {known}): give its overrides with --set KEY=VALUE"
            )
        load_scenarios(root / SCENARIOS_FILE, {name: overrides or {}})  # its name
        figures = [paper_figure(f) for f in figures]
        # checked as the workflow will check it: a bad value is one line here, not
        # Snakemake's log; an override that reaches nothing asked for is refused (what
        # it does not reach of the rest, the workflow says at planning)
        given = declared.get(name) if overrides is None else overrides
        scenario_reach(name, given, figures, root)
        files = scenario_results(name, given, root)
    except KeyError as exc:  # str() of a KeyError quotes its message
        raise ScenarioError(str(exc.args[0])) from None
    where, pages = folder(name), folder(name, "report")
    targets = [f"{where}/figures/{f}.png" for f in figures] or [
        f"{pages}/index.html",
        f"{pages}/article.pdf",
    ]
    return WhatIf(name, overrides, tuple(targets), tuple(figures), files)
