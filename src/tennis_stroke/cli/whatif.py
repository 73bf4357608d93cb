"""run a what-if scenario beside the paper (snakemake): its page or figures"""

from __future__ import annotations

import argparse
import sys


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("name", help="the scenario (declared in config/scenarios.yaml, or new)")
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="an override of a new scenario: a model parameter, reading or option "
        "(M2=0.35; 'tennis-stroke params' lists them) or a dotted config key "
        "(torque_delay.base_stroke.C2=8); a declared scenario is changed in "
        "config/scenarios.yaml",
    )
    parser.add_argument(
        "--figure",
        action="append",
        default=[],
        metavar="FIG",
        help="only this figure of the paper (fig2, fig09, fig09_v_tau); default: the page "
        "and its article",
    )
    parser.add_argument("-j", "--cores", type=int, default=2, help="snakemake --cores (2)")
    parser.add_argument("-n", "--dry-run", action="store_true", help="plan only (snakemake -n)")


def run(args: argparse.Namespace) -> int:
    import shlex
    from pathlib import Path

    import yaml

    from ..io.config_files import ConfigFileError
    from ..io.interrupts import run_forwarding
    from ..pipeline.config_check import load_schema
    from ..pipeline.scenarios import (
        SCHEMA_FILE,
        ScenarioError,
        folder,
        load_scenarios,
        override_from,
        scenario_reach,
    )
    from ..replication.registry import paper_figure

    if not Path("Snakefile").is_file():
        raise ValueError(f"no Snakefile in {Path.cwd()}: run whatif from the project's folder")
    try:
        others: dict = {}  # another scenario's error does not stop this one
        declared = load_scenarios("config/scenarios.yaml", errors=others)
        if args.set and (args.name in declared or args.name in others):
            # its folder holds the declared scenario's files: --set would replace them
            raise ScenarioError(
                f"scenario {args.name!r} is declared in config/scenarios.yaml: --set would "
                "replace its overrides and its files; give the new scenario another name "
                "(or change the declaration)"
            )
        try:
            top_level = load_schema(SCHEMA_FILE).get("properties", {})
        except (OSError, ConfigFileError) as exc:
            raise ScenarioError(f"{SCHEMA_FILE}: {exc}") from None
        overrides = override_from(args.set, top_level) if args.set else None
        if overrides is None and args.name in others:
            raise ScenarioError(others[args.name])
        if overrides is None and args.name not in declared:
            known = ", ".join(sorted(declared)) or "none"
            raise ScenarioError(
                f"scenario {args.name!r} is not declared in config/scenarios.yaml "
                f"(declared: {known}): give its overrides with --set KEY=VALUE"
            )
        load_scenarios("config/scenarios.yaml", {args.name: overrides or {}})  # its name
        figures = [paper_figure(f) for f in args.figure]
        # checked as the workflow will check it: a bad value is one line here, not
        # Snakemake's log; an override that reaches nothing asked for is refused (what
        # it does not reach of the rest, the workflow says at planning)
        scenario_reach(
            args.name, declared.get(args.name) if overrides is None else overrides, figures
        )
    except ScenarioError as exc:
        raise ValueError(str(exc)) from None
    except KeyError as exc:  # str() of a KeyError quotes its message
        raise ValueError(str(exc.args[0])) from None
    where, pages = folder(args.name), folder(args.name, "report")
    targets = [f"{where}/figures/{f}.png" for f in figures] or [
        f"{pages}/index.html",
        f"{pages}/article.pdf",
    ]
    command = [sys.executable, "-m", "snakemake", "--cores", str(args.cores), *targets]
    command += ["--quiet", "rules"]  # the log of make report: one line per job
    if overrides is not None:
        flow = yaml.safe_dump({args.name: overrides}, default_flow_style=True, width=10**6)
        command += ["--config", f"scenarios={flow.strip()}"]
    if args.dry_run:
        command.append("-n")
    print("$ " + shlex.join(["snakemake", *command[3:]]), flush=True)  # what reruns it
    code = run_forwarding(command)  # Ctrl-C: Snakemake removes its locks, then we stop
    if code == 0 and not args.dry_run:
        print("\n".join(targets))
    return code
