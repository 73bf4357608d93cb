"""The ``tennis-stroke`` command: one stroke (``strike``), a grid of strokes (``sweep``),
the check of the claims table (``claims``), the readings fitted to both fit sets of
``config/readings.yaml`` (``identify``), what a config key drives (``config explain``)
a what-if scenario beside the paper (``whatif``) and the live explorer (``explore``).

Bad input ends with one line ``tennis-stroke: error: ...`` on stderr and exit status 2,
before any output file is created; Ctrl-C ends with one line and exit status 130.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import time
from collections.abc import Sequence

import numpy as np

from ._version import __version__

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


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump), exit status 2, and negative
    numbers accepted after an option (``--delta0 -1``, ``--theta0 -30:10:5``)."""

    def parse_known_args(self, args=None, namespace=None):  # noqa: D102
        args = sys.argv[1:] if args is None else args
        return super().parse_known_args(_join_negative_values(list(args)), namespace)

    def error(self, message: str) -> None:  # noqa: D102
        _fail(message)


def _fail(message: str) -> None:
    """One line on stderr (whatever ``message`` holds), then exit status 2."""
    line = " ".join(message.split())
    sys.stderr.write(f"tennis-stroke: error: {line}\n")
    raise SystemExit(EXIT_USAGE)


def _parse_set(items: Sequence[str]) -> dict[str, object]:
    from .model.params import parse_value

    out: dict[str, object] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"--set expects KEY=VALUE, got {item!r}")
        out[key.strip()] = parse_value(key.strip(), value.strip())
    return out


def parse_range(text: str, name: str) -> np.ndarray:
    """``START:STOP:NUM`` -> ``numpy.linspace(START, STOP, NUM)`` (degrees)."""
    return np.linspace(*range_spec(text, name))


def range_spec(text: str, name: str) -> tuple[float, float, int]:
    """``START:STOP:NUM`` -> ``(START, STOP, NUM)``, checked, nothing allocated."""
    parts = text.split(":")
    if len(parts) != 3:
        raise ValueError(f"--{name} expects START:STOP:NUM, got {text!r}")
    try:
        start, stop = float(parts[0]), float(parts[1])
        num = int(parts[2])
    except ValueError:
        raise ValueError(f"--{name} expects numbers START:STOP:NUM, got {text!r}") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise ValueError(f"--{name} START and STOP must be finite, got {text!r}")
    if num < 1:
        raise ValueError(f"--{name} NUM must be >= 1, got {num}")
    if not math.isfinite(stop - start):
        raise ValueError(f"--{name} STOP - START overflows, got {text!r}")
    return start, stop, num


def angle(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"angle must be finite, got {text!r}")
    return value


def build_parser() -> argparse.ArgumentParser:
    # the module docstring's first paragraph, without its reST markup
    summary = " ".join(__doc__.split("\n\n")[0].split()).replace("``", "")
    parser = _Parser(prog="tennis-stroke", description=summary)
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def common(p: argparse.ArgumentParser) -> None:
        p.add_argument(
            "--set",
            action="append",
            default=[],
            metavar="KEY=VALUE",
            help="override a model parameter (SI units) or a reading",
        )
        p.add_argument(
            "--method",
            default="DOP853",
            metavar="{DOP853,DP54}",
            help="integrator (default DOP853)",
        )
        p.add_argument("--rtol", type=float, default=None, help="relative tolerance")
        p.add_argument("--atol", type=float, default=None, help="absolute tolerance")

    strike = sub.add_parser("strike", help="simulate one stroke")
    strike.add_argument(
        "--theta0",
        type=angle,
        required=True,
        metavar="DEG",
        help="initial angle of rod 1 (arm) in degrees from -y, counter-clockwise positive",
    )
    strike.add_argument(
        "--delta0",
        type=angle,
        required=True,
        metavar="DEG",
        help="initial angle of rod 2 relative to rod 1, phi0 - theta0, in degrees",
    )
    strike.add_argument("--json", action="store_true", help="print one JSON object")
    common(strike)

    sweep = sub.add_parser("sweep", help="simulate a (theta0, delta0) grid into netCDF")
    sweep.add_argument("--theta0", required=True, metavar="START:STOP:NUM")
    sweep.add_argument("--delta0", required=True, metavar="START:STOP:NUM")
    sweep.add_argument("--out", required=True, metavar="FILE.nc")
    sweep.add_argument("--threads", type=int, default=None, help="threads (default: all)")
    sweep.add_argument("--no-progress", action="store_true", help="no progress bar")
    sweep.add_argument(
        "--max-memory",
        default=None,
        metavar="SIZE",
        help="refuse a grid needing more memory (e.g. 8G; default: "
        "$TENNIS_STROKE_MAX_MEMORY, else half the machine's memory)",
    )
    common(sweep)

    claims = sub.add_parser(
        "claims", help="check a claims table: exit 1 if a claim marked reproduce failed"
    )
    claims.add_argument("csv", nargs="?", default="results/claims.csv", metavar="CLAIMS.csv")
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

    config = sub.add_parser("config", help="what the workflow's config keys drive")
    config_sub = config.add_subparsers(dest="action", required=True, parser_class=_Parser)
    explain = config_sub.add_parser(
        "explain", help="the result files, figures and claims a config key changes"
    )
    explain.add_argument("key", nargs="?", help="a dotted config key (torque_delay.base_stroke.C2)")
    explain.add_argument("--all", action="store_true", help="every key, as a Markdown table")
    explain.add_argument("--config", default="config/config.yaml", help="workflow config")
    explain.add_argument("--claims", default="config/claims.yaml", help="the declared claims")

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
        help="an override: a model parameter or reading (M2=0.35) or a dotted config key "
        "(torque_delay.base_stroke.C2=8); replaces the declared scenario's overrides",
    )
    whatif.add_argument(
        "--figure",
        action="append",
        default=[],
        metavar="FIG",
        help="only this figure of the paper (fig2, fig09, fig09_v_tau); default: the page",
    )
    whatif.add_argument("-j", "--cores", type=int, default=2, help="snakemake --cores (2)")
    whatif.add_argument("-n", "--dry-run", action="store_true", help="plan only (snakemake -n)")
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
    return parser


def _settings(args: argparse.Namespace):
    from .solver.settings import SolverSettings

    kwargs = {"method": args.method}
    if args.rtol is not None:
        kwargs["rtol"] = args.rtol
    if args.atol is not None:
        kwargs["atol"] = args.atol
    return SolverSettings(**kwargs)


def _strike(args: argparse.Namespace) -> int:
    from .model.params import resolve_params, scalar_params
    from .solver.stroke import strike

    overrides = _parse_set(args.set)
    params = resolve_params(overrides)
    settings = _settings(args)
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
    from .io.units import VARIABLES
    from .solver.results import COUNT_FIELDS, FILE_NAMES, RESULT_FIELDS

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
    from .solver.stroke import strike_batch

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
    from .io.netcdf import check_writable, result_dataset, write_netcdf
    from .model.params import resolve_params
    from .pipeline.memory import batch_bytes, check_memory, memory_limit, result_bytes
    from .solver.results import OK
    from .solver.stroke import default_threads

    theta_spec = range_spec(args.theta0, "theta0")
    delta_spec = range_spec(args.delta0, "delta0")
    overrides = _parse_set(args.set)
    params = resolve_params(overrides)
    settings = _settings(args)
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads must be >= 1, got {args.threads}")
    threads = min(args.threads or default_threads(), default_threads())
    n = theta_spec[2] * delta_spec[2]
    block = min(n, SWEEP_BLOCK_PER_THREAD * threads)
    check_memory(
        result_bytes(n) + batch_bytes(block, threads, settings.history),
        f"a sweep of {theta_spec[2]} x {delta_spec[2]} strokes",
        memory_limit(args.max_memory, "--max-memory"),
    )
    out = check_writable(args.out)
    theta0, delta0 = np.linspace(*theta_spec), np.linspace(*delta_spec)
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


def _claims(args: argparse.Namespace) -> int:
    from pathlib import Path

    from .inference.claims import ClaimError, load_claims
    from .inference.paper_config import describe_departures, read_record
    from .replication.claims import check, read_table

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
    status = check(args.csv, [c["id"] for c in declared], declared)
    if args.junit:
        from .replication.junit import write_junit

        write_junit(read_table(args.csv), args.junit)
        print(f"wrote {args.junit}")
    return status


def _identify(args: argparse.Namespace) -> int:
    from pathlib import Path

    from .experiments.specs import fit_set_arguments
    from .inference.claims import load_claims
    from .inference.identification import run_identification, summary
    from .inference.reading_space import load_reading_space
    from .io.config_files import ConfigKeyError, load_yaml
    from .model.params import resolve_params

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
    from .inference.claims import ClaimError, load_claims
    from .io.config_files import ConfigFileError, load_yaml
    from .pipeline.explain import UnknownKeyError, explain, markdown, text

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
    import subprocess
    from pathlib import Path

    import yaml

    from .pipeline.scenarios import ScenarioError, folder, load_scenarios, override_from
    from .replication.registry import paper_figure

    if not Path("Snakefile").is_file():
        raise ValueError(f"no Snakefile in {Path.cwd()}: run whatif from the project's folder")
    try:
        declared = load_scenarios("config/scenarios.yaml")
        overrides = override_from(args.set) if args.set else None
        if overrides is None and args.name not in declared:
            known = ", ".join(sorted(declared)) or "none"
            raise ScenarioError(
                f"scenario {args.name!r} is not declared in config/scenarios.yaml "
                f"(declared: {known}): give its overrides with --set KEY=VALUE"
            )
        load_scenarios("config/scenarios.yaml", {args.name: overrides or {}})  # its name
        figures = [paper_figure(f) for f in args.figure]
    except (ScenarioError, KeyError) as exc:
        raise ValueError(str(exc).strip("'\"")) from None
    where = folder(args.name)
    targets = [f"{where}/figures/{f}.png" for f in figures] or [
        f"{folder(args.name, 'report')}/index.html"
    ]
    command = [sys.executable, "-m", "snakemake", "--cores", str(args.cores), *targets]
    if overrides is not None:
        flow = yaml.safe_dump({args.name: overrides}, default_flow_style=True, width=10**6)
        command += ["--config", f"scenarios={flow.strip()}"]
    if args.dry_run:
        command.append("-n")
    print("$ " + shlex.join(["snakemake", *command[3:]]), flush=True)
    done = subprocess.run(command, check=False)
    if done.returncode == 0 and not args.dry_run:
        print("\n".join(targets))
    return done.returncode


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tennis-stroke`` console script."""
    from .io.interrupts import terminate_raises

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
    from .live.server import serve

    return serve(Path.cwd(), args.figure, args.host, args.port, args.threads)


def _main(argv: Sequence[str] | None) -> int:
    from .io.interrupts import Terminated

    try:
        args = build_parser().parse_args(argv)
        from .io.errors import OutputError, ResultError
        from .model.params import ParameterError
        from .solver.compiled import CompileCacheError

        commands = {
            "strike": _strike,
            "sweep": _sweep,
            "claims": _claims,
            "identify": _identify,
            "config": _config,
            "whatif": _whatif,
            "explore": _explore,
        }
        try:
            return commands[args.command](args)
        except (ParameterError, OutputError, ResultError, CompileCacheError, ValueError) as exc:
            _fail(str(exc))
        except MemoryError:
            _fail("out of memory (give sweep a lower --max-memory or TENNIS_STROKE_MAX_MEMORY)")
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


if __name__ == "__main__":
    sys.exit(main())
