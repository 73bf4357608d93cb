"""Claims across readings: quoting variants, the Figs. 5-6 axis cut, the robustness
classes with their deciding unknown, the evidence classes of deviations, and one reading
evaluated end to end against the claims of its own result files."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

from tennis_stroke.inference import multiverse as mv
from tennis_stroke.inference import robustness as ev
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.reading_space import CLAIM_LEVEL, load_reading_space
from tennis_stroke.pipeline.config_check import load_schema, with_defaults
from tennis_stroke.replication import robustness as rb
from tennis_stroke.replication.claims import evaluate
from tennis_stroke.solver.settings import SolverSettings

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def claims():
    return load_claims(ROOT / "config" / "claims.yaml")


@pytest.fixture(scope="module")
def space(claims):
    return load_reading_space(ROOT / "config" / "readings.yaml", [c["id"] for c in claims])


def test_variants_are_every_claim_level_combination(space):
    cases = ev.variants(space)
    assert len(cases) == np.prod([len(space.discrete[k]) for k in CLAIM_LEVEL])
    assert len({tuple(c.values()) for c in cases}) == len(cases)


def test_quoting_changes_only_the_claims_of_its_group(space, claims):
    before = {c["id"]: c["measure"].get("var") for c in claims}
    quoted = ev.quoted_claims(claims, space, {"fig11_theta": "contact", "table1_omega": "contact"})
    after = {c["id"]: c["measure"].get("var") for c in quoted}
    changed = {k for k in before if before[k] != after[k]}
    groups = space.raw["quoting"]
    assert changed == {"fig11_theta_c", *groups["table1_omega"]["claims"]}
    assert after["fig11_theta_c"] == "theta_deg_contact"
    assert after["table1_omega2_180"] == "omega2_contact"
    assert {c["id"]: c["measure"].get("var") for c in claims} == before  # not mutated


def test_the_figs_5_6_axis_is_cut_at_the_reading_s_end():
    ml = xr.Dataset(coords={"L1": [0.2, 0.3, 0.4, 0.5, 0.6, 0.7]})
    results = {"ml": ml, "fig4/free_swing": ml, "delay/free_swing": ml}
    files = ev.files_of_reading(results, "free_swing", 0.55)
    assert list(files["ml"]["L1"].values) == [0.2, 0.3, 0.4, 0.5]
    assert files["fig4"] is ml and "fig4/free_swing" not in files
    assert list(ev.files_of_reading(results, "free_swing", 0.5)["ml"]["L1"].values)[-1] == 0.5


def synthetic(space, within, values=None, lead=None):
    """A claims x readings dataset of three claims (``within``: reading x variant x
    claim) with the readings' contact lead rule and one continuous unknown."""
    n_read, n_var, n_claim = within.shape
    cases = ev.variants(space)[:n_var]
    values = np.where(within, 1.0, 5.0) if values is None else values
    return xr.Dataset(
        {
            "value": (("reading", "variant", "claim"), values),
            "within": (("reading", "variant", "claim"), within.astype(np.int8)),
            "contact_lead_rule": ("reading", lead or ["quarter_period"] * n_read),
            "k_contact": ("reading", np.geomspace(200.0, 18000.0, n_read)),
            **{k: ("variant", [c[k] for c in cases]) for k in CLAIM_LEVEL},
        },
        coords={"claim": ["a", "b", "c"][:n_claim]},
    )


CLAIMS = [{"id": i, "paper_value": 1.0, "tolerance": 0.5, "unit": "1"} for i in ("a", "b", "c")]


def test_robustness_classes_and_the_deciding_unknown(space):
    within = np.ones((4, 2, 3), dtype=bool)
    within[:, :, 1] = [[True, True], [True, True], [False, False], [False, False]]
    within[:, :, 2] = False
    lead = ["quarter_period", "quarter_period", "half_period", "half_period"]
    ds = synthetic(space, within, lead=lead)
    ds["value"][:, :, 2] = [[3.0, 2.0], [9.0, 4.0], [7.0, 8.0], [6.0, 5.0]]
    table = rb.classify(ds, space, CLAIMS).set_index("id")
    assert list(table["robustness"]) == ["robust", "reading_dependent", "not_reproduced"]
    assert table.loc["b", "pass_share"] == 0.5
    assert table.loc["b", "deciding"].startswith("contact_lead_rule")
    assert "quarter_period 4/4" in table.loc["b", "deciding"]
    assert table.loc["c", "best_value"] == 2.0 and table.loc["c", "best_residual"] == 2.0
    fit = [{**CLAIMS[0], "id": "fig4_t_a"}, *CLAIMS[1:]]
    assert (
        rb.classify(ds.assign_coords(claim=["fig4_t_a", "b", "c"]), space, fit)["robustness"].iloc[
            0
        ]
        == "used_for_fit"
    )


def test_a_continuous_unknown_can_decide(space):
    within = np.zeros((4, 1, 3), dtype=bool)
    within[:2, 0, 1] = True  # passes only in the lower half of the k range
    table = rb.classify(synthetic(space, within), space, CLAIMS).set_index("id")
    assert table.loc["b", "deciding"] == "k_contact (lower half 2/2, upper half 0/2)"


def default_table(statuses):
    return pd.DataFrame(
        {"id": ["a", "b", "c"], "status": statuses, "paper_value": [1.0, 1.0, 0.18]}
    )


def test_evidence_classes_of_the_deviations(space):
    within = np.zeros((3, 1, 3), dtype=bool)
    within[:, 0, 0] = True  # a passes everywhere (a pass of the default)
    within[0, 0, 1] = True  # b passes under reading 0, which passes a too
    ds = synthetic(space, within)
    table = default_table(["pass", "known_deviation", "fail"])
    out = rb.evidence(table, ds).set_index("id")
    assert list(out["evidence"]) == ["", "reading_choice", "irreducible"]
    within[0, 0, 0] = False  # now the reading that passes b fails a default pass
    out = rb.evidence(table, synthetic(space, within)).set_index("id")
    assert out.loc["b", "evidence"] == "paper_inconsistency"


def test_a_deviation_on_a_flat_objective_is_ill_conditioned(space):
    """The evidence reads the one rule of flatness from the claims table (its ``flat``
    column: tests/inference/test_optimum_claims.py), for a declared deviation and an
    unexpected failure alike."""
    within = np.zeros((1, 1, 3), dtype=bool)
    ds = synthetic(space, within).assign_coords(claim=["x", "fig9_tau_H", "y"])
    table = pd.DataFrame(
        {
            "id": ["x", "fig9_tau_H", "y"],
            "status": ["pass", "known_deviation", "fail"],
            "paper_value": [1.0, 0.185, 1.0],
            "flat": ["True", "True", "False"],
        }
    )
    out = rb.evidence(table, ds).set_index("id")
    assert list(out["evidence"]) == ["", "ill_conditioned", "irreducible"]
    table["flat"] = ["True", "False", "True"]
    out = rb.evidence(table, ds).set_index("id")
    assert list(out["evidence"]) == ["", "irreducible", "ill_conditioned"]


def test_one_reading_end_to_end_equals_the_claims_of_its_files(space, claims):
    """The claims of one reading at a tiny resolution equal claims.evaluate on the same
    experiment files (an independent path through the claims)."""
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    raw = dict(space.raw)
    tiny = {
        "angle_maps": {"theta0": {"start": 60.0, "stop": 120.0, "step": 30.0}},
        "mass_length": {
            "M2": {"start": 0.2, "stop": 0.5, "step": 0.3},
            "L1": {"start": 0.2, "stop": 0.5, "step": 0.3},
        },
        "fig7_tau": {"start": 0.0, "stop": 0.2, "step": 0.1},
    }
    raw["multiverse"] = {**raw["multiverse"], "resolution": tiny}
    small = type(space)(raw, space.discrete, space.continuous, space.fits)
    config["torque_delay"]["fig8"]["delta0"] = {"start": 0.0, "stop": 100.0, "step": 50.0}
    config["torque_delay"]["fig8"]["tau"] = {"start": 0.0, "stop": 0.2, "step": 0.1}
    config["torque_delay"]["fig9"]["tau"] = {"start": 0.0, "stop": 0.2, "step": 0.05}
    config["torque_delay"]["fig7"]["C2"] = {"start": 0.0, "stop": 10.0, "step": 5.0}
    config["elbow_force"]["psi_F"] = {"start": 0.0, "stop": 270.0, "step": 90.0}
    config["elbow_force"]["tau_F"] = {"start": -0.05, "stop": 0.05, "step": 0.05}
    config["fig4"]["samples"] = 33
    config["torque_delay"]["strokes"]["samples"] = 33
    config["k_sensitivity"]["points"] = 3
    reading = {
        "inertia": "uniform_rod",
        "contact_lead_rule": "quarter_period",
        "collision_coupling": "newton",
        "fig4_theta": "phi0",
        "fig4_omega": "contact",
        "k_contact": 5000.0,
        "ball_mass": 0.057,
        "elbow_force_mass": 1.2,
        "table1_tau_F": -0.02,
        "fig6_L1_max": 0.5,
    }
    cfg, model = mv.experiment_config(config, small, reading)
    settings = SolverSettings(**config["solver"])
    results = mv.paper_results(cfg, model, settings, small.discrete["figure_curves"])
    values, cases = ev.evaluate_reading(claims, small, results, reading)
    files = ev.files_of_reading(results, "free_swing", 0.5)
    for i, case in enumerate(cases):
        if case["figure_curves"] != "free_swing":
            continue
        instants = {"fig4_theta": "phi0", "fig4_omega": "contact", **case}
        table = evaluate(ev.quoted_claims(claims, small, instants), files)
        np.testing.assert_array_equal(values[i], table["reproduced_value"].to_numpy())


def _each_alone(claims, space, results, readings, cases) -> np.ndarray:
    """Every claim (reading x variant x claim) as the claims job measures it: one claim
    on one reading's files (claims.measure), variant by variant."""
    from tennis_stroke.inference.claims import measure

    out = np.full((len(readings), len(cases), len(claims)), np.nan)
    quoting = space.raw["quoting"]
    for r, (files, reading) in enumerate(zip(results, readings, strict=True)):
        fixed = {g: reading[g] for g in quoting if g in reading}
        for v, case in enumerate(cases):
            instants = {**fixed, **{g: case[g] for g in CLAIM_LEVEL if g in quoting}}
            read = ev.files_of_reading(files, case["figure_curves"], reading["fig6_L1_max"])
            for j, claim in enumerate(ev.quoted_claims(claims, space, instants)):
                out[r, v, j] = measure(claim["measure"], read)
    return out


def test_claims_across_readings_equal_each_reading_measured_alone(space, claims):
    """Every claim under every variant, measured across readings at once
    (evaluate_across: the readings stacked, each distinct measure once), equals bit for
    bit the claims job's path, each claim measured on one reading's files alone: on the
    targeted files of thirteen seeded readings (every discrete reading and every unknown
    drawn at random, on the tiny grids; the thirteenth ends Figs. 5-6's axis at its first
    L1, so its file has another size and goes to a stack of its own), and on the full
    maps of three of them (optima at other grid points from reading to reading); and the
    robustness chunk's path (the files of single strokes of all the readings as arrays,
    curve_files_of and number_files_of) equals the one through each reading's datasets."""
    import copy

    from tiny import TINY, TINY_READINGS

    from tennis_stroke.inference.targeted import curve_files_of, number_files_of, targeted_files_of

    config = copy.deepcopy(TINY)
    config.update(with_defaults(config, load_schema(ROOT / "workflow/schemas/config.schema.yaml")))
    raw = dict(space.raw)
    raw["multiverse"] = {
        **raw["multiverse"],
        "resolution": TINY_READINGS["multiverse"]["resolution"],
    }
    small = type(space)(raw, space.discrete, space.continuous, space.fits)
    rng = np.random.default_rng(55)
    readings = []
    for _ in range(12):
        reading = {k: str(rng.choice(v)) for k, v in small.discrete.items() if k not in CLAIM_LEVEL}
        reading.update({k: float(u.from_unit(rng.uniform())) for k, u in small.continuous.items()})
        readings.append(reading)
    readings.append({**readings[0], "fig6_L1_max": 0.25})  # the tiny L1 grid: 0.2, 0.5
    pairs = [mv.experiment_config(config, small, r) for r in readings]
    settings = SolverSettings(**config["solver"])
    curves = small.discrete["figure_curves"]
    targeted = targeted_files_of(
        [c for c, _ in pairs],
        [m for _, m in pairs],
        settings,
        curves,
        [r["fig6_L1_max"] for r in readings],
    )
    assert targeted[-1]["ml"].sizes["L1"] == 1 < targeted[0]["ml"].sizes["L1"]
    maps = [mv.paper_results(c, m, settings, curves) for c, m in pairs[:3]]
    for results, chosen in ((targeted, readings), (maps, readings[:3])):
        together, cases = ev.evaluate_across(claims, small, results, chosen)
        alone = _each_alone(claims, small, results, chosen, cases)
        assert np.array_equal(together.view(np.uint64), alone.view(np.uint64))  # bit for bit
        # the readings differ: most claims take more than one value across them
        varied = [len(np.unique(together[:, :, j])) > 1 for j in range(len(claims))]
        assert sum(varied) > len(claims) // 2
    # the robustness chunk's path: the curve files of every reading as arrays at once
    configs, models = [c for c, _ in pairs], [m for _, m in pairs]
    stacked = {
        **curve_files_of(configs, models, settings, curves),
        **number_files_of(configs, models, settings),
    }
    assert {k for k in targeted[0] if "/" in k} < set(stacked)
    rest = [{k: v for k, v in files.items() if k not in stacked} for files in targeted]
    from_arrays = ev.evaluate_across(claims, small, rest, readings, stacked)[0]
    from_files = ev.evaluate_across(claims, small, targeted, readings)[0]
    assert np.array_equal(from_arrays.view(np.uint64), from_files.view(np.uint64))
