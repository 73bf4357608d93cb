"""The runs of the workflow, as its rules read them: the paper's configuration and each
declared what-if scenario's, checked before any job.

A job belongs to a run by its wildcards: ``{run}`` is empty for the paper's (its files
under ``results/``) and ``scenarios/NAME/`` for a scenario's (under
``results/scenarios/NAME/``); a scenario's own jobs (its page, article, comparisons)
have a ``{scenario}`` wildcard.  :class:`Runs` gives every input and params function of
the rules from a job's wildcards: its configuration, its files (a scenario reads the
paper's file wherever it changes nothing that file's job reads), its figures and what
they say of the scenario.  :func:`checked_config` and :meth:`Runs.declared` are the
checks before any job; each failure is one line (:class:`PlanningError`).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path

from .._imports import PACKAGE as INSTALLED
from ..experiments.grids import chunk_count
from ..experiments.specs import EXPERIMENTS, PAPER_RESULTS, RESULT_FILES, sorted_data
from ..inference.claims import claim_axis_errors, claim_errors, load_claims
from ..inference.paper_config import PaperConfigError, load_paper_inputs
from ..inference.reading_space import ReadingSpace, ReadingSpaceError, load_reading_space
from ..replication.marks import mark_values
from ..replication.registry import FIGURES
from . import params as job_params
from .checkout import hold_folder, installed_difference, runs_no_code
from .config_check import (
    canonical,
    config_errors,
    job_points,
    load_schema,
    numbers_from_strings,
    rows_per_job,
    search_jobs,
    with_defaults,
)
from .resources import asked
from .scenarios import (
    FOLDER,
    SCENARIOS_FILE,
    ScenarioError,
    changes,
    changes_read,
    changing_config,
    describe,
    folder,
    load_scenarios,
    resolved_results,
    unreached,
)
from .targets import damaged_results, foreign_results

#: The robustness analysis' map, gathered from chunks like the table's maps.
ROBUSTNESS_MAP = "robustness/claims"
#: Nothing matches it (a wildcard constraint with no name to match).
NOTHING = "(?!x)x"


class PlanningError(Exception):
    """A check before any job failed: what failed (``config``, ``claims``, ...) and one
    line saying why."""

    def __init__(self, kind: str, message: str):
        super().__init__(message)
        self.kind = kind

    def line(self) -> str:
        return (
            f"tennis-stroke {self.kind} error: {self}"
            if self.kind
            else f"tennis-stroke error: {self}"
        )


def checked_config(config: dict, schema: Path) -> tuple[object, ReadingSpace]:
    """Check the workflow ``config``, the one validation of a Snakemake start (changed in
    place: nested ``--config`` values, which arrive as strings, become numbers again; the
    scenarios given on the command line are taken out, returned first; the schema's
    defaults filled in, every value in one spelling, :func:`canonical`), the claims
    (config/claims.yaml: ids, result files, measurements and their arguments,
    tolerances, else they fail after every simulation) and the reading space
    (config/readings.yaml, with the claims its fit sets name: the robustness analysis'
    chunks are planned from it); then the config against ``schema`` and its bounds,
    counting the readings the largest robustness job searches in lockstep.  Returns the
    command line's scenarios and the reading space."""
    config.update(numbers_from_strings(config))
    adhoc = config.pop("scenarios", None)
    errors = claim_errors("config/claims.yaml")
    if errors:
        raise PlanningError("claims", errors[0])
    claims = load_claims("config/claims.yaml")  # checked just above: read once here
    try:
        space = load_reading_space("config/readings.yaml", [c["id"] for c in claims])
    except ReadingSpaceError as exc:
        raise PlanningError("readings", str(exc)) from None
    multiverse = space.raw["multiverse"]
    loaded = load_schema(schema)
    filled = with_defaults(config, loaded)
    config.clear()
    config.update(filled)
    errors = config_errors(
        config, schema, rows_per_job(multiverse["readings"], multiverse["chunks"])
    )
    if errors:
        raise PlanningError("config", errors[0])
    errors = claim_axis_errors(claims, config, "config/claims.yaml") or claim_axis_errors(
        claims,
        space.at_resolution(config),
        "config/claims.yaml",
        " at the robustness analysis' resolution, config/readings.yaml",
    )
    if errors:
        raise PlanningError("claims", errors[0])
    # one spelling per value (C2: 5 is 5.0, keys in the schema's order): equal settings,
    # equal job params, no rerun
    spelled = canonical(config, loaded)
    config.clear()
    config.update(spelled)
    return adhoc, space


def guard_checkout(basedir: Path, argv: list[str]) -> None:
    """The files a run would build on: a damaged result file (truncated, garbage), or
    one at a row's path that its job did not write (:func:`foreign_results`), is
    named before any job (Snakemake would take it for up to date, and every job reading
    it would fail; a scenario's never stops the paper's run: a warning), and the jobs
    must run the checkout's code (an installed copy that differs would run stale code
    while the reruns follow the checkout's edits: refused when jobs would run, a warning
    for a dry run or ``--touch``, which run no code).  Last, one run at a time writes
    the working folder (:func:`~tennis_stroke.pipeline.checkout.hold_folder`): another
    one active is named, and the locks of a run that died are removed."""
    damaged = damaged_results()
    for path, problem in damaged:
        if path.startswith(f"results/{FOLDER}/"):
            sys.stderr.write(
                f"tennis-stroke results warning: {path} is damaged ({problem}): remove it; "
                "asking for its scenario's files again rebuilds it\n"
            )
    damaged = [d for d in damaged if not d[0].startswith(f"results/{FOLDER}/")]
    if damaged:
        path, problem = damaged[0]
        raise PlanningError(
            "results",
            f"{path} is damaged ({problem}): remove it and make it with: snakemake -j2 {path}",
        )
    for path, why in foreign_results():
        raise PlanningError(
            "results",
            f"{path} is not this workflow's file ({why}: written by tennis-stroke sweep "
            f"--out, say): move it elsewhere and make it with: snakemake -j2 {path}",
        )
    differs = installed_difference(INSTALLED, basedir / "src" / "tennis_stroke")
    if differs is not None:
        line = (
            f"the jobs would import the tennis_stroke installed at {str(INSTALLED)!r}, whose "
            f"{differs} differs from this checkout's: install the checkout editable (make "
            "install, or pip install -e .)"
        )
        if not runs_no_code(argv):
            raise PlanningError("", line)
        sys.stderr.write(f"tennis-stroke warning: {line}\n")
    active = hold_folder(argv)
    if active:
        raise PlanningError("", active)


def _regex(names) -> str:
    """A regex matching any of ``names`` (none: nothing)."""
    return "|".join(re.escape(n) for n in names) or NOTHING


class Runs:
    """The paper's run and the declared scenarios' (:meth:`declared`), and every input
    and params function of the rules, from a job's wildcards."""

    def __init__(self, config, space, scenarios, scenario_configs, errors, stated):
        self.config = config
        self.space = space
        #: The scenarios' overrides and checked configurations by name, and the errors
        #: of those refused (by name; None: the scenarios file itself).
        self.scenarios, self.configs, self.errors = scenarios, scenario_configs, errors
        #: The model parameters and readings whose default a fit set chose: a scenario's
        #: overrides call their default "fitted", as `tennis-stroke params` does.
        self.fitted = space.fitted()
        #: The config keys the paper states: a scenario's change of any other key names
        #: its old value config.yaml's, not the paper's.
        self.stated = stated
        #: The declared claims by id, and the scenario notes said in this run.
        self.claims = {c["id"]: c for c in load_claims("config/claims.yaml")}
        self._said: set[tuple[str, str, str]] = set()
        self._files: dict[str, dict[str, str]] = {}
        #: The largest search's points, for one reading and for a chunk's in lockstep.
        self._search_points: dict[bool, int] = {}

    @classmethod
    def declared(cls, config: Mapping, space: ReadingSpace, adhoc, schema: Path) -> Runs:
        """The runs of ``config`` (checked): the scenarios of config/scenarios.yaml and
        the command line's (``adhoc``), each checked as the paper's configuration is.  A
        bad scenario never stops the paper's run: it is named in one warning line, and
        asking for any of its files is refused in one line (:meth:`refuse_unknown`)."""
        try:
            stated = [item["key"] for item in load_paper_inputs("config/claims.yaml")]
        except PaperConfigError as exc:
            raise PlanningError("claims", str(exc)) from None
        errors: dict = {}
        try:
            scenarios = load_scenarios(SCENARIOS_FILE, adhoc, errors)
        except ScenarioError as exc:
            scenarios, errors[None] = {}, str(exc)
        configs = {}
        claims = load_claims("config/claims.yaml")
        for name, overrides in scenarios.items():
            try:
                configs[name] = changing_config(config, name, overrides, schema)
            except ScenarioError as exc:
                errors[name] = str(exc)
                continue
            off = claim_axis_errors(claims, configs[name], "config/claims.yaml")
            if off:
                errors[name] = f"scenario {name!r}: {off[0]}"
                del configs[name]
        for error in errors.values():
            sys.stderr.write(f"tennis-stroke scenario warning: {error} (the paper's runs go on)\n")
        return cls(config, space, scenarios, configs, errors, stated)

    # -- a job's run ------------------------------------------------------------------

    @property
    def declared_names(self) -> str:
        """A regex of the declared scenarios' names (none: nothing)."""
        return _regex(self.configs)

    @property
    def run_pattern(self) -> str:
        """The ``run`` wildcard: empty (the paper's) or a declared scenario's folder."""
        return f"({FOLDER}/({self.declared_names})/)?"

    def scenario_name(self, wildcards) -> str | None:
        """The scenario of a job: its ``scenario`` wildcard, or the name in its ``run``
        wildcard (``scenarios/NAME/``); None for the paper's configuration."""
        if "scenario" in wildcards.keys():
            return wildcards.scenario
        run = wildcards.get("run") or ""
        return run.split("/")[1] if run else None

    def configuration(self, wildcards) -> Mapping:
        """The configuration of a job: its scenario's, else the paper's."""
        name = self.scenario_name(wildcards)
        return self.config if name is None else self.configs[name]

    def files(self, wildcards) -> dict[str, str]:
        """The result files of a job's run by key (:meth:`files_of`)."""
        return self.files_of(self.scenario_name(wildcards))

    def files_of(self, name: str | None) -> dict[str, str]:
        """The result files of a run by key: the paper's (``name`` None), or scenario
        ``name``'s, its own where it changes what their jobs read and the paper's
        elsewhere."""
        if name is None:
            return dict(PAPER_RESULTS)
        if name not in self._files:
            self._files[name] = resolved_results(self.config, self.configs[name], name)
        return dict(self._files[name])

    # -- the table's rows -------------------------------------------------------------

    def row_param(self, key: str):
        """A params function: ``key`` of the row's params in its run's configuration
        (:func:`tennis_stroke.pipeline.params.simulation_params`; None where the row has
        no such key: a row without the model has no ``common``)."""

        def value(wildcards):
            row = ROWS[wildcards.stem]
            return job_params.simulation_params(row, self.configuration(wildcards)).get(key)

        return value

    def map_rows(self, name: str, configuration: Mapping) -> tuple[int, int]:
        """Requested chunks and number of rows of the first axis of map ``name`` in a
        ``configuration``; the robustness analysis' from config/readings.yaml (its rows:
        at most the declared number of readings)."""
        if name == ROBUSTNESS_MAP:
            spec = self.space.raw["multiverse"]
            return spec["chunks"], spec["readings"]
        experiment = CHUNKED[name]
        requested = experiment.requested_chunks(configuration)
        return requested, experiment.row_count(experiment.arguments(configuration))

    def chunk_files(self, wildcards) -> list[str]:
        """The chunk files of a map: the requested chunk count, at most one per row."""
        n = chunk_count(*self.map_rows(wildcards.map, self.configuration(wildcards)))
        name = self.scenario_name(wildcards)
        where = "results" if name is None else folder(name)
        return [f"{where}/chunks/{wildcards.map}/{i}-of-{n}.nc" for i in range(n)]

    # -- resources --------------------------------------------------------------------

    def row_resources(self, name: str):
        """A resources function (``mem_mb`` or ``runtime``): what a job of the table's row
        (its ``stem`` wildcard) asks, from its points in its run's configuration."""

        def value(wildcards):
            points, _ = job_points(ROWS[wildcards.stem], self.configuration(wildcards))
            return asked(points)[name]

        return value

    def map_resources(self, name: str):
        """A resources function: what gathering a chunked map asks (all its strokes)."""

        def value(wildcards):
            if wildcards.map == ROBUSTNESS_MAP:
                return asked(self.space.raw["multiverse"]["readings"])[name]
            e = CHUNKED[wildcards.map]
            batches = e.strokes(e.arguments(self.configuration(wildcards))) if e.strokes else [0]
            return asked(batches[0])[name]

        return value

    def search_resources(self, name: str, lockstep: bool = False):
        """A resources function: what a job running the claims' searches asks, from the
        largest search's first batch in the paper's configuration, for one reading or
        (``lockstep``) for a robustness chunk's readings at once."""
        if lockstep not in self._search_points:  # once per kind, for every rule asking
            readings = 1
            if lockstep:
                multiverse = self.space.raw["multiverse"]
                readings = rows_per_job(multiverse["readings"], multiverse["chunks"])
            found = (p for _, _, p in search_jobs(self.config, readings))
            self._search_points[lockstep] = max(found, default=0)
        points = self._search_points[lockstep]
        return lambda wildcards: asked(points)[name]

    # -- claims -----------------------------------------------------------------------

    def claim_inputs(self, wildcards) -> dict[str, str]:
        """The claims job's result files by key; for the paper's run, with its robustness
        analysis (a scenario is an exploration, not graded)."""
        files = self.files(wildcards)
        if self.scenario_name(wildcards) is None:
            files["robustness"] = RESULT_FILES["robustness"]
        return files

    def record(self, wildcards) -> dict | None:
        """What a job's scenario is (None for the paper's run): its name, its overrides
        and every change of the paper's configuration they make (key, the paper's value,
        the scenario's)."""
        name = self.scenario_name(wildcards)
        if name is None:
            return None
        return {
            "name": name,
            "overrides": self.scenarios[name],
            "changes": [
                {
                    "key": k,
                    "paper": old,
                    "scenario": new,
                    "text": describe(k, old, new, self.fitted, self.stated),
                }
                for k, old, new in changes(self.config, self.configs[name])
            ],
        }

    # -- figures ----------------------------------------------------------------------

    def figure_inputs(self, wildcards) -> list[str]:
        """The result files a figure is drawn from: the registry's for the paper's; for a
        scenario's, its own where it changes them and the paper's elsewhere (and, once,
        what of the scenario does not reach them)."""
        name = self.scenario_name(wildcards)
        if name is None:
            return FIGURES[wildcards.name].inputs
        self.say_unreached(name, FIGURES[wildcards.name].files)
        files = self.files(wildcards)
        return [files[key] for key in FIGURES[wildcards.name].files]

    @staticmethod
    def paper_figure_inputs(wildcards) -> list[str]:
        """The paper's result files a figure is drawn from (a scenario's comparison)."""
        return [PAPER_RESULTS[key] for key in FIGURES[wildcards.name].files]

    @staticmethod
    def figure_entry(wildcards) -> dict:
        """A figure's registry entry as plain data (a param: editing one entry reruns its
        figure only)."""
        return sorted_data(asdict(FIGURES[wildcards.name]))

    def figure_marks(self, wildcards) -> list:
        """The paper's values of the claims a figure marks (a param: editing one of them
        in config/claims.yaml reruns the figures that draw it, and no other)."""
        return sorted_data(mark_values(FIGURES[wildcards.name], self.claims))

    def figure_note(self, wildcards) -> str:
        """A figure's second title line: none for the paper's; for a scenario's, the
        scenario and what it changes of what the figure's files read."""
        name = self.scenario_name(wildcards)
        if name is None:
            return ""
        read = changes_read(FIGURES[wildcards.name].files, self.config, self.configs[name])
        what = (
            "; ".join(describe(*change, self.fitted, self.stated) for change in read)
            or "no change to its inputs"
        )
        return f"scenario {name}: {what}"

    def changed_figures(self, name: str) -> list[str]:
        """The paper's figures scenario ``name`` changes (one of their files is its own)."""
        files = self.files_of(name)
        return [
            f for f in PAPER_FIGURES if any(files[k] != PAPER_RESULTS[k] for k in FIGURES[f].files)
        ]

    # -- a scenario's page and article ------------------------------------------------

    def report_figures(self, wildcards) -> list[str]:
        """A scenario's page's figure inputs: its own of the figures it changes, and each
        against the paper's (shared scales, the difference); and, once, what of the
        scenario reaches none of them."""
        self.say_unreached(wildcards.scenario)
        return self.figure_files(wildcards) + self.comparisons(wildcards)

    def figure_files(self, wildcards) -> list[str]:
        """The scenario's own images of the figures it changes."""
        where = folder(wildcards.scenario)
        return [f"{where}/figures/{f}.png" for f in self.changed_figures(wildcards.scenario)]

    def comparisons(self, wildcards) -> list[str]:
        """The comparison images of the figures a scenario changes (its page, its
        article)."""
        where = folder(wildcards.scenario)
        return [f"{where}/compare/{f}.png" for f in self.changed_figures(wildcards.scenario)]

    def figure_table(self, wildcards) -> list[dict]:
        """Each paper figure on a scenario's page: the paper's file, the scenario's (None
        where it changes nothing the figure shows) and what it changes of its inputs."""
        name = wildcards.scenario
        changed = set(self.changed_figures(name))
        files = self.files(wildcards)
        out = []
        for f in PAPER_FIGURES:
            read = changes_read(FIGURES[f].files, self.config, self.configs[name])
            out.append(
                {
                    "name": f,
                    "paper": f"results/figures/{f}.png",
                    "scenario": f"{folder(name)}/figures/{f}.png" if f in changed else None,
                    "compare": f"{folder(name)}/compare/{f}.png" if f in changed else None,
                    "changes": [describe(*c, self.fitted, self.stated) for c in read],
                    "files": [
                        [PAPER_RESULTS[k], files[k]]
                        for k in FIGURES[f].files
                        if files[k] != PAPER_RESULTS[k]
                    ],
                }
            )
        return out

    def say_unreached(self, name: str, files=None) -> None:
        """At planning, once per override and row: each model override of scenario
        ``name`` that the rows of ``files`` (default all) set themselves, and the key each
        reads instead (one line per override; the jobs neither rerun nor relabel those
        rows)."""
        rows: dict[str, list[str]] = {}
        for key in PAPER_RESULTS if files is None else files:
            for line in unreached(self.config, self.configs[name], [key]):
                override, _, row = line.partition(" does not reach ")
                if (name, override, row) not in self._said:
                    self._said.add((name, override, row))
                    rows.setdefault(override, []).append(row)
        for override, missed in rows.items():
            sys.stderr.write(
                f"tennis-stroke scenario note: scenario {name!r}: {override} does not reach "
                f"{', '.join(missed)}\n"
            )

    # -- refusals ---------------------------------------------------------------------

    @property
    def unknown_pattern(self) -> str:
        """A name no scenario declares (rule unknown_scenario refuses it in one line)."""
        return f"(?!(?:{self.declared_names})/)[^/]+"

    def refuse_unknown(self, wildcards) -> None:
        """The input function of rule unknown_scenario: one line, then exit status 1."""
        error = self.errors.get(wildcards.unknown, self.errors.get(None))
        if error:
            sys.stderr.write(f"tennis-stroke scenario error: {error}\n")
            sys.exit(1)
        known = ", ".join(sorted(self.configs)) or "none"
        sys.stderr.write(
            f"tennis-stroke scenario error: no scenario {wildcards.unknown!r} is declared "
            f"(declared: {known}; config/scenarios.yaml, or --config "
            f"'scenarios={{{wildcards.unknown}: {{...}}}}')\n"
        )
        sys.exit(1)

    @staticmethod
    def refuse_unknown_file(wildcards) -> None:
        """The input function of rule unknown_scenario_file: one line, then exit 1."""
        where = f"{wildcards.top}/scenarios/{wildcards.declared}/{wildcards.path}"
        sys.stderr.write(
            f"tennis-stroke scenario error: no rule makes {where}: a scenario makes the "
            "paper experiments' files, the paper's figures (figures/fig02_angle_map.png "
            "... figures/fig14_elbow_paths.png), claims.csv and its page "
            "(docs/scenarios.md)\n"
        )
        sys.exit(1)


#: The table's rows by the stem of their file (the ``stem`` wildcard), and the maps
#: computed in chunks (gathered by rule gather_map, with the robustness analysis').
ROWS = {e.stem: e for e in EXPERIMENTS.values()}
CHUNKED = {e.stem: e for e in EXPERIMENTS.values() if e.chunks}
CHUNKED_MAPS = _regex([*CHUNKED, ROBUSTNESS_MAP])
#: The paper's figures, drawn from the paper's experiments only: the figures a scenario
#: draws.
PAPER_FIGURES = [name for name, f in FIGURES.items() if set(f.files) <= set(PAPER_RESULTS)]


def stems(chunked: bool, family: str | None = None) -> str:
    """A regex of the stems of the rows computed in chunks or not, of one family or all."""
    return _regex(
        e.stem
        for e in EXPERIMENTS.values()
        if bool(e.chunks) == chunked and family in (None, e.family)
    )


#: The paths a scenario's rules make below its folders; any other path under a declared
#: scenario is refused in one line (rule unknown_scenario_file).
SCENARIO_PATHS = "|".join(
    [
        rf"chunks/({stems(True, 'paper')})/\d+-of-\d+\.nc",
        *(re.escape(f"{e.stem}.nc") for e in EXPERIMENTS.values() if e.family == "paper"),
        rf"figures/({_regex(PAPER_FIGURES)})\.png",
        rf"compare/({_regex(PAPER_FIGURES)})\.png",
        r"claims\.csv",
        r"configuration\.yaml",
        r"index\.html",
        r"article\.pdf",
    ]
)
UNKNOWN_SCENARIO_PATH = rf"(?!(?:{SCENARIO_PATHS})$).+"
#: A figure of ``results/figures/`` that the registry does not have (``fig9.png``,
#: ``fig09_v_tua.png``): rule unknown_figure's name, so that a guess is one line
#: (:func:`refuse_unknown_figure`), not Snakemake's traceback.  The look-ahead reads
#: past the wildcard to the rule's ``.png`` (the pattern's end).
UNKNOWN_FIGURE = rf"(?!(?:{_regex(FIGURES)})\.png$)[^/]+"


def nearest_figures(name: str, n: int = 3) -> list[str]:
    """The figures of the registry nearest to ``name``: those of its number (``fig9``:
    ``fig09_v_tau``), else the closest spellings (difflib), always some."""
    import difflib

    number = re.fullmatch(r"([a-z]+)0*(\d+)", name)
    if number:
        prefix = f"{number[1]}{int(number[2]):02d}_"
        same = [f for f in sorted(FIGURES) if f.startswith(prefix)]
        if same:
            return same[:n]
    return difflib.get_close_matches(name, sorted(FIGURES), n=n, cutoff=0.0)


def refuse_unknown_figure(wildcards) -> None:
    """The input function of rule unknown_figure: one line naming the file and the
    nearest figures, then exit 1."""
    near = ", ".join(f"results/figures/{f}.png" for f in nearest_figures(wildcards.name))
    sys.stderr.write(
        f"tennis-stroke figure error: no rule makes results/figures/{wildcards.name}.png "
        f"(nearest: {near}; python -m tennis_stroke.pipeline.targets lists every file)\n"
    )
    sys.exit(1)
