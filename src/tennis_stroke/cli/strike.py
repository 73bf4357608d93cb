"""simulate one stroke

Simulate one stroke: every result field with its unit, its meaning and the stroke it
comes from (the swing without the ball, run on to phi = 0, or the stroke with the ball,
which leaves that swing at the contact start).
"""

from __future__ import annotations

import argparse
import json
import math

from .parsing import add_model_options, angle, angle_help, parse_set, solver_settings


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--theta0", type=angle, required=True, metavar="DEG", help=angle_help("theta0")
    )
    parser.add_argument(
        "--delta0", type=angle, required=True, metavar="DEG", help=angle_help("delta0")
    )
    parser.add_argument(
        "--json",
        action="store_true",
        help="print one JSON object: the resolved parameters, solver settings and result",
    )
    add_model_options(parser)


def run(args: argparse.Namespace) -> int:
    from ..model.params import resolve_params, scalar_params
    from ..solver.stroke import strike

    overrides = parse_set(args.set)
    params = resolve_params(overrides)
    settings = solver_settings(args)
    result = strike(args.theta0, args.delta0, overrides, settings)
    if args.json:
        fields = {"status": result["status_name"], "status_code": result["status"]}
        fields.update((k, v) for k, v in result.items() if k not in ("status", "status_name"))
        payload = {
            "params": {
                "theta0_deg": args.theta0,
                "delta0_deg": args.delta0,
                **scalar_params(params),
            },
            "solver": settings.as_dict(),
            "result": {
                k: None if isinstance(v, float) and math.isnan(v) else v for k, v in fields.items()
            },
        }
        print(json.dumps(payload, indent=2))
        return 0
    from ..io.result_strokes import result_label
    from ..io.units import unit_of
    from ..solver.results import COUNT_FIELDS, FILE_NAMES, RESULT_FIELDS

    print(
        f"stroke theta0 = {args.theta0:g} deg, delta0 = {args.delta0:g} deg: "
        f"{result['status_name']}"
    )
    for name in RESULT_FIELDS:
        file_name = FILE_NAMES.get(name, name)
        units, label = unit_of(file_name), result_label(file_name)
        if name in COUNT_FIELDS and name != "status":
            print(f"  {name:18s} {int(result[name]):14d} {units:7s} {label}")
        elif name != "status":
            print(f"  {name:18s} {result[name]:14.6f} {units:7s} {label}")
    return 0
