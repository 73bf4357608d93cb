"""what the workflow's config keys drive"""

from __future__ import annotations

import argparse

from .parsing import Parser


def add_arguments(parser: argparse.ArgumentParser) -> None:
    config_sub = parser.add_subparsers(dest="action", required=True, parser_class=Parser)
    explain = config_sub.add_parser(
        "explain", help="the result files, figures and claims a config key changes"
    )
    explain.add_argument("key", nargs="?", help="a dotted config key (torque_delay.base_stroke.C2)")
    explain.add_argument("--all", action="store_true", help="every key, as a Markdown table")
    explain.add_argument("--config", default="config/config.yaml", help="workflow config")
    explain.add_argument("--claims", default="config/claims.yaml", help="the declared claims")
    keys = config_sub.add_parser(
        "keys", help="every config key: type, bounds, value and description (config/README.md)"
    )
    keys.add_argument("--config", default="config/config.yaml", help="workflow config")


def run(args: argparse.Namespace) -> int:
    from ..inference.claims import ClaimError, load_claims
    from ..io.config_files import ConfigFileError, load_yaml
    from ..pipeline.explain import UnknownKeyError, explain, markdown, text

    if args.action == "keys":
        return _keys(args.config)
    try:
        config, claims = load_yaml(args.config), load_claims(args.claims)
    except (ConfigFileError, ClaimError) as exc:
        raise ValueError(str(exc)) from None
    if args.all == bool(args.key):
        raise ValueError("config explain takes a KEY or --all (one of them)")
    if args.all:
        print(markdown(config, claims))
        return 0
    try:
        print(text(explain(args.key, config, claims)))
    except UnknownKeyError as exc:
        raise ValueError(str(exc)) from None
    return 0


def _keys(config_path: str) -> int:
    from ..io.config_files import ConfigFileError, load_yaml
    from ..pipeline.config_check import key_table, load_schema
    from ..pipeline.scenarios import SCHEMA_FILE

    try:
        config, schema = load_yaml(config_path), load_schema(SCHEMA_FILE)
    except (ConfigFileError, OSError) as exc:
        raise ValueError(f"config keys: {exc} (run it from the project's folder)") from None
    print(key_table(schema, config))
    return 0
