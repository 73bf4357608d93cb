"""Claims are checked before any job: every kind of bad entry of config/claims.yaml is one
line naming the claim (tennis_stroke.inference.claims.claim_errors)."""

import copy
import inspect
import typing

import pytest
import xarray as xr
import yaml
from conftest import ROOT

from tennis_stroke.experiments.specs import PAPER_RESULTS
from tennis_stroke.inference.claims import (
    ClaimError,
    claim_axis_errors,
    claim_errors,
    load_claims,
    measure,
)
from tennis_stroke.inference.measures import MEASUREMENTS, Stack

CLAIMS = yaml.safe_load((ROOT / "config" / "claims.yaml").read_text())


def _claims_file(tmp_path, change):
    """config/claims.yaml with ``change`` applied to its list of claims (by id)."""
    raw = copy.deepcopy(CLAIMS)
    by_id = {c["id"]: c for c in raw["claims"]}
    change(raw["claims"], by_id)
    path = tmp_path / "claims.yaml"
    path.write_text(yaml.safe_dump(raw, sort_keys=False))
    return path


def _set(claim_id, **values):
    def change(claims, by_id):
        by_id[claim_id].update(values)

    return change


def _measure(claim_id, **values):
    def change(claims, by_id):
        by_id[claim_id]["measure"].update(values)

    return change


def _drop(claim_id, key, where=None):
    def change(claims, by_id):
        target = by_id[claim_id] if where is None else by_id[claim_id][where]
        del target[key]

    return change


def _duplicate(claims, by_id):
    claims[2]["id"] = claims[1]["id"]


BAD = {
    "duplicate id": (_duplicate, "duplicate claim id 'fig2_best_delta0_at_120'"),
    # the table of experiments says which variables a file holds: refused before any job
    # (it failed in the identification with only "KeyError: 'nonexistent'")
    "unknown variable": (
        _measure("fig4_t_a", var="nonexistent"),
        "claim 'fig4_t_a': file 'fig4' has no variable 'nonexistent' (its variables:",
    ),
    "missing field": (
        _drop("fig4_t_a", "unit"),
        "claim 'fig4_t_a': lacks 'unit'",
    ),
    "missing id": (_drop("fig4_t_a", "id"), "claim 'number 7': lacks 'id'"),
    "unknown file": (
        _measure("fig2_best_delta0_at_120", file="fig44"),
        "claim 'fig2_best_delta0_at_120': unknown result file 'fig44' (known: delay, elbow,",
    ),
    "unknown file in a list": (
        _measure("fig3_delta0_smaller_than_fig2", file=["fig2", "fig33"]),
        "claim 'fig3_delta0_smaller_than_fig2': unknown result file 'fig33'",
    ),
    "unknown measurement": (
        _measure("fig2_best_delta0_at_120", function="best_delta"),
        "claim 'fig2_best_delta0_at_120': unknown measurement 'best_delta' (known: ",
    ),
    "missing argument": (
        _drop("fig2_best_delta0_at_120", "theta0", "measure"),
        "claim 'fig2_best_delta0_at_120': measurement 'best_delta0' with 1 file(s) and "
        "arguments {}: missing a required argument: 'theta0'",
    ),
    "unknown argument": (
        _measure("fig8_tau_opt", coordinate="tau"),
        "claim 'fig8_tau_opt': measurement 'optimum' with 1 file(s) and arguments "
        "{'coord': 'tau', 'coordinate': 'tau'}: got an unexpected keyword argument "
        "'coordinate'",
    ),
    "too few files": (
        _measure("fig3_delta0_smaller_than_fig2", file="fig2"),
        "claim 'fig3_delta0_smaller_than_fig2': measurement "
        "'delta0_smaller_for_longer_arm' with 1 file(s) and arguments {}: missing a "
        "required argument: 'long'",
    ),
    "too many files": (
        _measure("fig2_best_delta0_at_120", file=["fig2", "fig3"]),
        "claim 'fig2_best_delta0_at_120': measurement 'best_delta0' with 2 file(s) and "
        "arguments {'theta0': 120.0}: multiple values for argument 'theta0'",
    ),
    "argument of the wrong type": (
        _measure("fig2_best_delta0_at_120", theta0="120"),
        "claim 'fig2_best_delta0_at_120': measurement 'best_delta0': argument 'theta0' = "
        "'120' is not a float",
    ),
    "argument not among the choices": (
        _measure("fig6_theta_c_folded_arm", end="smallest"),
        "claim 'fig6_theta_c_folded_arm': measurement 'theta_c': argument 'end' = "
        "'smallest' is not one of ('small', 'large')",
    ),
    "a file given as an argument": (
        _measure("fig2_best_delta0_at_120", ds="fig2"),
        "claim 'fig2_best_delta0_at_120': measurement 'best_delta0' with 1 file(s) and "
        "arguments {'theta0': 120.0, 'ds': 'fig2'}: multiple values for argument 'ds'",
    ),
    "variable measure with an unknown key": (
        _measure("fig4_theta_c_a", absolute=True),
        "claim 'fig4_theta_c_a': measure has unknown keys ['absolute']",
    ),
    "variable measure without a variable": (
        _drop("fig4_t_a", "var", "measure"),
        "claim 'fig4_t_a': measure lacks 'var' (the variable of the file) or 'function'",
    ),
    "variable measure with a label for a position": (
        _measure("fig4_t_a", sel={"stroke": "b"}),
        "claim 'fig4_t_a': sel must map dimensions to integer positions or coordinate values",
    ),
    "measure without a file": (
        _drop("fig4_t_a", "file", "measure"),
        "claim 'fig4_t_a': measure lacks 'file' (the result file it reads)",
    ),
    "negative tolerance": (
        _set("fig4_t_a", tolerance=-0.002),
        "claim 'fig4_t_a': tolerance must be >= 0, got -0.002",
    ),
    "zero tolerance of a quantitative claim": (
        _set("fig4_t_a", tolerance=0),
        "claim 'fig4_t_a': tolerance must be > 0 (0 only for a qualitative claim, unit '1'; "
        "unit here 's')",
    ),
    "tolerance not a number": (
        _set("fig4_t_a", tolerance="2 ms"),
        "claim 'fig4_t_a': tolerance must be a finite number, got '2 ms'",
    ),
    "paper value not finite": (
        _set("fig4_t_a", paper_value=float("nan")),
        "claim 'fig4_t_a': paper_value must be a finite number, got nan",
    ),
    "unknown expectation": (
        _set("fig4_t_a", expectation="reproduced"),
        "claim 'fig4_t_a': expectation must be one of ('reproduce', 'known_deviation')",
    ),
    "known deviation without a reason": (
        _set("fig4_t_a", expectation="known_deviation"),
        "claim 'fig4_t_a': a known deviation needs a reason",
    ),
    # issue 66, case 10: each was accepted
    "unknown key": (
        _set("fig4_t_a", weight=3),
        "claim 'fig4_t_a': unknown key 'weight' (a claim takes id, source,",
    ),
    "misspelt key": (
        _set("fig4_t_a", reasn="r"),
        "claim 'fig4_t_a': unknown key 'reasn' (did you mean reason?)",
    ),
    "a unit the measurement does not give": (
        _set("fig2_best_delta0_at_120", unit="rad"),
        "claim 'fig2_best_delta0_at_120': unit 'rad' is not the unit its measure gives, 'degree'",
    ),
    "a unit nobody knows": (
        _set("fig2_best_delta0_at_120", unit="furlong"),
        "unit 'furlong' is not the unit its measure gives, 'degree'",
    ),
    "a unit the file's variable does not have": (
        _set("fig4_t_a", unit="ms"),
        "claim 'fig4_t_a': unit 'ms' is not the unit its measure gives, 's'",
    ),
    "a unit that depends on the measurement's argument": (
        _set("fig8_tau_opt", unit="degree"),
        "claim 'fig8_tau_opt': unit 'degree' is not the unit its measure gives, 's'",
    ),
    "a qualitative claim with a value between true and false": (
        _set("fig2_best_delta0_decreases", paper_value=0.5),
        "claim 'fig2_best_delta0_decreases': a qualitative claim (its measure gives 1, "
        "true, or 0, false) has paper_value 1 or 0, got 0.5",
    ),
    "a qualitative claim with a tolerance": (
        _set("fig2_best_delta0_decreases", tolerance=1),
        "a qualitative claim (its measure gives 1 or 0) has tolerance 0, got 1",
    ),
    "a measurement's argument not finite": (
        _measure("fig2_best_delta0_at_120", theta0=float("nan")),
        "claim 'fig2_best_delta0_at_120': measure.theta0 must be a finite number, got nan",
    ),
}


def test_the_paper_claims_are_good():
    assert claim_errors(ROOT / "config" / "claims.yaml") == []


@pytest.mark.parametrize("kind", sorted(BAD))
def test_each_kind_of_bad_claim_is_one_line_naming_it(tmp_path, kind):
    change, expected = BAD[kind]
    path = _claims_file(tmp_path, change)
    errors = claim_errors(path)
    assert errors, kind
    assert errors[0].startswith(f"{path}: ")
    assert expected in errors[0], errors[0]
    assert "\n" not in errors[0]
    with pytest.raises(ClaimError, match="^" + str(path)):
        load_claims(path)


@pytest.mark.parametrize(
    "text, expected",
    [
        ("claims: [\n", ", line 2, column 1: YAML syntax error: expected the node content"),
        ("statements: {}\n", "no list of claims (key 'claims')"),
        ("claims: [just a claim]\n", "claim 1 is not a mapping: 'just a claim'"),
    ],
)
def test_a_claims_file_that_is_not_a_list_of_claims(tmp_path, text, expected):
    path = tmp_path / "claims.yaml"
    path.write_text(text)
    errors = claim_errors(path)
    assert len(errors) == 1
    if expected.startswith(","):  # a YAML error: file, line and column, then the problem
        assert errors[0].startswith(f"{path}{expected}"), errors
    else:
        assert errors == [f"{path}: {expected}"]


def test_a_missing_claims_file(tmp_path):
    assert claim_errors(tmp_path / "nothing.yaml") == [
        f"cannot read {str(tmp_path / 'nothing.yaml')!r}: No such file or directory"
    ]


def test_the_known_files_are_the_registry_s_paper_results(tmp_path):
    """A claim may name only a file the workflow makes for the claims job."""
    path = _claims_file(tmp_path, _measure("fig2_best_delta0_at_120", file="work_precision"))
    assert "unknown result file 'work_precision'" in claim_errors(path)[0]
    assert claim_errors(path, [*PAPER_RESULTS, "work_precision"]) == []


KNOWN_ANNOTATIONS = (Stack, float, int, str, bool)


@pytest.mark.parametrize("name", sorted(MEASUREMENTS))
def test_every_measurement_says_what_it_takes(name):
    """The check reads the signatures: every parameter is annotated with a dataset, a
    plain type or a Literal of choices, and the datasets come first."""
    parameters = inspect.signature(MEASUREMENTS[name], eval_str=True).parameters.values()
    kinds = []
    for p in parameters:
        literal = typing.get_origin(p.annotation) is typing.Literal
        on_axis = typing.get_origin(p.annotation) is typing.Annotated and typing.get_args(
            p.annotation
        )[0] in (float, int)
        assert literal or on_axis or p.annotation in KNOWN_ANNOTATIONS, (name, p.name)
        kinds.append(p.annotation is Stack)
    assert kinds[0] and kinds == sorted(kinds, reverse=True), name
    assert callable(getattr(MEASUREMENTS[name], "unit", None)), f"{name} says no unit (gives)"


def test_sel_takes_a_position_or_a_coordinate_value():
    """An integer in ``sel`` is a position, a decimal number a value of the dimension's
    coordinate (the README's worked example reads Fig. 9 at delta0: 52.5); a value not
    on the axis is one line naming the nearest."""
    import numpy as np

    ds = xr.Dataset(
        {"v": (("delta0", "tau"), np.arange(6.0).reshape(3, 2))},
        coords={"delta0": [50.0, 52.5, 55.0], "tau": [0.0, 0.1]},
    )
    spec = {"file": "f", "var": "v"}
    assert measure({**spec, "sel": {"delta0": 52.5, "tau": 1}}, {"f": ds}) == 3.0
    assert measure({**spec, "sel": {"delta0": 2, "tau": 0.0}}, {"f": ds}) == 4.0
    with pytest.raises(ClaimError, match=r"f: no delta0 = 52.4 on its axis \(nearest 52.5\)"):
        measure({**spec, "sel": {"delta0": 52.4, "tau": 0}}, {"f": ds})


PAPER_CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())


def _axis_errors(claim_id, config=PAPER_CONFIG, **values):
    claims = copy.deepcopy(CLAIMS["claims"])
    next(c for c in claims if c["id"] == claim_id)["measure"].update(values)
    return claim_axis_errors(claims, config, "claims.yaml")


@pytest.mark.parametrize("theta0", [130.0, 500.0, -1000.0, 120.001, 59.99])
def test_a_claim_read_off_its_file_s_axis_is_refused_before_any_job(theta0):
    """Fig. 2's map spans theta0 60-120 deg (config/config.yaml): a claim at 130 deg was
    read at the nearest row, 120 deg's value, and passed for it (issue 66, case 1)."""
    errors = _axis_errors("fig2_best_delta0_at_120", theta0=theta0)
    assert errors == [
        f"claims.yaml: claim 'fig2_best_delta0_at_120': theta0 = {theta0:g} lies off the "
        "theta0 axis of file 'fig2', 60 to 120 (config key 'angle_maps.theta0'): a "
        "measurement reads a value on its axis, never beyond"
    ]


@pytest.mark.parametrize("theta0", [120.0, 120.0 + 1e-9, 60.0 - 1e-9, 90.1, 60])
def test_a_claim_on_its_axis_passes_between_grid_points_and_at_a_float_end(theta0):
    assert _axis_errors("fig2_best_delta0_at_120", theta0=theta0) == []


def test_the_axis_is_the_config_s_grid_of_the_file():
    """A mass-length claim's M2 against Figs. 5-6's M2 grid (mass_length.M2)."""
    assert (
        "m2 = 0.6 lies off the M2 axis of file 'ml', 0.2 to 0.5 (config key "
        in (_axis_errors("fig5_heavy_racket_trend", m2=0.6)[0])
    )
    assert _axis_errors("fig5_heavy_racket_trend", m2=0.5) == []


def test_the_angles_of_a_trend_claim_are_checked_against_its_file_s_axis():
    """Fig. 2's 'best delta0 decreases from 60 to 120 deg' read 60, 90 and 120 deg fixed in
    the measurement, where no check saw them: on a map from 70 deg it failed in the
    claims job. They are now the claim's arguments, checked at planning."""
    config = copy.deepcopy(PAPER_CONFIG)
    config["angle_maps"]["theta0"]["start"] = 70.0
    (error,) = _axis_errors("fig2_best_delta0_decreases", config)
    assert "claim 'fig2_best_delta0_decreases': low = 60 lies off the theta0 axis" in error
    assert _axis_errors("fig2_best_delta0_decreases", config, low=75.0) == []
