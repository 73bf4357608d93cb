"""Simulate tennis strokes with the double-pendulum model of Youn (arXiv:1505.01916) and
check the replication of the paper's claims.

The commands: ``strike`` (one stroke), ``sweep`` (a grid of strokes into netCDF),
``params`` (the model's parameters, readings and model options), ``claims`` (the check of
a claims table), ``identify`` (the readings fitted to the fit sets of
``config/readings.yaml``), ``config explain`` (what a config key drives), ``whatif`` (a
what-if scenario beside the paper) and ``explore`` (the live explorer).  Each is a module
of this package, named as the command: its docstring is its help (the first paragraph,
the line of ``tennis-stroke --help``) and its description (the rest, if any),
``add_arguments(parser)`` its options and ``run(args)`` what it does, calling the
library; :mod:`.parsing` holds the parser and the options commands share.

Bad input ends with one line ``tennis-stroke: error: ...`` on stderr and exit status 2,
before any output file is created; Ctrl-C ends with one line and exit status 130.  The
first paragraph of this docstring is ``tennis-stroke --help``'s description: plain text.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from types import ModuleType

from .._version import __version__
from . import claims, config, explore, identify, params, strike, sweep, whatif
from .parsing import EXIT_USAGE, Parser, fail

#: Exit status after SIGTERM (128 + SIGTERM, as a shell reports it).
EXIT_TERMINATED = 143
#: Exit status after Ctrl-C (128 + SIGINT, as a shell reports it).
EXIT_INTERRUPTED = 130

#: The commands, in the order ``tennis-stroke --help`` lists them.
COMMANDS = (strike, sweep, params, claims, identify, config, whatif, explore)

#: After ``tennis-stroke --help``'s list of commands.
_EPILOG = (
    "Run 'tennis-stroke COMMAND --help' for the options of a command; docs/cli.md describes "
    "every one. Bad input prints one line 'tennis-stroke: error: ...' and exits with status 2."
)


def _description() -> str:
    """The module docstring's first paragraph, as one line of plain text."""
    return " ".join(__doc__.split("\n\n")[0].split())


def _name(command: ModuleType) -> str:
    """A command's name: its module's."""
    return command.__name__.rpartition(".")[2]


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="tennis-stroke", description=_description(), epilog=_EPILOG)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for command in COMMANDS:
        help_text, _, description = command.__doc__.partition("\n\n")
        command.add_arguments(
            sub.add_parser(_name(command), help=help_text, description=description or None)
        )
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tennis-stroke`` console script."""
    from ..io.interrupts import terminate_raises

    with terminate_raises():
        return _main(argv)


def _main(argv: Sequence[str] | None) -> int:
    from ..io.interrupts import Terminated

    try:
        args = build_parser().parse_args(argv)
        from ..io.errors import OutputError, ResultError
        from ..model.params import ParameterError
        from ..solver.compiled import CompileCacheError

        run = {_name(command): command.run for command in COMMANDS}[args.command]
        try:
            return run(args)
        except (ParameterError, OutputError, ResultError, CompileCacheError, ValueError) as exc:
            fail(str(exc))
        except MemoryError:
            fail("out of memory (give sweep a lower --max-memory or TENNIS_STROKE_MAX_MEMORY)")
    except KeyboardInterrupt:
        sys.stderr.write("tennis-stroke: interrupted\n")
        return EXIT_INTERRUPTED
    except Terminated:
        sys.stderr.write("tennis-stroke: terminated\n")
        return EXIT_TERMINATED
    except BrokenPipeError:  # the reader went away (e.g. `| head`): stop quietly
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    return EXIT_USAGE
