"""list the model's parameters (unit, default, source, bounds), readings and model options:
the keys of --set

List every model parameter with its unit, default, where the default comes from (the
paper, fitted to the fit sets, derived) and bounds, then every reading and model option
with its choices: the keys 'strike' and 'sweep' take with --set.
"""

from __future__ import annotations

import argparse
import sys

from .tables import text_table


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--readings",
        default="config/readings.yaml",
        help="the reading space whose fit sets say which defaults are fitted "
        "(default config/readings.yaml)",
    )


def run(args: argparse.Namespace) -> int:
    import shutil

    from ..inference.reading_space import ReadingSpaceError, load_reading_space
    from ..model.listing import CHOICE_COLUMNS, PARAMETER_COLUMNS, choice_rows, parameter_rows

    try:  # the fitted defaults, as config/readings.yaml declares them
        fitted = load_reading_space(args.readings).fitted()
    except ReadingSpaceError as exc:
        raise ValueError(str(exc)) from None
    # a terminal wraps the meanings to its width; a pipe gets one line a row (for grep)
    width = shutil.get_terminal_size().columns if sys.stdout.isatty() else 0
    print("Model parameters, in SI units (--set NAME=VALUE). source: the paper's value,")
    print(f"fitted to the fit sets of {args.readings}, or derived from the others.\n")
    print(text_table(PARAMETER_COLUMNS, parameter_rows(fitted), width))
    print("\nReadings of the paper and model options (--set NAME=CHOICE); [paper] marks the")
    print("choice that reads the paper word for word, [fitted] a default fitted to the fit sets.\n")
    print(text_table(CHOICE_COLUMNS, choice_rows(fitted), width))
    return 0
