"""Bad workflow configs: each stops before any job, with one line naming key and rule."""

import copy

import pytest
import yaml
from conftest import ROOT, planned_kinds, run_snakemake, workdir

from tennis_stroke.io.config_files import ConfigFileError, load_yaml
from tennis_stroke.pipeline.config_check import (
    canonical,
    config_errors,
    key_table,
    load_schema,
    numbers_from_strings,
    points_errors,
    rows_per_job,
)
from tennis_stroke.pipeline.resources import DEFAULT_MAX_POINTS
from tennis_stroke.pipeline.runs import PlanningError, checked_config

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
GOOD = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())


def _set(config, path, value):
    node = config
    for key in path[:-1]:
        node = node[key]
    if value is _DELETE:
        del node[path[-1]]
    else:
        node[path[-1]] = value


_DELETE = object()

BAD = [  # (path, value, fragment of the message)
    # the same stroke or tolerance twice computes the same numbers twice
    (("fig4", "strokes"), [[120.0, 81.5], [120.0, 81.5]], "'fig4.strokes': [[120.0, 81.5], "),
    (
        ("solver_study", "compiled_tolerances"),
        [1e-8, 1e-8],
        "'solver_study.compiled_tolerances': [1e-08, 1e-08] has non-unique elements",
    ),
    # a range whose step does not land on its stop (it ran past it: tau = [0, 0.5])
    (
        ("torque_delay", "fig9", "tau"),
        {"start": 0.0, "stop": 0.3, "step": 0.5},
        "'torque_delay.fig9.tau': step 0.5 does not land on stop 0.3",
    ),
    (("angle_maps", "theta0"), {"start": 60.0, "stop": 120.0, "step": 0.7}, "does not land"),
    # a list where a model scalar belongs (it planned, then failed deep in numpy)
    (("model",), {"M2": [0.3, 0.4]}, "'model.M2': a model parameter or reading takes one value"),
    # bounds of the model parameters a row's values become, named by their config key
    (("elbow_force", "F0"), 1.0e6, "'elbow_force.F0': parameter 'F0' must be <= 10000 N"),
    (("mass_length", "M2"), {"start": -0.1, "stop": 0.5, "step": 0.1}, "'mass_length.M2'"),
    (("k_sensitivity", "k_contact"), [188.0, 1.0e13], "'k_sensitivity.k_contact': parameter"),
    (("torque_delay", "fig7", "tau"), {"start": 0.0, "stop": 20.0, "step": 0.5}, "parameter 'tau'"),
    (("torque_delay", "L1"), 1.0e3, "'torque_delay.L1': parameter 'L1' must be"),
    (("chunks", "angle_map"), 0, "'chunks.angle_map': 0 is less than the minimum of 1"),
    (("chunks", "delay_map"), 2.5, "'chunks.delay_map': 2.5 is not of type 'integer'"),
    (("max_failure_share",), 1.5, "'max_failure_share': 1.5 is greater than the maximum"),
    (("max_failure_share",), "1%", "'max_failure_share': '1%' is not of type 'number'"),
    (("threads",), 2, "'threads' was unexpected) (unknown key)"),
    (("solver", "rtol"), 0.0, "'solver.rtol': 0.0 is less than or equal to the minimum"),
    (("solver", "rtol"), -1e-6, "'solver.rtol'"),
    (("solver", "method"), "RK4", "'solver.method': 'RK4' is not one of"),
    (("solver", "atol"), float("nan"), "'solver.atol': nan is not a finite number"),
    (("model",), {"M2": -0.3}, "'M2' must be > 0 kg"),
    (("model",), {"L1": 0.0}, "'L1' must be > 0 m"),
    (("model",), {"bogus": 1.0}, "unknown parameter 'bogus'"),
    (("model",), {"k_contact": float("nan")}, "'model.k_contact': nan is not a finite"),
    (("model",), {"inertia": "hollow"}, "reading 'inertia' must be one of"),
    (("angle_maps", "theta0", "stop"), 10.0, "'angle_maps.theta0': stop 10.0 is below start"),
    (("angle_maps", "delta0", "step"), 0.0, "'angle_maps.delta0.step': 0.0 is less than or"),
    (("angle_maps", "L1"), [], "'angle_maps.L1': [] is too short"),
    (("angle_maps", "L1"), [-0.3, 0.4], "'angle_maps.L1.0': -0.3 is less than or equal"),
    (
        ("mass_length", "theta0_range"),
        [120.0, 60.0],
        "'mass_length.theta0_range': [120.0, 60.0] is empty",
    ),
    (("mass_length", "coarse_step"), -2.0, "'mass_length.coarse_step'"),
    (("torque_delay", "fig7", "tau"), _DELETE, "'torque_delay.fig7.tau' is missing"),
    (("elbow_force", "F0"), -20.0, "'elbow_force.F0': -20.0 is less than the minimum"),
    (("fig4", "samples"), 1, "'fig4.samples': 1 is less than the minimum of 2"),
    (("figure_curves",), "sketch", "'figure_curves': 'sketch' is not one of"),
    (("unknown_section",), 1, "(unknown key)"),
    (("solver_study", "stability", "cases"), [], "'solver_study.stability.cases': []"),
    # the accuracy bound of SolverSettings, the same as the CLI's and the Python API's
    (("solver", "rtol"), 10.0, "'solver.rtol': solver setting 'rtol' must be <= 0.0001"),
    (("solver", "rtol"), 1e-300, "'solver.rtol': solver setting 'rtol' must be >= 2.22e-14"),
    (("solver", "atol"), 1e-3, "'solver.atol': solver setting 'atol' must be <= 0.0001"),
    (
        ("solver_study", "compiled_tolerances"),
        [1e-4, 1e-2],
        "'solver_study.compiled_tolerances.1': solver setting 'rtol' must be <= 0.0001",
    ),
    # method names: a case named fixed.RK5 is not run as RK4 under that label
    (
        ("solver_study", "stability", "cases"),
        [["tennis_stroke.DOP853", 1e-3], ["fixed.RK5", 1e-3]],
        "'solver_study.stability.cases.1': unknown method 'fixed.RK5' (known: ",
    ),
    (
        ("solver_study", "stability", "cases"),
        [["DOP853", 1e-3]],
        "'solver_study.stability.cases.0': unknown method 'DOP853'",
    ),
    (
        ("solver_study", "stability", "cases"),
        [["fixed.RK4", 0.0]],
        "'solver_study.stability.cases.0.1': 0.0 is less than or equal to the minimum",
    ),
    # a work-precision scene: each value checked by the model's own bounds
    (
        ("solver_study", "scenes", "stiff", "k_contact"),
        -1.0,
        "'solver_study.scenes.stiff': ",
    ),
    (
        ("solver_study", "scenes", "elbow", "psi_F_deg"),
        [360.0, 0.0],
        "'solver_study.scenes.elbow.psi_F_deg': range [360.0, 0.0] has its low end above",
    ),
    (
        ("solver_study", "scipy_methods"),
        ["RK45", "RK5"],
        "'solver_study.scipy_methods.1': 'RK5' is not one of",
    ),
    # the model ladder: checked by the code that will run its rungs
    (("model_ladder", "reference"), "paper", "model_ladder.reference 'paper' is not a rung"),
    (
        ("model_ladder", "rungs", 1, "name"),
        "swing_omega2",
        "rung name 'swing_omega2' is used twice",
    ),
    (
        ("model_ladder", "rungs", 0, "contact_model"),
        "hertz",
        "'model_ladder.rungs.0.contact_model': 'hertz' is not one of",
    ),
    (
        ("model_ladder", "rungs", 4, "restitution"),
        1.5,
        "'model_ladder.rungs.4.restitution': 1.5 is greater than the maximum of 1",
    ),
    (
        ("model_ladder", "rungs", 5, "solver", "rtol"),
        0.01,
        "'model_ladder.rungs.5.solver.rtol': solver setting 'rtol' must be <= 0.0001",
    ),
    (("model_ladder", "rungs", 0, "colour"), "red", "'colour' was unexpected"),
    (("model_ladder",), _DELETE, "config key 'model_ladder' is missing (required)"),
    # a job's points against the declared bound (the job failed with MemoryError 179 GiB)
    (
        ("angle_maps", "theta0", "step"),
        1e-6,
        "'angle_maps': a Figs. 2-3 map job (60000001 x 401 strokes) holds 24060000401 points, "
        "above max_points_per_job = 10000000",
    ),
    (("max_points_per_job",), 1000, "'angle_maps': a Figs. 2-3 map job (241 x 401 strokes) holds"),
    (("max_points_per_job",), "lots", "'max_points_per_job': 'lots' is not of type 'integer'"),
    (("max_points_per_job",), 1.5, "'max_points_per_job': 1.5 is not of type 'integer', 'null'"),
    (("max_points_per_job",), 0, "'max_points_per_job': 0 is less than the minimum of 1"),
    (
        ("mass_length", "coarse_step"),
        1e-4,
        "'mass_length': a Figs. 5-6 map job (13 x 7.80e+12 strokes)",
    ),
    (
        ("solver_study", "stability", "k_contact", "num"),
        1_000_000,
        "'solver_study.stability.k_contact': the stability map (11 cases x 1000000 spring "
        "constants) holds 11000000 points",
    ),
    # an RK4 step that would compute for days (issue 56): the smallest step declared
    (
        ("solver_study", "rk4_steps"),
        [1.0e-12],
        "'solver_study.rk4_steps.0': RK4 step of case 'fixed.RK4' must be at least 1e-05 s",
    ),
    (
        ("solver_study", "stability", "cases", 10, 1),
        1.0e-6,
        "'solver_study.stability.cases.10': RK4 step of case 'fixed.RK4' must be at least",
    ),
]


def test_the_shipped_config_is_good():
    assert config_errors(GOOD, SCHEMA) == []


@pytest.mark.parametrize(
    "path, value, fragment", BAD, ids=[".".join(map(str, b[0])) + f"={b[1]!r}"[:20] for b in BAD]
)
def test_bad_config_gives_one_line_naming_the_key(path, value, fragment):
    config = copy.deepcopy(GOOD)
    _set(config, path, value)
    errors = config_errors(config, SCHEMA)
    assert errors, "not detected"
    assert "\n" not in errors[0]
    assert fragment in errors[0], errors[0]


@pytest.mark.parametrize(
    "path, value, fragment",
    [
        # `whatif --set torque_delay.theta0=450` gave 69.9 km/h, a turn late (issue 66)
        (
            ("torque_delay", "theta0"),
            450.0,
            "config key 'torque_delay.theta0': initial angle 'theta0' must be <= 360 degree, "
            "got 450 (rule: initial angles)",
        ),
        (  # each angle within a turn, but Fig. 8's delta0 up to 100 deg: 400 deg in all
            ("torque_delay", "theta0"),
            300.0,
            "config keys 'torque_delay.theta0' and 'torque_delay.fig8.delta0': initial angles "
            "theta0 + delta0 must be < 360 degree",
        ),
        (
            ("fig4", "strokes"),
            [[120.0, 81.5], [75.0, 801.5]],
            "config key 'fig4.strokes': initial angle 'delta0' must be <= 360 degree",
        ),
        (
            ("mass_length", "delta0_range"),
            [0.0, 300.0],
            "config keys 'mass_length.theta0_range' and 'mass_length.delta0_range': initial",
        ),
        (
            ("angle_maps", "theta0"),
            {"start": -400.0, "stop": 120.0, "step": 0.25},
            "config key 'angle_maps.theta0': initial angle 'theta0' must be >= -360 degree",
        ),
        (("solver_study", "convergence", "delta0"), 500.0, "'solver_study.convergence.delta0'"),
    ],
)
def test_an_initial_angle_beyond_a_turn_is_refused_naming_its_keys(path, value, fragment):
    """Every initial angle a row of the table reads, by the one rule of the angles."""
    config = copy.deepcopy(GOOD)
    _set(config, path, value)
    errors = config_errors(config, SCHEMA)
    assert errors and fragment in errors[0], errors


@pytest.mark.workflow
def test_a_bad_config_stops_snakemake_before_any_job_in_one_line(tmp_path):
    """The wiring, once (every bad case is checked in-process above, each by the same
    check the Snakefile runs): a refused config reaches the user through Snakemake as its
    one line, exit status 1, no traceback, no job and nothing written."""
    config = copy.deepcopy(GOOD)
    config["solver"]["rtol"] = -1.0
    done = run_snakemake("report", workdir(tmp_path, config), "-n")
    assert done.returncode == 1
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert lines == [
        "tennis-stroke config error: config key 'solver.rtol': -1.0 is less "
        "than or equal to the minimum of 0 (rule: exclusiveMinimum)"
    ]
    assert "Traceback" not in done.stderr and "Job stats" not in done.stdout
    assert not (tmp_path / "results").exists()


def test_the_bound_is_per_job_and_a_gathering_holds_its_whole_map():
    """Chunks bring a map's jobs under the bound; gathering them holds every stroke of the
    map at once, and the plan names that job then."""
    config = copy.deepcopy(GOOD)
    config["max_points_per_job"] = 100_000
    config["angle_maps"]["theta0"]["step"] = 0.125  # 481 x 401 strokes
    assert (
        "'angle_maps': a Figs. 2-3 map job (481 x 401 strokes) holds 192881 points"
        in (config_errors(config, SCHEMA)[0])
    )
    config["chunks"] = {"angle_map": 2}
    (error,) = config_errors(config, SCHEMA)
    assert "'angle_maps': gathering the Figs. 2-3 map (192881 strokes) holds" in error
    config["max_points_per_job"] = 200_000
    assert config_errors(config, SCHEMA) == []


def test_readings_searched_in_lockstep_multiply_a_search_s_points():
    """The robustness job searches its readings together: a bracket that fits one reading
    can exceed the bound for all of them, and the plan says so before any job."""
    config = copy.deepcopy(GOOD)
    config["max_points_per_job"] = 30_000_000
    config["search"]["angle_step"] = 1e-3  # 241 x 100001 strokes
    assert list(points_errors(config, 1)) == []
    (error,) = points_errors(config, 32)
    assert error.startswith("config key 'search.angle_step': the search of the Figs. 2-3 ")
    assert "24100241 strokes at once for each of 32 readings) holds 771207712 points" in error


def test_planning_counts_the_readings_searched_in_lockstep(monkeypatch):
    """The Snakefile's check (checked_config) bounds the points once, for the readings of
    the largest robustness job (config/readings.yaml: its readings over its chunks)."""
    multiverse = load_yaml(ROOT / "config" / "readings.yaml")["multiverse"]
    largest = rows_per_job(multiverse["readings"], multiverse["chunks"])
    assert largest > 1
    config = copy.deepcopy(GOOD)
    config["max_points_per_job"] = 30_000_000
    config["search"]["angle_step"] = 1e-3
    monkeypatch.chdir(ROOT)
    with pytest.raises(PlanningError) as info:
        checked_config(config, SCHEMA)
    line = info.value.line()
    assert line.startswith("tennis-stroke config error: config key 'search.angle_step'")
    assert f"24100241 strokes at once for each of {largest} readings) holds" in line


def test_the_shipped_config_leaves_the_bound_to_the_package():
    schema = yaml.safe_load(SCHEMA.read_text())
    spec = schema["properties"]["max_points_per_job"]
    assert spec["default"] is None and "DEFAULT_MAX_POINTS" in spec["description"]
    assert GOOD["max_points_per_job"] is None
    bad = copy.deepcopy(GOOD)
    bad["angle_maps"]["theta0"]["step"] = 0.002  # 30001 x 401 strokes
    assert 30001 * 401 > DEFAULT_MAX_POINTS
    assert f"above max_points_per_job = {DEFAULT_MAX_POINTS}" in config_errors(bad, SCHEMA)[0]


@pytest.mark.parametrize(
    "text, where, problem",
    [
        ("solver:\n  rtol: [1e-8\nmodel: {}\n", "line 3, column 6", "expected ',' or ']'"),
        ("solver:\n\trtol: 1e-8\n", "line 2, column 1", "found character '\\t'"),
        ("a: 1\na: {b: 2\n", "line 3, column 1", "expected ',' or '}'"),
        ("key: 'unclosed\n", "line 2, column 1", "found unexpected end of stream"),
    ],
)
def test_yaml_syntax_errors_name_the_file_and_the_line(text, where, problem, tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigFileError) as err:
        load_yaml(path)
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith(f"{path}, {where}: YAML syntax error: "), message
    assert problem in message


def test_load_yaml_reads_a_good_file_and_refuses_a_missing_one(tmp_path):
    assert load_yaml(ROOT / "config" / "config.yaml") == GOOD
    with pytest.raises(ConfigFileError, match="cannot read .*none.yaml"):
        load_yaml(tmp_path / "none.yaml")


def test_numbers_given_as_strings_are_numbers_again():
    given = {"chunks": {"angle_map": "3"}, "solver": {"rtol": "1e-9", "method": "DP54"}}
    given["angle_maps"] = {"L1": ["0.3", "x"]}
    assert numbers_from_strings(given) == {
        "chunks": {"angle_map": 3},
        "solver": {"rtol": 1e-9, "method": "DP54"},
        "angle_maps": {"L1": [0.3, "x"]},
    }


@pytest.mark.workflow
def test_nested_command_line_overrides_work_and_split_each_map_as_asked(tmp_path):
    """Snakemake reads nested values as strings; the workflow takes them as numbers, and
    each map is planned in the chunks asked of it, at most one per row (that gathered
    chunks equal the unchunked map, bit for bit, is tests/workflow/test_chunking.py's)."""
    chunks = "chunks={angle_map: 3, mass_length: 2, delay_map: 2, elbow_force_map: 4}"
    done = run_snakemake("report", workdir(tmp_path, GOOD), "-n", "--config", chunks)
    assert done.returncode == 0, (done.stdout + done.stderr)[-2000:]
    counts = planned_kinds(done.stdout + done.stderr)
    # fig9 has a single delta0 row: one chunk, whatever was asked
    expected = {"fig2": 3, "fig3": 3, "fig7": 2, "fig8": 2, "fig9": 1}
    expected.update(mass_length=2, elbow_force_map=4)
    assert {k: counts[k] for k in expected} == expected
    # 7 maps, the robustness analysis' claims x readings file and the work-precision
    # study's scenes are gathered
    assert counts["gather_map"] == 9


def test_every_reading_of_the_model_runs_the_ladder():
    """The ladder's rungs are defined under every reading of the collision force (the
    impact with Eq. 8 as printed is the stiff limit of that contact), and a model option
    in the model section is a run of the whole replication under that rung."""
    for model in ({"collision_coupling": "paper_eq8"}, {"contact_model": "impact"}):
        config = copy.deepcopy(GOOD)
        config["model"] = model
        assert config_errors(config, SCHEMA) == []


def _checked(config):
    from snakemake.utils import validate

    config = copy.deepcopy(config)
    validate(config, str(SCHEMA), set_default=True)
    return canonical(config, load_schema(SCHEMA))


def test_the_shipped_config_is_already_canonical():
    """The schema lists the keys in config/config.yaml's order, so canonical() changes no
    job's params for the paper's configuration (no rerun after this change)."""
    shipped = load_yaml(ROOT / "config" / "config.yaml")
    from snakemake.utils import validate

    validate(shipped, str(SCHEMA), set_default=True)
    assert repr(canonical(shipped, load_schema(SCHEMA))) == repr(shipped)


@pytest.mark.parametrize(
    "edit",
    [
        lambda c: c["torque_delay"]["base_stroke"].update(C2=5),
        lambda c: c["solver"].update(rtol=c["solver"].pop("rtol")),  # rtol after atol
        lambda c: c.update(solver=c.pop("solver")),  # the section last
        lambda c: c["angle_maps"]["theta0"].update(start=60),
        lambda c: c["fig4"].update(strokes=[[120, 81.5], [75, 39]]),
    ],
)
def test_equal_values_spelled_differently_are_one_config(edit):
    """C2: 5 and C2: 5.0, or two keys in another order, gave other job params (33 jobs
    planned for the same values)."""
    shipped = load_yaml(ROOT / "config" / "config.yaml")
    edited = copy.deepcopy(shipped)
    edit(edited)
    assert repr(_checked(edited)) == repr(_checked(shipped))


def test_canonical_keeps_integers_booleans_and_sorts_free_keys():
    shipped = load_yaml(ROOT / "config" / "config.yaml")
    config = copy.deepcopy(shipped)
    # a parameter (C1 = 25 N m, an int) or option (the spring) at its default is left out
    config["model"] = {"M2": 1, "L1": 0.35, "inertia": "rod", "C1": 25, "contact_model": "spring"}
    out = _checked(config)
    assert list(out["model"]) == ["L1", "M2", "inertia"] and out["model"]["M2"] == 1.0
    assert isinstance(out["model"]["M2"], float)
    assert isinstance(out["chunks"]["angle_map"], int)  # an integer key stays one
    assert out["solver_study"]["stability"]["cases"][0][1] == float(
        shipped["solver_study"]["stability"]["cases"][0][1]
    )


def test_config_readme_is_the_key_table_of_config_yaml():
    """config/README.md is `tennis-stroke config keys`: every leaf key of config.yaml has
    its row, with the value the file gives."""
    text = (ROOT / "config" / "README.md").read_text()
    assert text == key_table(load_schema(SCHEMA), load_yaml(ROOT / "config" / "config.yaml")) + "\n"
    assert "| `torque_delay.base_stroke.C2` | number | `5.0` | Wrist torque (N m). |" in text
    assert "| `chunks.angle_map` | integer, >= 1 | `1` |" in text


#: The JSON Schema keywords the config schema may use (a key of a schema entry not among
#: them is a typo or a YAML slip that jsonschema ignores without a word).
KEYWORDS = {
    "$schema", "$defs", "$ref", "description", "type", "additionalProperties", "required",
    "properties", "items", "prefixItems", "minItems", "maxItems", "uniqueItems", "minimum",
    "maximum", "exclusiveMinimum", "exclusiveMaximum", "enum", "default", "allOf", "anyOf",
    "oneOf", "const", "minLength", "pattern", "propertyNames", "minProperties", "not",
}  # fmt: skip


def test_every_schema_entry_uses_json_schema_keywords_only():
    """A flow-style `description: (theta0, delta0) pairs` split at its comma into a
    description '(theta0' and a key 'delta0) pairs (degree).' (three entries)."""

    def entries(node):
        if isinstance(node, dict):
            yield node
            for key, child in node.items():
                if key in ("properties", "$defs"):
                    for grand in child.values():
                        yield from entries(grand)
                elif key not in ("default", "enum", "const", "required"):
                    yield from entries(child)
        elif isinstance(node, list):
            for child in node:
                yield from entries(child)

    odd = {key for entry in entries(load_yaml(SCHEMA)) for key in entry} - KEYWORDS
    assert not odd
