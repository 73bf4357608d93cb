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
before any output file is created; Ctrl-C ends with one line and exit status 130; a
stdout that cannot take the output (closed, or full) with one line and exit status 1,
and a reader that went away (``| head``) with exit status 1 alone.  The
first paragraph of this docstring is ``tennis-stroke --help``'s description: plain text.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from types import ModuleType

from .._version import __version__
from . import claims, config, explore, identify, params, strike, sweep, whatif
from .parsing import EXIT_USAGE, Parser, fail, say

#: Exit status after SIGTERM (128 + SIGTERM, as a shell reports it).
EXIT_TERMINATED = 143
#: Exit status after Ctrl-C (128 + SIGINT, as a shell reports it).
EXIT_INTERRUPTED = 130
#: Exit status when stdout does not take the output: closed, full, or its reader gone.
EXIT_NO_OUTPUT = 1

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


class StdoutError(Exception):
    """stdout did not take the output (the ``OSError`` or ``ValueError`` it raised is
    the cause); not a ``ValueError`` itself, so no command's error handling takes it."""


class _Stdout:
    """``sys.stdout`` while a command runs: a write or flush that fails raises
    :class:`StdoutError`, so that the entry point tells it apart from the other
    ``OSError``s of a command; everything else is the stream's own."""

    def __init__(self, stream) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return self._stream.write(text)
        except (OSError, ValueError) as exc:  # ValueError: I/O operation on closed file
            raise StdoutError(exc) from exc

    def flush(self) -> None:
        try:
            self._stream.flush()
        except (OSError, ValueError) as exc:
            raise StdoutError(exc) from exc

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tennis-stroke`` console script."""
    from ..io.interrupts import terminate_raises

    if sys.stdout is None:  # closed before Python started (a shell's >&-)
        say("tennis-stroke: error: stdout is closed: the output would be lost")
        return EXIT_NO_OUTPUT
    stdout = sys.stdout
    sys.stdout = _Stdout(stdout)
    try:
        with terminate_raises():
            return _main(argv)
    finally:
        sys.stdout = stdout


def _output_lost(exc: StdoutError) -> int:
    """One line for a stdout that did not take the output, none for a reader that went
    away (``| head``); stdout then points at the null device, so that Python's own flush
    at exit finds nothing to fail on (it would add a message and exit status 120)."""
    import os

    cause = exc.__cause__
    if not isinstance(cause, BrokenPipeError):
        say(f"tennis-stroke: error: stdout did not take the output: {cause}")
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):  # not a descriptor (a test's stream) or closed
        pass
    return EXIT_NO_OUTPUT


def _main(argv: Sequence[str] | None) -> int:
    from ..io.interrupts import Terminated

    try:
        args = build_parser().parse_args(argv)
        from ..io.errors import OutputError, ResultError
        from ..model.params import ParameterError
        from ..solver.compiled import CompileCacheError

        run = {_name(command): command.run for command in COMMANDS}[args.command]
        try:
            code = run(args)
            sys.stdout.flush()  # here, not at exit: a full stdout is told, not lost
            return code
        except (ParameterError, OutputError, ResultError, CompileCacheError, ValueError) as exc:
            fail(str(exc))
        except MemoryError:
            fail("out of memory (give sweep a lower --max-memory or TENNIS_STROKE_MAX_MEMORY)")
    except StdoutError as exc:
        return _output_lost(exc)
    except KeyboardInterrupt:
        say("tennis-stroke: interrupted")
        return EXIT_INTERRUPTED
    except Terminated:
        say("tennis-stroke: terminated")
        return EXIT_TERMINATED
    return EXIT_USAGE
