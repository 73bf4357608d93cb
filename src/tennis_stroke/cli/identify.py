"""fit the paper's open readings to the declared fit sets"""

from __future__ import annotations

import argparse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--rows", type=int, default=6, help="best fits to print per fit set")
    parser.add_argument(
        "--claims", default="config/claims.yaml", help="claims (the fit targets' values)"
    )
    parser.add_argument(
        "--readings", default="config/readings.yaml", help="the declared reading space"
    )
    parser.add_argument(
        "--config", default="config/config.yaml", help="workflow config (the strokes)"
    )


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..experiments.specs import fit_set_arguments
    from ..inference.claims import load_claims
    from ..inference.identification import run_identification, summary
    from ..inference.reading_space import load_reading_space
    from ..io.config_files import ConfigKeyError, load_yaml
    from ..model.params import resolve_params

    if args.rows < 1:
        raise ValueError(f"--rows must be >= 1, got {args.rows}")
    for path in (args.claims, args.config, args.readings):
        if not Path(path).is_file():
            raise ValueError(f"{path!r} does not exist (run from the project's folder)")
    # Each loader's error is one line naming its file (and the line of a YAML error).
    config = load_yaml(args.config)
    claims = load_claims(args.claims)
    space = load_reading_space(args.readings, [c["id"] for c in claims])
    if not isinstance(config, dict):
        raise ValueError(f"{args.config}: not a workflow config (a mapping of sections)")
    base = config.get("model") or {}
    if not isinstance(base, dict):
        raise ValueError(f"{args.config}: 'model' must be a mapping of parameters, got {base!r}")
    resolve_params(base)  # units and bounds: one line naming the parameter
    try:  # what the fit sets simulate, from the rows that compute it (as the workflow)
        fit = fit_set_arguments(config)
    except ConfigKeyError as exc:
        raise ValueError(f"{args.config}: {exc}") from None
    fits = run_identification(space, claims, **fit, base=base)
    print(summary(fits, args.rows))
    return 0
