"""run a what-if scenario beside the paper (snakemake): its page or figures

With --figure, each figure's claims are printed after the run, measured from the files
it is drawn from as the claims are, with the inputs every stroke of it shares.
"""

# What the run asks of the workflow (the checks, the targets, Snakemake's command line)
# is planned by tennis_stroke.pipeline.whatif; this command prints and runs the plan.

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

    from .._cache import cache_problem
    from ..io.interrupts import run_forwarding
    from ..pipeline.whatif import plan_whatif
    from .parsing import set_items

    set_items(args.set)  # each key once
    if args.cores < 1:
        raise ValueError(f"-j/--cores must be >= 1, got {args.cores}")
    if not Path("workflow/Snakefile").is_file():
        raise ValueError(
            f"no workflow/Snakefile in {Path.cwd()}: run whatif from the project's folder"
        )
    problem = cache_problem()  # Snakemake's own message is a long traceback
    if problem:
        raise ValueError(problem)
    plan = plan_whatif(args.name, args.set, args.figure)  # a refusal: one line
    snakemake = plan.snakemake_args(args.cores, args.dry_run)
    print("$ " + shlex.join(["snakemake", *snakemake]), flush=True)  # what reruns it
    # a signal goes on to Snakemake and its jobs, which stop; then we stop
    code = run_forwarding([sys.executable, "-m", "snakemake", *snakemake])
    if code == 0 and not args.dry_run:
        _print_numbers(plan)
        print("\n".join(plan.targets))
    return code


def _print_numbers(plan) -> None:
    """Each figure of ``plan``: the inputs its strokes share, then its claims (ours as its
    files give them, the paper's beside)."""
    from ..inference.claims import load_claims
    from ..replication.figure_claims import figure_numbers
    from ..replication.registry import FIGURES, UNIT_SHORT

    claims = load_claims("config/claims.yaml") if plan.figures else []
    for name in plan.figures:
        shared, rows = figure_numbers(FIGURES[name], claims, plan.files)
        print(f"{name} of scenario {plan.name}" + (f", at {shared}" if shared else "") + ":")
        for row in rows:
            unit = UNIT_SHORT.get(row["unit"], row["unit"])
            value = f"{row['value']:.4g} {unit}".strip()
            print(f"  {row['id']:26s} {value:14s} {row['quantity']} (paper: {row['paper']:g})")
        if not rows:
            print("  (no claim of the paper reads only its files)")
