"""What-if scenarios (tennis_stroke.pipeline.scenarios), the paper's configuration and
its gate (tennis_stroke.inference.paper_config), and what each config key drives
(tennis_stroke.pipeline.explain): the parts that need no workflow run."""

import pytest
from conftest import ROOT, record_configuration
from tiny import TINY

from tennis_stroke.cli import main
from tennis_stroke.experiments.specs import PAPER_RESULTS
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.paper_config import (
    PaperConfigError,
    configuration_record,
    departures,
    load_paper_inputs,
    read_record,
    write_record,
)
from tennis_stroke.inference.reading_space import load_reading_space
from tennis_stroke.io.config_files import load_yaml
from tennis_stroke.pipeline.explain import explain, leaves, markdown, rows_reading
from tennis_stroke.pipeline.params import changed_results
from tennis_stroke.pipeline.scenarios import (
    ScenarioError,
    changes,
    describe,
    load_scenarios,
    merged,
    override_from,
    resolved_results,
    scenario_config,
)
from tennis_stroke.replication.registry import paper_figure

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
PAPER = load_yaml(ROOT / "config" / "config.yaml")
INPUTS = load_paper_inputs(ROOT / "config" / "claims.yaml")
CLAIMS = load_claims(ROOT / "config" / "claims.yaml")
STATED = [i["key"] for i in load_paper_inputs(ROOT / "config" / "claims.yaml")]
BASE_STROKE = {"torque_delay": {"base_stroke": {"C2": 8.0}}}
#: The tiny configuration with the defaults the workflow's schema fills in.
BASE = merged(PAPER, TINY)


def test_overrides_merge_key_by_key_and_replace_lists_whole():
    out = merged(PAPER, {"torque_delay": {"base_stroke": {"C2": 8.0}}, "angle_maps": {"L1": [0.5]}})
    assert out["torque_delay"]["base_stroke"] == {"C2": 8.0, "delta0": 52.5}
    assert out["torque_delay"]["L1"] == 0.4 and out["angle_maps"]["L1"] == [0.5]
    assert PAPER["torque_delay"]["base_stroke"]["C2"] == 5.0  # the base is not touched
    assert changes(PAPER, out) == [
        ("angle_maps.L1", [0.3, 0.4], [0.5]),
        ("torque_delay.base_stroke.C2", 5.0, 8.0),
    ]


def test_a_change_of_the_base_stroke_moves_the_files_of_secs_5_6_only():
    config = scenario_config(BASE, "s", BASE_STROKE, SCHEMA)
    # the Sec. V stroke's C2 is Fig. 8's too (one value of the paper, one key)
    assert changed_results(BASE, config) == ["fig8", "fig9", "delay", "elbow_map", "elbow"]
    files = resolved_results(BASE, config, "s")
    assert files["fig9"] == "results/scenarios/s/torque_delay/fig9.nc"
    assert files["fig2"] == PAPER_RESULTS["fig2"] == "results/angle_maps/fig2.nc"
    # a model parameter is read by every model row
    heavy = scenario_config(BASE, "h", {"model": {"M2": 0.35}}, SCHEMA)
    # every model row but Figs. 5-6's, which set M2 themselves at every point
    assert changed_results(BASE, heavy) == [k for k in PAPER_RESULTS if k != "ml"]
    long_arm = scenario_config(BASE, "l", {"model": {"L1": 0.5}}, SCHEMA)
    assert not {"fig2", "fig3", "ml"} & set(changed_results(BASE, long_arm))
    assert changed_results(BASE, BASE) == []


@pytest.mark.parametrize(
    ("name", "overrides", "message"),
    [
        ("1st", {}, "scenario name '1st': a letter"),
        ("a/b", {}, "scenario name 'a/b'"),
        # Snakemake's PeriodicWildcardError, once a 6-line traceback of rule scenario_article
        ("a" + "x" * 20, {}, "ends in 'x' repeated 20 times"),
        ("q" + "ab" * 21, {}, "ends in 'ab' repeated 21 times"),
        ("s", [1], "scenario 's': overrides must be a mapping"),
        ("s", {"solver_study": {"seed": 2}}, "may not override 'solver_study'"),
        ("s", {"model_ladder": {}}, "may not override 'model_ladder'"),
        (
            "s",
            {"model": {"M2": -1.0}},
            "scenario 's': config key 'model': parameter 'M2' must be > 0",
        ),
        ("s", {"torque_delay": {"base": 1}}, "scenario 's': config key 'torque_delay'"),
        ("s", {"solver": {"method": "Euler"}}, "scenario 's': config key 'solver.method'"),
        # every size key against the bound on a job's points (the job tried to allocate 14.9 GiB)
        (
            "s",
            {"fig4": {"samples": 2_000_000_000}, "max_points_per_job": 5_000_000},
            "scenario 's': config key 'fig4.samples': the curves of the Fig. 4 strokes",
        ),
        (
            "s",
            {"search": {"tau_step": 1e-9}, "max_points_per_job": 5_000_000},
            "scenario 's': config key 'search': the search of the Fig. 7 map's claims",
        ),
    ],
)
def test_a_bad_scenario_is_one_line_naming_it(name, overrides, message):
    with pytest.raises(ScenarioError) as info:
        scenario_config(BASE, name, overrides, SCHEMA)
    assert message in str(info.value) and "\n" not in str(info.value)


def test_a_name_with_19_repeats_at_its_end_is_a_scenario():
    """The refusal of a periodic name starts where Snakemake's does (20 repeats)."""
    config = scenario_config(BASE, "a" + "x" * 19, {"model": {"M2": 0.35}}, SCHEMA)
    assert config["model"]["M2"] == 0.35


def test_scenarios_come_from_the_file_and_the_command_line(tmp_path):
    path = tmp_path / "scenarios.yaml"
    assert load_scenarios(path) == {}  # no file: none
    path.write_text("")
    assert load_scenarios(path) == {}  # an empty file: none
    path.write_text("a: {model: {M2: 0.35}}\nb:\n")
    assert load_scenarios(path, {"a": {"model": {"M2": 0.4}}}) == {
        "a": {"model": {"M2": 0.4}},
        "b": {},
    }
    path.write_text("- a\n")
    with pytest.raises(ScenarioError, match="must map each scenario's name"):
        load_scenarios(path)
    path.write_text("a: {model: {M2: 0.35}}\na: {}\n")
    with pytest.raises(ScenarioError, match="duplicate key 'a'"):
        load_scenarios(path)


def test_one_bad_scenario_stops_only_itself(tmp_path):
    """A bad name or shape of one scenario is recorded for it by name, the others load;
    without a place for errors it raises, as before."""
    path = tmp_path / "scenarios.yaml"
    path.write_text("ok_one: {model: {M2: 0.35}}\n'a b': {model: {M2: 0.4}}\nc: [1]\n")
    errors: dict = {}
    assert load_scenarios(path, None, errors) == {"ok_one": {"model": {"M2": 0.35}}}
    assert sorted(errors) == ["a b", "c"]
    assert errors["a b"].startswith("scenario name 'a b': a letter")
    assert errors["c"].startswith("scenario 'c': overrides must be a mapping")
    with pytest.raises(ScenarioError, match="scenario name 'a b'"):
        load_scenarios(path)


def test_the_declared_scenarios_are_valid():
    for name, overrides in load_scenarios(ROOT / "config" / "scenarios.yaml").items():
        scenario_config(PAPER, name, overrides, SCHEMA)


def test_command_line_overrides_name_a_parameter_or_a_dotted_key():
    assert override_from(["M2=0.35", "inertia=paper_text"]) == {
        "model": {"M2": 0.35, "inertia": "paper_text"}
    }
    # a model option is set as a reading is (it went to the top level and was refused)
    assert override_from(["contact_model=impact"]) == {"model": {"contact_model": "impact"}}
    assert override_from(["torque_delay.base_stroke.C2=8", "angle_maps.L1=[0.3, 0.5]"]) == {
        "torque_delay": {"base_stroke": {"C2": 8}},
        "angle_maps": {"L1": [0.3, 0.5]},
    }
    for bad in ("M2", "=1", "M2=", "a=1 a.b=2"):
        with pytest.raises(ScenarioError):
            override_from(bad.split(" "))


def test_an_override_is_described_with_the_papers_value_and_unit():
    assert describe("model.M2", None, 0.35, (), STATED) == "model.M2 = 0.35 kg (paper: 0.3 kg)"
    # one vocabulary: a default is the paper's, fitted, derived or ours (model.listing)
    assert describe("model.inertia", None, "paper_text", (), STATED) == (
        "model.inertia = paper_text (ours: uniform_rod)"
    )
    assert describe("model.contact_model", None, "impact", (), STATED) == (
        "model.contact_model = impact (paper: spring)"
    )
    assert describe("model.k_contact", None, 2e4, {"k_contact"}, STATED) == (
        "model.k_contact = 20000 N/m (fitted: 7800 N/m)"
    )
    fitted = load_reading_space(ROOT / "config" / "readings.yaml").fitted()
    assert describe("model.k_contact", None, 2e4, fitted, STATED).endswith("(fitted: 7800 N/m)")
    assert describe("torque_delay.base_stroke.C2", 5.0, 8.0, (), STATED) == (
        "torque_delay.base_stroke.C2 = 8 N m (paper: 5 N m)"
    )
    # a value a row puts into the model has its parameter's unit (torque_delay.L1 had none)
    assert describe("torque_delay.L1", 0.4, 0.5, (), STATED) == (
        "torque_delay.L1 = 0.5 m (paper: 0.4 m)"
    )
    # a model value set back to its default (canonical leaves it out: new is None)
    assert describe("model.M2", 0.35, None, (), STATED) == "model.M2 = 0.3 kg (config: 0.35 kg)"
    # a key the paper does not state is config.yaml's (it said "paper: 0.25" of our grid)
    assert describe("angle_maps.theta0.step", 0.25, 1.0, (), STATED) == (
        "angle_maps.theta0.step = 1 (config: 0.25)"
    )
    assert describe("angle_maps.L1.0", 0.3, 0.35, (), STATED).endswith("(paper: 0.3 m)")


def test_the_paper_configuration_is_the_declared_inputs():
    assert departures(PAPER, INPUTS) == [] and departures(TINY, INPUTS) == []
    for item in INPUTS:  # every declared key exists in the config
        node = PAPER
        for part in item["key"].split("."):
            node = node[part]
    moved = merged(PAPER, {**BASE_STROKE, "model": {"M2": 0.35, "inertia": "uniform_rod"}})
    assert [(d["key"], d["value"], d["paper_value"]) for d in departures(moved, INPUTS)] == [
        ("torque_delay.base_stroke.C2", 8.0, 5.0),
        ("model.M2", 0.35, 0.3),  # a reading at its default is not a departure
    ]
    # grids, chunks, searches and the solver are ours: never a departure
    ours = merged(PAPER, {"solver": {"rtol": 1e-9}, "fig9": {}, "chunks": {"angle_map": 4}})
    assert departures(ours, INPUTS) == []


def test_the_gate_grades_the_paper_configuration_only(tmp_path, capsys):
    table = tmp_path / "claims.csv"
    table.write_text("id\n")
    write_record(
        configuration_record(merged(PAPER, BASE_STROKE), INPUTS), tmp_path / "configuration.yaml"
    )
    with pytest.raises(SystemExit) as info:
        main(["claims", str(table)])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"tennis-stroke: error: {table} was computed under a configuration")
    assert "torque_delay.base_stroke.C2 = 8 (the paper's 5" in err and "\n" not in err
    (tmp_path / "configuration.yaml").unlink()
    with pytest.raises(SystemExit):
        main(["claims", str(table)])
    assert "configuration.yaml is missing" in capsys.readouterr().err
    for text, message in [
        ("[1]\n", "not a configuration record"),
        ("scenario: null\ndepartures: 3\n", "departures must be a list"),
        ("scenario: {name: x}\ndepartures: []\n", "scenario must be null or have"),
    ]:
        (tmp_path / "configuration.yaml").write_text(text)
        with pytest.raises(PaperConfigError, match=message):
            read_record(table)


def test_a_scenario_table_is_checked_and_not_graded(tmp_path, capsys):
    from tennis_stroke.replication.claims import COLUMNS

    header = ",".join(COLUMNS)
    ids = [c["id"] for c in CLAIMS]
    lines = [header] + [
        ",".join(
            {"id": i, "status": "fail", "reproduced_value": "1.0"}.get(col, "") for col in COLUMNS
        )
        for i in ids
    ]
    table = tmp_path / "claims.csv"
    table.write_text("\n".join(lines) + "\n")
    change = {"key": "model.M2", "paper": None, "scenario": 0.35, "text": "model.M2 = 0.35 kg"}
    record_configuration(tmp_path, scenario={"name": "h", "overrides": {}, "changes": [change]})
    assert main(["claims", str(table)]) == 0
    out = capsys.readouterr().out
    assert "scenario 'h', an exploration beside the paper: not graded" in out
    assert "model.M2 = 0.35 kg" in out


@pytest.mark.process
def test_the_readme_is_never_written_from_a_scenario_or_a_departure(tmp_path):
    import subprocess
    import sys

    table = tmp_path / "claims.csv"
    table.write_text("id,status,robustness\n")
    readme = tmp_path / "README.md"
    readme.write_text("<!-- results:begin -->\n<!-- results:end -->\n")
    record_configuration(tmp_path, scenario={"name": "h", "overrides": {}, "changes": []})
    tool = [sys.executable, str(ROOT / "tools" / "readme_results.py")]
    done = subprocess.run(
        [*tool, "--claims", table, "--readme", readme], capture_output=True, text=True
    )
    assert done.returncode == 2 and "scenario 'h'" in done.stderr
    record_configuration(
        tmp_path, departures=[{"key": "model.M2", "value": 0.35, "paper_value": 0.3, "source": "s"}]
    )
    done = subprocess.run(
        [*tool, "--claims", table, "--readme", readme, "--check"], capture_output=True, text=True
    )
    assert done.returncode == 2 and "departs from the paper's (model.M2 = 0.35" in done.stderr
    assert readme.read_text() == "<!-- results:begin -->\n<!-- results:end -->\n"


def test_each_key_names_what_it_drives():
    e = explain("torque_delay.base_stroke.C2", PAPER, CLAIMS)
    assert e.rows == ("fig8", "fig9", "delay", "elbow_map", "elbow")
    assert e.figures == (
        "fig08_delay_delta0",
        "fig09_v_tau",
        "fig10_omegas_delay",
        "fig11_strobe_tau_H",
        "fig12_strobe_tau_L",
        "fig13_elbow_force",
        "fig14_elbow_paths",
    )
    assert "fig9_v_H" in e.claims and "fig2_best_delta0_at_120" not in e.claims
    assert "identification" in e.inference and "claims" in e.inference
    # the Fig. 9 section now holds only its delays
    assert rows_reading("torque_delay.fig9.tau") == ["fig9"]
    assert "moves no number" in explain("chunks.angle_map", PAPER, CLAIMS).note
    # a model parameter by its name or its key, as whatif --set takes it
    assert explain("M2", PAPER, CLAIMS) == explain("model.M2", PAPER, CLAIMS)
    assert explain("M2", PAPER, CLAIMS).rows == tuple(k for k in PAPER_RESULTS if k != "ml")
    assert explain("chunks.angle_map", PAPER, CLAIMS).files == ()
    with pytest.raises(KeyError, match="did you mean torque_delay.base_stroke.C2"):
        explain("torque_delay.base_stroke.c2", PAPER, CLAIMS)


#: A valid value of every model parameter and reading other than its default.
def _other(name):
    from tennis_stroke.model.params import PARAMETERS, READINGS

    if name in READINGS:
        return next(c for c in READINGS[name].choices if c != READINGS[name].default)
    spec = PARAMETERS[name]
    value = spec.default * 1.1 if spec.default else 0.01
    value = min(value, spec.upper) if spec.upper is not None else value
    return value if value != spec.default else spec.default * 0.9  # at its upper bound


def test_explain_agrees_with_what_a_scenario_reruns_for_every_model_key():
    """`config explain model.P` names exactly the paper's files a scenario overriding P
    recomputes (and a figure's title names P only if so): for every model parameter and
    reading.  Fig. 9 sets C2 itself: model.C2 reran it and labelled it."""
    from tennis_stroke.model.params import PARAMETERS, READINGS
    from tennis_stroke.pipeline.scenarios import changes_read

    for name in (*PARAMETERS, *READINGS):
        config = scenario_config(BASE, "s", {"model": {name: _other(name)}}, SCHEMA)
        planned = changed_results(BASE, config)
        explained = [k for k in rows_reading(f"model.{name}") if k in PAPER_RESULTS]
        assert planned == explained, name
        for key in PAPER_RESULTS:
            assert bool(changes_read([key], BASE, config)) == (key in planned), (name, key)
    c2 = scenario_config(BASE, "s", {"model": {"C2": 3.0}}, SCHEMA)
    assert "fig9" not in changed_results(BASE, c2) and "fig2" in changed_results(BASE, c2)
    assert "Fig. 9 map (reads torque_delay.base_stroke.C2)" in explain("C2", PAPER, CLAIMS).instead


def _changed(value):
    """Another valid-looking value of a config leaf: a number moved by 10 % (0 -> 0.01),
    an int by one, a bool flipped, a list of numbers each moved, a range's stop moved;
    None for what this cannot move (a name, a list of mappings)."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return value + 1
    if isinstance(value, float):
        return value * 1.1 if value else 0.01
    numbers = isinstance(value, list) and value
    if numbers and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        return [_changed(v) for v in value]
    if isinstance(value, dict) and isinstance(value.get("stop"), (int, float)):
        return {**value, "stop": _changed(value["stop"])}
    return None


#: Leaves of config.yaml that :func:`_changed` cannot move: names and structured lists.
UNMOVED = {
    "solver.method",
    "max_points_per_job",
    "model",
    "figure_curves",
    "fig4.strokes",
    "model_ladder.rungs",
    "model_ladder.reference",
    "solver_study.stability.cases",
    "solver_study.optimum.steps",
    "solver_study.optimum.searches",
}


def test_explain_agrees_with_what_a_scenario_reruns_for_every_config_key():
    """For every leaf of config.yaml a scenario may override, the paper files `config
    explain` names are exactly those a scenario changing it recomputes (a chunk count
    or the failure limit moves no number: no file).  Every leaf is checked, refused to
    scenarios (PAPER_ONLY sections) or named in UNMOVED."""
    from tennis_stroke.pipeline.explain import effect
    from tennis_stroke.pipeline.scenarios import PAPER_ONLY

    checked = []
    for key in leaves(PAPER):
        node = PAPER
        for part in key.split("."):
            node = node[part]
        value = _changed(node)
        if key.split(".")[0] in PAPER_ONLY or value is None:
            assert key.split(".")[0] in PAPER_ONLY or key in UNMOVED, key
            continue
        for part in reversed(key.split(".")):
            value = {part: value}
        config = scenario_config(BASE, "s", value, SCHEMA)
        files = effect(key, CLAIMS).files
        explained = [k for k, path in PAPER_RESULTS.items() if path in files]
        assert changed_results(BASE, config) == explained, key
        checked.append(key)
    assert {"fig4.samples", "search.tau_step", "chunks.angle_map", "elbow_force.F0"} <= set(checked)


def test_a_mistyped_key_gets_the_nearest_full_keys():
    with pytest.raises(KeyError, match=r"did you mean model\.ball_mass"):
        explain("model.ballmass", PAPER, CLAIMS)


def test_every_key_of_the_config_at_any_depth_is_explained():
    """Issue 53: `config explain torque_delay.fig9.tau.step` was refused though
    `torque_delay.fig9.tau` was explained.  Every key of config.yaml at any depth is
    explained, and a range's start, stop or step moves what the range moves."""
    from tennis_stroke.io.config_files import config_keys

    keys = list(config_keys(PAPER))
    assert {"torque_delay.fig9.tau.step", "angle_maps.theta0.start", "torque_delay"} <= set(keys)
    for key in keys:
        assert explain(key, PAPER, CLAIMS).key == key
    ranges = [k for k in keys if {f"{k}.start", f"{k}.stop"} <= set(keys)]
    assert "torque_delay.fig9.tau" in ranges
    for key in ranges:
        whole = explain(key, PAPER, CLAIMS)
        for part in ("start", "stop", "step"):
            if f"{key}.{part}" in keys:
                inner = explain(f"{key}.{part}", PAPER, CLAIMS)
                assert (inner.rows, inner.files, inner.figures, inner.claims) == (
                    whole.rows,
                    whole.files,
                    whole.figures,
                    whole.claims,
                ), f"{key}.{part}"
    with pytest.raises(KeyError, match=r"did you mean torque_delay\.fig9\.tau\.step"):
        explain("torque_delay.fig9.tau.stepp", PAPER, CLAIMS)


def test_a_model_option_is_explained_as_whatif_sets_it():
    """`whatif --set contact_model=impact` sets model.contact_model: explain knows it."""
    for key in ("contact_model", "model.contact_model"):
        assert explain(key, PAPER, CLAIMS).key == "model.contact_model"


def test_the_config_keys_page_is_current():
    """docs/config_keys.md holds `tennis-stroke config explain --all` of config.yaml."""
    text = (ROOT / "docs" / "config_keys.md").read_text()
    assert markdown(PAPER, CLAIMS) in text
    assert len(list(leaves(PAPER))) == text.count("\n| `")


def test_a_figure_is_found_by_its_number():
    assert paper_figure("fig9") == paper_figure("fig09") == "fig09_v_tau"
    assert paper_figure("fig02_angle_map") == "fig02_angle_map"
    for bad in ("fig99", "study01_work_precision", "nine"):
        with pytest.raises(KeyError, match="no figure"):
            paper_figure(bad)


def test_whatif_refuses_in_one_line(tmp_path, monkeypatch, capsys):
    """Outside the project's folder, an undeclared scenario without overrides, an unknown
    figure and a bad --set are each one line and exit status 2, before Snakemake runs."""
    cases = [(["whatif", "x", "--set", "M2=0.4"], "no workflow/Snakefile in")]
    cases_root = [
        (["whatif", "nosuch"], "scenario 'nosuch' is not declared in config/scenarios.yaml"),
        (["whatif", "x", "--set", "M2=0.4", "--figure", "fig99"], "no figure 'fig99'"),
        (["whatif", "x", "--set", "M2"], "--set 'M2': expected KEY=VALUE"),
        (["whatif", "1x", "--set", "M2=0.4"], "scenario name '1x'"),
        # a declared scenario's files are not replaced by --set
        (
            ["whatif", "strong_wrist", "--set", "M2=0.35", "-n"],
            "scenario 'strong_wrist' is declared in config/scenarios.yaml: --set would",
        ),
        # a bare name that is nothing gets the closest names (it went to the top level)
        (["whatif", "x", "--set", "M22=0.35", "-n"], "'M22' is no model parameter"),
        (["whatif", "x", "--set", "M22=0.35", "-n"], "(did you mean M2?)"),
        # an override that is the value already: nothing to compute (it ran 40 jobs)
        (["whatif", "x", "--set", "M2=0.3", "-n"], "changes nothing of the paper's"),
        # a message keeps its closing quote
        (["whatif", "x", "--set", "M2=abc", "-n"], "got 'abc'\n"),
        # a bad value: one line, not Snakemake's log and exit 1
        (
            ["whatif", "x", "--set", "M2=-1", "-n"],
            "scenario 'x': config key 'model': parameter 'M2' must be > 0 kg, got -1",
        ),
        # a figure that sets the parameter itself: nothing of it changes
        (
            ["whatif", "x", "--set", "C2=3.0", "--figure", "fig9"],
            "scenario 'x' does not change fig09_v_tau: model.C2 does not reach the Fig. 9 "
            "map (it reads torque_delay.base_stroke.C2)",
        ),
        (
            ["whatif", "x", "--set", "L1=0.5", "--figure", "fig2"],
            "model.L1 does not reach the Figs. 2-3 map (it reads angle_maps.L1.0)",
        ),
        # issue 66: an arm a turn too far gave 69.9 km/h (case 2), the last of two --set
        # won (case 12), -j -3 went to Snakemake (case 17)
        (
            ["whatif", "x", "--set", "torque_delay.theta0=450", "-n"],
            "scenario 'x': config key 'torque_delay.theta0': initial angle 'theta0' must be "
            "<= 360 degree, got 450",
        ),
        (
            ["whatif", "x", "--set", "M2=0.3", "--set", "model.M2=0.5", "-n"],
            "--set 'model.M2=0.5': 'M2' is set twice (also --set 'M2=0.3')",
        ),
        (["whatif", "x", "--set", "M2=0.4", "-j", "-3", "-n"], "-j/--cores must be >= 1, got -3"),
        (["whatif", "x", "--set", "M2=0.4", "-j", "0", "-n"], "-j/--cores must be >= 1, got 0"),
    ]
    for where, runs in ((tmp_path, cases), (ROOT, cases_root)):
        monkeypatch.chdir(where)
        for argv, message in runs:
            with pytest.raises(SystemExit) as info:
                main(argv)
            err = capsys.readouterr().err
            assert info.value.code == 2 and message in err and err.count("\n") == 1, err


@pytest.mark.parametrize("figure, key", [("fig9", "fig9"), ("fig04_omegas", "fig4")])
def test_whatif_prints_a_figure_s_claims_and_the_inputs_they_were_computed_at(
    figure, key, tmp_path, monkeypatch, capsys
):
    """Issue 66, case 21: `whatif myracket --set M2=0.34 --set L2=0.69 --figure fig9`
    printed only the PNG's path: the answer (tau_H, v_H, the gain) was in the legend only,
    and nothing named the theta0 = 90 deg and delta0 = 52.5 deg it was computed at. It
    prints each claim of the figure, measured from the file the run wrote as the claims
    are, and the inputs every stroke of it shares (Fig. 4's strokes share none). The run
    is in-process: Snakemake's part, the figure's file, written as its job writes it."""
    from tennis_stroke.experiments.specs import EXPERIMENTS, compute
    from tennis_stroke.inference.claims import claim_files, measure
    from tennis_stroke.io import interrupts
    from tennis_stroke.io.netcdf import load_result
    from tennis_stroke.pipeline.jobs import save, settings
    from tennis_stroke.pipeline.params import simulation_params

    for name in ("config", "workflow"):
        (tmp_path / name).symlink_to(ROOT / name)
    monkeypatch.chdir(tmp_path)
    row = EXPERIMENTS[key]
    path = tmp_path / "results/scenarios/myracket" / row.path.removeprefix("results/")

    def snakemake(command):
        params = simulation_params(row, merged(PAPER, {"model": {"M2": 0.34, "L2": 0.69}}))
        common = params["common"]
        ds = compute(row, params["args"], common["model"], settings(common), (0, 1), 1)
        path.parent.mkdir(parents=True)
        save(ds, path, params, 0.0)
        return 0

    monkeypatch.setattr(interrupts, "run_forwarding", snakemake)
    argv = ["whatif", "myracket", "--set", "M2=0.34", "--set", "L2=0.69", "--figure", figure]
    assert main(argv) == 0
    out = capsys.readouterr().out
    lines = {line.split()[0]: line for line in out.splitlines() if line.startswith("  ")}
    with load_result(path) as ds:
        ours = {
            c["id"]: measure(c["measure"], {key: ds})
            for c in CLAIMS
            if c["id"].startswith(f"{key}_") and claim_files(c) == [key]
        }
    assert ours and set(ours) <= set(lines), out
    for claim_id, value in ours.items():
        assert f"{value:.4g}" in lines[claim_id], lines[claim_id]
    assert ("theta0 = 90 deg, delta0 = 52.5 deg, L1 = 0.4 m, C2 = 5 N m" in out) == (key == "fig9")
    assert out.rstrip().endswith(f"results/scenarios/myracket/figures/{paper_figure(figure)}.png")


def test_whatif_reads_the_config_as_the_workflow_does_with_its_defaults(tmp_path):
    """A config that leaves keys to the schema's defaults (the solver section here):
    whatif's own check stopped with "tennis-stroke: error: solver"."""
    import shutil

    import yaml

    from tennis_stroke.pipeline.scenarios import scenario_reach

    (tmp_path / "config").mkdir()
    (tmp_path / "workflow" / "schemas").mkdir(parents=True)
    shutil.copy(SCHEMA, tmp_path / "workflow" / "schemas")
    config = {k: v for k, v in PAPER.items() if k not in ("solver", "chunks", "model")}
    (tmp_path / "config" / "config.yaml").write_text(yaml.safe_dump(config))
    assert scenario_reach("s", {"model": {"M2": 0.35}}, ["fig02_angle_map"], tmp_path) == []
    with pytest.raises(ScenarioError, match="does not change fig09_v_tau"):
        scenario_reach("s", {"model": {"C2": 3.0}}, ["fig09_v_tau"], tmp_path)
