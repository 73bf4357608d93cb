"""The command line's parser and the options its commands share: a one-line error with
exit status 2 (:func:`fail`), help wrapped at spaces, negative numbers after an option,
the angles' help from the one table of units, ``--set`` and the solver's options."""

from __future__ import annotations

import argparse
import contextlib
import math
import re
import sys
from collections.abc import Sequence

#: Exit status after bad input (argparse's).
EXIT_USAGE = 2

#: A value after an option that argparse would take for an option: a negative number
#: (``-1``, ``-1e3``, ``-.5``, ``-inf``) or range (``-30:10:5``).
_NEGATIVE_VALUE = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


def _join_negative_values(args: Sequence[str]) -> list[str]:
    """``--opt -1`` -> ``--opt=-1``: argparse reads ``-1e3`` or ``-30:10:5`` after an
    option as an option of its own (it only knows plain negative numbers)."""
    out: list[str] = []
    for arg in args:
        prev = out[-1] if out else ""
        if (
            _NEGATIVE_VALUE.match(arg)
            and prev.startswith("--")
            and prev != "--"
            and "=" not in prev
        ):
            out[-1] = f"{prev}={arg}"
        else:
            out.append(arg)
    return out


class _HelpFormatter(argparse.HelpFormatter):
    """argparse's help, wrapped at spaces only (never inside ``counter-clockwise``)."""

    def _split_lines(self, text, width):
        import textwrap

        return textwrap.wrap(" ".join(text.split()), width, break_on_hyphens=False)

    def _fill_text(self, text, width, indent):
        import textwrap

        return textwrap.fill(
            " ".join(text.split()),
            width,
            initial_indent=indent,
            subsequent_indent=indent,
            break_on_hyphens=False,
        )


class Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump), exit status 2, help wrapped at
    spaces, and negative numbers accepted after an option (``--delta0 -1``,
    ``--theta0 -30:10:5``)."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", _HelpFormatter)
        super().__init__(*args, **kwargs)

    def parse_known_args(self, args=None, namespace=None):  # noqa: D102
        args = sys.argv[1:] if args is None else args
        return super().parse_known_args(_join_negative_values(list(args)), namespace)

    def error(self, message: str) -> None:  # noqa: D102
        fail(message)


def say(line: str) -> None:
    """``line`` on stderr, or nowhere if stderr is closed or full: the exit status still
    tells, and a message that cannot be written must not raise in its place."""
    stream = sys.stderr  # None when the descriptor was closed before Python started
    if stream is not None:
        with contextlib.suppress(OSError, ValueError):
            stream.write(f"{line}\n")
            stream.flush()


def fail(message: str) -> None:
    """One line on stderr (whatever ``message`` holds), then exit status 2."""
    say("tennis-stroke: error: " + " ".join(message.split()))
    raise SystemExit(EXIT_USAGE)


def angle(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"angle must be finite, got {text!r}")
    return value


#: The sign of the model's angles (:mod:`tennis_stroke.model.dynamics`), said beside each
#: angle's long name and unit (:mod:`tennis_stroke.io.units`).
_ANGLE_SIGN = "counter-clockwise positive"


def angle_help(name: str, also: str = "") -> str:
    """An angle option's help: its long name and unit from the one table of units and
    long names, and the sign convention."""
    from ..io.units import VARIABLES

    unit, long_name = VARIABLES[name]
    return f"{long_name}, {_ANGLE_SIGN} ({unit}){also}"


def add_model_options(p: argparse.ArgumentParser) -> None:
    """``--set`` and the solver's options; choices and defaults from the solver's settings."""
    from ..solver.settings import MAX_ATOL, MAX_RTOL, METHOD_IDS, SolverSettings

    p.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a model parameter (SI units), a reading or a model option; "
        "repeatable. 'tennis-stroke params' lists every KEY with its unit, default and bounds",
    )
    p.add_argument(
        "--method",
        choices=tuple(METHOD_IDS),
        default=SolverSettings.method,
        help=f"integrator, an embedded Runge-Kutta pair (default {SolverSettings.method})",
    )
    for name, bound in (("rtol", MAX_RTOL), ("atol", MAX_ATOL)):
        kind = "relative" if name == "rtol" else "absolute"
        p.add_argument(
            f"--{name}",
            type=float,
            default=None,
            metavar=name.upper(),
            help=f"{kind} tolerance of the local error (default "
            f"{getattr(SolverSettings, name):g}, at most {bound:g})",
        )


def set_items(items: Sequence[str]) -> list[tuple[str, str]]:
    """``--set KEY=VALUE`` items as ``(KEY, VALUE)`` pairs, stripped, for every command
    that takes ``--set`` (``strike``, ``sweep``, ``whatif``).  A key given twice is
    refused, naming it (the last would win silently); ``model.NAME`` and ``NAME`` are
    one key (``whatif`` reads both as the model's ``NAME``)."""
    out: list[tuple[str, str]] = []
    seen: dict[str, str] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ValueError(f"--set {item!r}: expected KEY=VALUE")
        name = key.removeprefix("model.")
        if name in seen:
            raise ValueError(
                f"--set {item!r}: {name!r} is set twice (also --set {seen[name]!r}); give "
                "each key once"
            )
        seen[name] = item
        out.append((key, value.strip()))
    return out


def parse_set(items: Sequence[str]) -> dict[str, object]:
    """``--set NAME=VALUE`` items of a command that takes model parameters, readings and
    options by name (:func:`set_items`): a name that is none of them is refused with the
    closest names, as every command refuses a name or key it does not know."""
    from ..io.config_files import did_you_mean
    from ..model.params import known_names, parse_value

    out: dict[str, object] = {}
    for key, value in set_items(items):
        item = f"{key}={value}"
        if key not in known_names():
            raise ValueError(
                f"--set {item!r}: {key!r} is no model parameter, reading or option"
                f"{did_you_mean(key, known_names())} ('tennis-stroke params' lists them)"
            )
        out[key] = parse_value(key, value)
    return out


def solver_settings(args: argparse.Namespace):
    from ..solver.settings import SolverSettings

    kwargs = {"method": args.method}
    if args.rtol is not None:
        kwargs["rtol"] = args.rtol
    if args.atol is not None:
        kwargs["atol"] = args.atol
    return SolverSettings(**kwargs)
