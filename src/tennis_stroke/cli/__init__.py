"""Simulate tennis strokes with the double-pendulum model of Youn (arXiv:1505.01916) and
check the replication of the paper's claims.

The commands: ``strike`` (one stroke), ``sweep`` (a grid of strokes into netCDF),
``params`` (the model's parameters, readings and model options), ``claims`` (the check of
a claims table), ``identify`` (the readings fitted to the fit sets of
``config/readings.yaml``), ``config explain`` (what a config key drives), ``whatif`` (a
what-if scenario beside the paper) and ``explore`` (the live explorer).

Bad input ends with one line ``tennis-stroke: error: ...`` on stderr and exit status 2,
before any output file is created; Ctrl-C ends with one line and exit status 130.  The
first paragraph of this docstring is ``tennis-stroke --help``'s description: plain text.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._version import __version__

EXIT_USAGE = 2
#: Exit status after SIGTERM (128 + SIGTERM, as a shell reports it).
EXIT_TERMINATED = 143
#: Exit status after Ctrl-C (128 + SIGINT, as a shell reports it).
EXIT_INTERRUPTED = 130
#: Strokes per thread in one call of the compiled solver during a sweep: a sweep runs in
#: blocks so that Ctrl-C (handled between blocks) stops it within a fraction of a second
#: (4096 strokes at about 16 us per stroke and thread, docs/performance.md: about
#: 0.07 s).  Blocks never change a number: every stroke is computed on its own.
SWEEP_BLOCK_PER_THREAD = 4096
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


def fail(message: str) -> None:
    """One line on stderr (whatever ``message`` holds), then exit status 2."""
    line = " ".join(message.split())
    sys.stderr.write(f"tennis-stroke: error: {line}\n")
    raise SystemExit(EXIT_USAGE)


def parse_set(items: Sequence[str]) -> dict[str, object]:
    from ..model.params import parse_value

    out: dict[str, object] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"--set expects KEY=VALUE, got {item!r}")
        out[key.strip()] = parse_value(key.strip(), value.strip())
    return out


#: The two forms of a range on the command line, as ``--help`` and the errors say them.
RANGE_FORMS = (
    "START:STOP:NUM (NUM points from START to STOP, both included) or START:STOP/STEP "
    "(from START to STOP in steps of STEP, which must land on STOP; the config's form)"
)


@dataclass(frozen=True)
class GridRange:
    """A sweep's axis as the command line gives it: ``step`` None for ``START:STOP:NUM``
    (``num`` points), else ``START:STOP/STEP`` (``num`` counts its points)."""

    start: float
    stop: float
    num: int
    step: float | None = None

    def values(self) -> np.ndarray:
        """The axis: :func:`numpy.linspace` for a count, the workflow's inclusive grid
        (:func:`tennis_stroke.experiments.grids.grid`) for a step."""
        if self.step is None:
            return np.linspace(self.start, self.stop, self.num)
        from ..experiments.grids import grid

        return grid(self.start, self.stop, self.step)


def parse_range(text: str, name: str) -> np.ndarray:
    """``START:STOP:NUM`` or ``START:STOP/STEP`` -> the axis (degrees)."""
    return range_spec(text, name).values()


def range_spec(text: str, name: str) -> GridRange:
    """``START:STOP:NUM`` or ``START:STOP/STEP`` -> :class:`GridRange`, checked, nothing
    allocated; a bad form or value raises ValueError (one line naming ``--name``)."""
    option = f"--{name}"
    ends, slash, step_text = text.partition("/")
    parts = ends.split(":")
    if len(parts) != (2 if slash else 3):
        raise ValueError(f"{option} expects {RANGE_FORMS}, got {text!r}")
    start = _range_number(option, "START", parts[0])
    stop = _range_number(option, "STOP", parts[1])
    if not math.isfinite(stop - start):
        raise ValueError(f"{option} STOP - START overflows, got {text!r}")
    if slash:
        return _step_range(option, start, stop, _range_number(option, "STEP", step_text))
    try:
        num = int(parts[2])
    except ValueError:
        raise ValueError(
            f"{option} NUM (of START:STOP:NUM) must be a whole number of points, got "
            f"{parts[2]!r} (a step is written START:STOP/STEP)"
        ) from None
    if num < 1:
        raise ValueError(f"{option} NUM must be >= 1, got {num}")
    return GridRange(start, stop, num)


def _range_number(option: str, part: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{option} {part} must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{option} {part} must be finite, got {text!r}")
    return value


def _step_range(option: str, start: float, stop: float, step: float) -> GridRange:
    """``START:STOP/STEP``, by the rules the workflow applies to a configured range."""
    from ..experiments.grids import grid_size, lands_on_stop

    if step <= 0:
        raise ValueError(f"{option} STEP must be > 0, got {step:g}")
    if stop < start:
        raise ValueError(f"{option} STOP {stop:g} is below START {start:g} (a step goes up)")
    if not lands_on_stop(start, stop, step):
        raise ValueError(
            f"{option} step {step:g} does not land on STOP {stop:g} from START {start:g} "
            "(a whole number of steps; START:STOP:NUM gives NUM points instead)"
        )
    return GridRange(start, stop, grid_size(start, stop, step), step)


def angle(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"angle must be finite, got {text!r}")
    return value


#: After ``tennis-stroke --help``'s list of commands.
_EPILOG = (
    "Run 'tennis-stroke COMMAND --help' for the options of a command; docs/cli.md describes "
    "every one. Bad input prints one line 'tennis-stroke: error: ...' and exits with status 2."
)
#: The sign of the model's angles (:mod:`tennis_stroke.model.dynamics`), said beside each
#: angle's long name and unit (:mod:`tennis_stroke.io.units`).
_ANGLE_SIGN = "counter-clockwise positive"


def _description() -> str:
    """The module docstring's first paragraph, as one line of plain text."""
    return " ".join(__doc__.split("\n\n")[0].split())


def angle_help(name: str, also: str = "") -> str:
    """An angle option's help: its long name and unit from the one table of units and
    long names, and the sign convention."""
    from ..io.units import VARIABLES

    unit, long_name = VARIABLES[name]
    return f"{long_name}, {_ANGLE_SIGN} ({unit}){also}"


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="tennis-stroke", description=_description(), epilog=_EPILOG)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for add in (
        _add_strike,
        _add_sweep,
        _add_params,
        _add_claims,
        _add_identify,
        _add_config,
        _add_whatif,
        _add_explore,
    ):
        add(sub)
    return parser


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


def _add_strike(sub) -> None:
    strike = sub.add_parser(
        "strike",
        help="simulate one stroke",
        description="Simulate one stroke: every result field with its unit and meaning.",
    )
    strike.add_argument(
        "--theta0", type=angle, required=True, metavar="DEG", help=angle_help("theta0")
    )
    strike.add_argument(
        "--delta0", type=angle, required=True, metavar="DEG", help=angle_help("delta0")
    )
    strike.add_argument(
        "--json",
        action="store_true",
        help="print one JSON object: the resolved parameters, solver settings and result",
    )
    add_model_options(strike)


def _add_sweep(sub) -> None:
    sweep = sub.add_parser(
        "sweep",
        help="simulate a (theta0, delta0) grid into netCDF",
        description="Simulate every stroke of a (theta0, delta0) grid into a netCDF file. "
        f"A RANGE is {RANGE_FORMS}.",
    )
    for name in ("theta0", "delta0"):
        sweep.add_argument(
            f"--{name}", required=True, metavar="RANGE", help=angle_help(name, ": a RANGE")
        )
    sweep.add_argument(
        "--out",
        required=True,
        metavar="FILE.nc",
        help="the netCDF file to write (under a temporary name, then renamed)",
    )
    sweep.add_argument("--threads", type=int, default=None, help="threads (default: all)")
    sweep.add_argument("--no-progress", action="store_true", help="no progress bar")
    sweep.add_argument(
        "--max-memory",
        default=None,
        metavar="SIZE",
        help="refuse a grid needing more memory (e.g. 8G; default: "
        "$TENNIS_STROKE_MAX_MEMORY, else half the machine's memory)",
    )
    add_model_options(sweep)


def _add_params(sub) -> None:
    params = sub.add_parser(
        "params",
        help="list the model's parameters (unit, default, source, bounds), readings and "
        "model options: the keys of --set",
        description="List every model parameter with its unit, default, where the default "
        "comes from (the paper, fitted to the fit sets, derived) and bounds, then every "
        "reading and model option with its choices: the keys 'strike' and 'sweep' take "
        "with --set.",
    )
    params.add_argument(
        "--readings",
        default="config/readings.yaml",
        help="the reading space whose fit sets say which defaults are fitted "
        "(default config/readings.yaml)",
    )


def _add_claims(sub) -> None:
    claims = sub.add_parser(
        "claims",
        help="check a claims table: exit 1 if a claim marked reproduce failed",
        description="Check a claims table the workflow wrote and print it: every claim with "
        "its status, the paper's value and ours; exit 1 if a claim marked reproduce failed.",
    )
    claims.add_argument(
        "csv",
        nargs="?",
        default="results/claims.csv",
        metavar="CLAIMS.csv",
        help="the claims table (default: results/claims.csv)",
    )
    claims.add_argument(
        "--claims",
        default="config/claims.yaml",
        help="the declared claims the table must hold, in order (default: config/claims.yaml)",
    )
    claims.add_argument(
        "--junit",
        metavar="FILE.xml",
        help="also write the claims as JUnit XML for CI (a test case per claim)",
    )


def _add_identify(sub) -> None:
    identify = sub.add_parser(
        "identify", help="fit the paper's open readings to the declared fit sets"
    )
    identify.add_argument("--rows", type=int, default=6, help="best fits to print per fit set")
    identify.add_argument(
        "--claims", default="config/claims.yaml", help="claims (the fit targets' values)"
    )
    identify.add_argument(
        "--readings", default="config/readings.yaml", help="the declared reading space"
    )
    identify.add_argument(
        "--config", default="config/config.yaml", help="workflow config (the strokes)"
    )


def _add_config(sub) -> None:
    config = sub.add_parser("config", help="what the workflow's config keys drive")
    config_sub = config.add_subparsers(dest="action", required=True, parser_class=Parser)
    explain = config_sub.add_parser(
        "explain", help="the result files, figures and claims a config key changes"
    )
    explain.add_argument("key", nargs="?", help="a dotted config key (torque_delay.base_stroke.C2)")
    explain.add_argument("--all", action="store_true", help="every key, as a Markdown table")
    explain.add_argument("--config", default="config/config.yaml", help="workflow config")
    explain.add_argument("--claims", default="config/claims.yaml", help="the declared claims")


def _add_whatif(sub) -> None:
    whatif = sub.add_parser(
        "whatif",
        help="run a what-if scenario beside the paper (snakemake): its page or figures",
    )
    whatif.add_argument("name", help="the scenario (declared in config/scenarios.yaml, or new)")
    whatif.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="an override of a new scenario: a model parameter, reading or option "
        "(M2=0.35; 'tennis-stroke params' lists them) or a dotted config key "
        "(torque_delay.base_stroke.C2=8); a declared scenario is changed in "
        "config/scenarios.yaml",
    )
    whatif.add_argument(
        "--figure",
        action="append",
        default=[],
        metavar="FIG",
        help="only this figure of the paper (fig2, fig09, fig09_v_tau); default: the page "
        "and its article",
    )
    whatif.add_argument("-j", "--cores", type=int, default=2, help="snakemake --cores (2)")
    whatif.add_argument("-n", "--dry-run", action="store_true", help="plan only (snakemake -n)")


def _add_explore(sub) -> None:
    explore = sub.add_parser(
        "explore",
        help="a live explorer in the browser: change a parameter, see Figs. 2-3 and 9 and "
        "their claims recomputed",
    )
    explore.add_argument(
        "--figure",
        choices=("fig2", "fig3", "fig9"),
        default="fig2",
        help="the map shown: Fig. 2 (L1 0.3 m) or Fig. 3 (0.4 m; also for fig9); default fig2",
    )
    explore.add_argument(
        "--port", type=int, default=None, help="the port (default: a free one, printed)"
    )
    explore.add_argument(
        "--host",
        default="127.0.0.1",
        help="the address to serve on (default 127.0.0.1, this machine only; another one "
        "exposes the explorer to whoever reaches it)",
    )
    explore.add_argument(
        "--threads", type=int, default=None, help="solver threads (default: every core)"
    )


def solver_settings(args: argparse.Namespace):
    from ..solver.settings import SolverSettings

    kwargs = {"method": args.method}
    if args.rtol is not None:
        kwargs["rtol"] = args.rtol
    if args.atol is not None:
        kwargs["atol"] = args.atol
    return SolverSettings(**kwargs)


def _strike(args: argparse.Namespace) -> int:
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
    from ..io.units import VARIABLES
    from ..solver.results import COUNT_FIELDS, FILE_NAMES, RESULT_FIELDS

    print(
        f"stroke theta0 = {args.theta0:g} deg, delta0 = {args.delta0:g} deg: "
        f"{result['status_name']}"
    )
    for name in RESULT_FIELDS:
        units, long_name = VARIABLES[FILE_NAMES.get(name, name)]
        if name in COUNT_FIELDS and name != "status":
            print(f"  {name:18s} {int(result[name]):14d} {units:7s} {long_name}")
        elif name != "status":
            print(f"  {name:18s} {result[name]:14.6f} {units:7s} {long_name}")
    return 0


def _sweep_blocks(theta0, delta0, overrides, settings, threads, block, progress):
    """``strike_batch`` over the grid ``theta0 x delta0`` in blocks of ``block`` strokes
    (Ctrl-C is handled between blocks); the result fields on the grid."""
    from ..solver.stroke import strike_batch

    nd, n = delta0.size, theta0.size * delta0.size
    results: dict[str, np.ndarray] = {}
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n, unit="stroke", leave=False)
    try:
        for a in range(0, n, block):
            index = np.arange(a, min(a + block, n))
            res = strike_batch(
                theta0[index // nd], delta0[index % nd], overrides, settings, threads
            )
            for name, values in res.items():
                results.setdefault(name, np.empty(n, values.dtype))[a : a + index.size] = values
            if bar is not None:
                bar.update(index.size)
    finally:
        if bar is not None:
            bar.close()
    return {name: values.reshape(theta0.size, nd) for name, values in results.items()}


def _sweep(args: argparse.Namespace) -> int:
    from ..io.netcdf import check_writable, result_dataset, write_netcdf
    from ..model.params import resolve_params
    from ..pipeline.memory import batch_bytes, check_memory, memory_limit, result_bytes
    from ..solver.results import OK
    from ..solver.stroke import default_threads

    theta_range = range_spec(args.theta0, "theta0")
    delta_range = range_spec(args.delta0, "delta0")
    overrides = parse_set(args.set)
    params = resolve_params(overrides)
    settings = solver_settings(args)
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads must be >= 1, got {args.threads}")
    threads = min(args.threads or default_threads(), default_threads())
    n = theta_range.num * delta_range.num
    block = min(n, SWEEP_BLOCK_PER_THREAD * threads)
    check_memory(
        result_bytes(n) + batch_bytes(block, threads, settings.history),
        f"a sweep of {theta_range.num} x {delta_range.num} strokes",
        memory_limit(args.max_memory, "--max-memory"),
    )
    out = check_writable(args.out)
    theta0, delta0 = theta_range.values(), delta_range.values()
    start = time.perf_counter()
    results = _sweep_blocks(
        theta0,
        delta0,
        overrides,
        settings,
        args.threads,
        block,
        progress=not args.no_progress and sys.stderr.isatty(),
    )
    wall = time.perf_counter() - start
    ds = result_dataset(
        results,
        {"theta0": theta0, "delta0": delta0},
        params,
        settings,
        {"wall_time_s": wall, "command": " ".join(sys.argv)},
    )
    write_netcdf(ds, out)
    n_ok = int((results["status"] == OK).sum())
    print(f"{out}: {results['status'].size} strokes ({n_ok} ok) in {wall:.2f} s")
    return 0


def text_table(
    columns: Sequence[str],
    rows: Sequence[Sequence[str]],
    width: int = 0,
    right: Sequence[int] = (),
) -> str:
    """``rows`` under ``columns`` as aligned plain text, two spaces between columns, the
    columns numbered in ``right`` aligned right; with ``width``, the last column wraps to
    fit it (its further lines indented under it)."""
    import textwrap

    widths = [max(len(str(r[i])) for r in [columns, *rows]) for i in range(len(columns) - 1)]
    indent = sum(widths) + 2 * len(widths)
    fill = max(width - indent, 30) if width else 0
    lines = []
    for row in [columns, *rows]:
        head = "".join(
            f"{str(cell):{'>' if i in right else '<'}{w}s}  "
            for i, (cell, w) in enumerate(zip(row, widths, strict=False))
        )
        last = textwrap.wrap(str(row[-1]), fill) if fill else [str(row[-1])]
        lines.append(head + (last[0] if last else ""))
        lines.extend(" " * indent + more for more in last[1:])
    return "\n".join(line.rstrip() for line in lines)


def _params(args: argparse.Namespace) -> int:
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


def _claims_table(table) -> str:
    """Every claim of a claims table (checked) as one aligned line: id, status (in the
    report's words), the paper's value, ours, unit and tolerance."""
    from ..replication.claims import STATUS_WORDS

    rows = [
        (
            row["id"],
            STATUS_WORDS[row["status"]][1],
            f"{float(row['paper_value']):.4g}",
            f"{float(row['reproduced_value']):.4g}",
            row["unit"],
            f"{float(row['tolerance']):g}",
        )
        for row in table.to_dict("records")
    ]
    columns = ("claim", "status", "paper", "ours", "unit", "tolerance")
    return text_table(columns, rows, right=(2, 3, 5))


def _claims(args: argparse.Namespace) -> int:
    import io
    from contextlib import redirect_stdout
    from pathlib import Path

    from ..inference.claims import ClaimError, load_claims
    from ..inference.paper_config import describe_departures, read_record
    from ..replication.claims import check, read_table

    try:
        declared = load_claims(args.claims)
    except ClaimError as exc:
        raise ValueError(f"the declared claims: {exc}") from None
    if not Path(args.csv).is_file():
        raise ValueError(f"claims table {args.csv!r} does not exist (run the workflow first)")
    record = read_record(args.csv)
    if record["scenario"]:
        # a scenario is an exploration: the table is checked, never graded
        read_table(args.csv, [c["id"] for c in declared])
        if args.junit:
            raise ValueError("--junit grades the paper's configuration only, not a scenario")
        name = record["scenario"]["name"]
        print(f"{args.csv}: scenario {name!r}, an exploration beside the paper: not graded")
        for change in record["scenario"]["changes"]:
            print(f"  {change['text']}")
        return 0
    if record["departures"]:
        raise ValueError(
            f"{args.csv} was computed under a configuration that departs from the paper's, "
            f"so it is not graded: {describe_departures(record)} (declare a change as a "
            "scenario in config/scenarios.yaml and restore config/config.yaml)"
        )
    # the check prints its verdict; the table goes above it, and nothing is printed when
    # the check refuses the table
    verdict = io.StringIO()
    with redirect_stdout(verdict):
        status = check(args.csv, [c["id"] for c in declared], declared)
    print(_claims_table(read_table(args.csv)))
    print(verdict.getvalue(), end="")
    if args.junit:
        from ..replication.junit import write_junit

        write_junit(read_table(args.csv), args.junit)
        print(f"wrote {args.junit}")
    return status


def _identify(args: argparse.Namespace) -> int:
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


def _config(args: argparse.Namespace) -> int:
    from ..inference.claims import ClaimError, load_claims
    from ..io.config_files import ConfigFileError, load_yaml
    from ..pipeline.explain import UnknownKeyError, explain, markdown, text

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


def _whatif(args: argparse.Namespace) -> int:
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


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tennis-stroke`` console script."""
    from ..io.interrupts import terminate_raises

    with terminate_raises():
        return _main(argv)


def _explore(args: argparse.Namespace) -> int:
    from pathlib import Path

    if not Path("Snakefile").is_file() or not Path("config/config.yaml").is_file():
        raise ValueError(f"no Snakefile in {Path.cwd()}: run explore from the project's folder")
    if args.port is not None and not 0 < args.port < 65536:
        raise ValueError(f"--port {args.port}: a port is 1 to 65535")
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads {args.threads}: at least 1")
    from ..live.server import serve

    return serve(Path.cwd(), args.figure, args.host, args.port, args.threads)


def _main(argv: Sequence[str] | None) -> int:
    from ..io.interrupts import Terminated

    try:
        args = build_parser().parse_args(argv)
        from ..io.errors import OutputError, ResultError
        from ..model.params import ParameterError
        from ..solver.compiled import CompileCacheError

        commands = {
            "strike": _strike,
            "sweep": _sweep,
            "params": _params,
            "claims": _claims,
            "identify": _identify,
            "config": _config,
            "whatif": _whatif,
            "explore": _explore,
        }
        try:
            return commands[args.command](args)
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
