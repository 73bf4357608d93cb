"""Identification as a fit: targets come from the declared fit sets, a fit recovers a
known reading from its own numbers, the default rule and the reading-space checks."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke.inference import identification as idn
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.reading_space import ReadingSpaceError, load_reading_space

ROOT = Path(__file__).resolve().parents[2]
READINGS = ROOT / "config" / "readings.yaml"
STROKES = [[120.0, 81.5], [75.0, 39.0]]


@pytest.fixture(scope="module")
def claims():
    return load_claims(ROOT / "config" / "claims.yaml")


@pytest.fixture(scope="module")
def space(claims):
    return load_reading_space(READINGS, [c["id"] for c in claims])


def test_targets_are_the_declared_fit_claims(space, claims):
    by_id = {c["id"]: c for c in claims}
    for fit in space.fits.values():
        goal = idn.targets(space, fit, claims)
        assert [t.claim for t in goal] == list(fit.claims)
        assert [t.paper for t in goal] == [by_id[c]["paper_value"] for c in fit.claims]
        assert [t.tolerance for t in goal] == [by_id[c]["tolerance"] for c in fit.claims]
    quoted = {t.claim: t.quoting for t in idn.targets(space, space.fits["model"], claims)}
    assert quoted["fig4_omega2_b"] == "fig4_omega" and quoted["fig4_t_a"] is None


def test_quoted_variable_follows_the_instant(space):
    assert idn.quoted_variable("omega1_contact", "phi0", space) == "omega1_phi0"
    assert idn.quoted_variable("theta_deg_at_phi0", "contact", space) == "theta_deg_contact"
    assert idn.quoted_variable("v_out", "contact", space) == "v_out"


def test_a_fit_claim_that_reads_no_stroke_variable_is_refused(space, claims):
    bad = [dict(c) for c in claims]
    for c in bad:
        if c["id"] == "fig4_t_a":
            c["measure"] = {"function": "greater", "file": "fig4"}
    with pytest.raises(ValueError, match="claim 'fig4_t_a'"):
        idn.targets(space, space.fits["model"], bad)


def _exact_targets(space, claims, values, instants):
    """The model fit's targets with the paper's values replaced by ``values`` (a
    simulation), read at ``instants`` (quoting group -> phi0 or contact)."""
    goal = []
    for t in idn.targets(space, space.fits["model"], claims):
        var = idn.quoted_variable(t.var, instants[t.quoting], space) if t.quoting else t.var
        v = float(values[var][t.stroke])
        goal.append(
            idn.Target(
                t.claim,
                t.stroke,
                t.var,
                abs(v) if t.absolute else v,
                t.tolerance,
                t.unit,
                t.absolute,
                t.quoting,
            )
        )
    return goal


def test_the_fit_recovers_a_known_reading_from_its_own_numbers(space, claims):
    """Targets made from one reading's own simulation (k = 3000 N/m, ball 57.5 g,
    quarter-period lead, omega at phi = 0): that combination ranks first with residuals
    near zero, and the fit finds its k and ball mass."""
    truth = {
        "inertia": "uniform_rod",
        "contact_lead_rule": "quarter_period",
        "collision_coupling": "newton",
        "k_contact": 3000.0,
        "ball_mass": 0.0575,
    }
    fit = space.fits["model"]
    simulate = idn.model_simulator(STROKES)
    values = simulate(truth)
    goal = _exact_targets(space, claims, values, {"fig4_theta": "phi0", "fig4_omega": "phi0"})
    rows = idn.fit_all(space, fit, goal, simulate)
    best = rows[0]
    assert {k: best["readings"][k] for k in ("inertia", "contact_lead_rule")} == {
        "inertia": "uniform_rod",
        "contact_lead_rule": "quarter_period",
    }
    assert best["readings"]["fig4_omega"] == "phi0"
    assert best["passed"] == len(goal) and best["score"] < 0.02
    assert best["unknowns"]["k_contact"] == pytest.approx(3000.0, rel=0.05)
    assert len(rows) == 2 * 3 * 2 * 2 * 2


def test_leave_one_out_of_exact_targets_predicts_them(space, claims):
    fit = space.fits["model"]
    simulate = idn.model_simulator(STROKES)
    reading = {
        "inertia": "uniform_rod",
        "contact_lead_rule": "half_period",
        "collision_coupling": "newton",
        "fig4_theta": "phi0",
        "fig4_omega": "contact",
    }
    truth = {"k_contact": 5000.0, "ball_mass": 0.058}
    values = simulate({**{k: reading[k] for k in list(reading)[:3]}, **truth})
    goal = _exact_targets(space, claims, values, reading)
    loo = idn.leave_one_out(space, fit, goal, simulate, {"readings": reading, "unknowns": truth})
    assert max(abs(r["residual"]) for r in loo) < 0.05


def test_default_rule_prefers_more_passes_then_score_then_literal(space):
    def row(lead, passed, score):
        return {"readings": {"contact_lead_rule": lead}, "passed": passed, "score": score}

    rows = [row("zero", 10, 0.300), row("quarter_period", 9, 0.1), row("half_period", 10, 0.305)]
    order = [r["readings"]["contact_lead_rule"] for r in idn.sort_fits(rows, space)]
    # within the declared tie margin (0.01) the literal choice (half_period) wins
    assert order == ["half_period", "zero", "quarter_period"]
    rows[2]["score"] = 0.4
    order = [r["readings"]["contact_lead_rule"] for r in idn.sort_fits(rows, space)]
    assert order == ["zero", "half_period", "quarter_period"]


def test_rounding_keeps_significant_digits():
    assert idn.rounded({"k": 7803.79, "m": 0.057631}, 2) == {"k": 7800.0, "m": 0.058}


def test_unit_variables_round_trip(space):
    for u in space.continuous.values():
        for explo in (False, True):
            lo, hi = u.bounds(explo)
            x = np.linspace(lo, hi, 7)
            assert np.allclose(u.from_unit(u.to_unit(x, explo), explo), x)
            assert u.to_unit(lo, explo) == pytest.approx(0.0)


def _write(tmp_path, change):
    raw = yaml.safe_load(READINGS.read_text())
    change(raw)
    path = tmp_path / "readings.yaml"
    path.write_text(yaml.safe_dump(raw))
    return path


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            lambda r: r["model"]["inertia"].update(choices=["uniform_rod", "hollow"]),
            "'model.inertia': unknown choice",
        ),
        (
            lambda r: r["model"].update(gravity={"choices": ["on"], "why": "not in the paper"}),
            "'model.gravity': not a model reading",
        ),
        (
            lambda r: r["continuous"]["k_contact"].update(range=[19000.0, 188.0]),
            "'continuous.k_contact.range': low must be below high",
        ),
        (
            lambda r: r["continuous"]["ball_mass"].update(range=[-0.1, 0.06]),
            "'continuous.ball_mass'",
        ),
        (
            lambda r: r["fits"]["model"].update(claims=["fig4_t_a", "fig99"]),
            "unknown claim 'fig99'",
        ),
        (
            lambda r: r["fits"]["model"].update(unknowns=["spin"]),
            "'fits.model.unknowns': unknown 'spin'",
        ),
        (lambda r: r["consistent"].update(max_abs_residual=0), "'consistent.max_abs_residual'"),
        (lambda r: r.update(extra=1), "Additional properties"),
        # a duplicate fit unknown or reading planned 56 jobs
        (
            lambda r: r["fits"]["model"].update(unknowns=["k_contact", "k_contact"]),
            "'fits.model.unknowns': ['k_contact', 'k_contact'] has non-unique elements",
        ),
        (
            lambda r: r["fits"]["model"].update(discrete=["inertia", "inertia"]),
            "'fits.model.discrete'",
        ),
        # the fit sets and the quoting instants are enums of the schema
        (
            lambda r: next(iter(r["quoting"].values())).update(choices=["phi0", "impact"]),
            "'impact' is not one of ['phi0', 'contact']",
        ),
        (
            lambda r: next(iter(r["quoted_variables"].values())).pop("contact"),
            "does not have enough properties (rule: minProperties)",
        ),
        (
            lambda r: r["fits"]["elbow_force"].update(given="modle"),
            "'fits.elbow_force.given': 'modle' is not one of ['model', 'elbow_force']",
        ),
        # a NaN passes the schema's minimum; accepted, 23 jobs planned (issue 66, case 9)
        (
            lambda r: r["default_rule"].update(tie_margin=math.nan),
            "'default_rule.tie_margin': nan is not a finite number (rule: finite)",
        ),
        (
            lambda r: r["consistent"].update(fallback_margin=math.inf),
            "'consistent.fallback_margin': inf is not a finite number",
        ),
        (
            lambda r: r["consistent"].update(max_abs_residual=math.nan),
            "'consistent.max_abs_residual': nan is not a finite number",
        ),
    ],
)
def test_bad_reading_space_is_one_line_naming_the_key(tmp_path, claims, change, message):
    path = _write(tmp_path, change)
    with pytest.raises(ReadingSpaceError, match="readings key") as err:
        load_reading_space(path, [c["id"] for c in claims])
    assert message in str(err.value) and "\n" not in str(err.value)


def test_the_fit_sets_of_the_schema_are_the_fits_it_requires():
    """FIT_SETS is read from the schema's enum: the fits section must name each."""
    from tennis_stroke.inference.reading_space import FIT_SETS, SCHEMA

    fits = yaml.safe_load(SCHEMA.read_text())["properties"]["fits"]
    assert FIT_SETS == ("model", "elbow_force")
    assert set(FIT_SETS) <= set(fits["required"]) and set(FIT_SETS) <= set(fits["properties"])


def test_a_yaml_syntax_error_names_the_line(tmp_path):
    path = tmp_path / "readings.yaml"
    path.write_text("model:\n  inertia: [a,\n")
    where = r"readings.yaml, line 3, column 1: YAML syntax error"
    with pytest.raises(ReadingSpaceError, match=where):
        load_reading_space(path)
