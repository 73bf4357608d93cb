"""The robustness analysis' readings: the declared design, the screen against both fit
sets (checked against strokes simulated one by one), the consistency rule, the
round-robin selection and each reading's experiment config."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from tennis_stroke.experiments.specs import fit_set_arguments
from tennis_stroke.experiments.strokes import table1_cases
from tennis_stroke.inference import multiverse as mv
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.inference.identification import targets
from tennis_stroke.inference.reading_space import load_reading_space
from tennis_stroke.solver.results import FILE_NAMES
from tennis_stroke.solver.stroke import strike

ROOT = Path(__file__).resolve().parents[2]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
STROKES = CONFIG["fig4"]["strokes"]
#: File variable -> the key strike() returns it under.
STRIKE_NAMES = {v: k for k, v in FILE_NAMES.items()}
FORCE = {k: CONFIG["elbow_force"][k] for k in ("F0", "t_d", "table1_psi", "table1_tau_F")}


@pytest.fixture(scope="module")
def claims():
    return load_claims(ROOT / "config" / "claims.yaml")


def small_space(claims, tmp_path, **multiverse):
    """The declared space with one discrete combination (the default readings) and a
    smaller design."""
    raw = yaml.safe_load((ROOT / "config" / "readings.yaml").read_text())
    raw["model"]["inertia"]["choices"] = ["uniform_rod"]
    raw["model"]["contact_lead_rule"]["choices"] = ["quarter_period"]
    raw["model"]["collision_coupling"]["choices"] = ["newton"]
    raw["quoting"]["fig4_theta"]["choices"] = ["phi0"]
    raw["quoting"]["fig4_omega"]["choices"] = ["contact"]
    raw["multiverse"].update(multiverse)
    path = tmp_path / "readings.yaml"
    path.write_text(yaml.safe_dump(raw))
    return load_reading_space(path, [c["id"] for c in claims])


def test_design_is_seeded_and_inside_the_declared_ranges(claims, tmp_path):
    space = small_space(claims, tmp_path, candidates=64)
    a, b = mv.design(space), mv.design(space)
    assert list(a) == list(space.continuous)
    for name, values in a.items():
        unknown = space.continuous[name]
        assert values.shape == (64,)
        assert np.array_equal(values, b[name])
        assert (values >= unknown.low).all() and (values <= unknown.high).all()
        u = unknown.to_unit(values)  # space-filling in the declared scale
        assert np.histogram(u, bins=4, range=(0, 1))[0].min() >= 12


def test_the_screen_agrees_with_strokes_simulated_one_by_one(claims, tmp_path):
    space = small_space(claims, tmp_path, candidates=4)
    screened = mv.screen(space, claims, STROKES, FORCE, fit_set_arguments(CONFIG)["stroke"])
    points = mv.design(space)
    model_goal = targets(space, space.fits["model"], claims)
    elbow_goal = targets(space, space.fits["elbow_force"], claims)
    cases = table1_cases(FORCE, fit_set_arguments(CONFIG)["stroke"])
    stroke = fit_set_arguments(CONFIG)["stroke"]
    computed = np.isfinite(screened["rms"].values[0, :, 1])
    assert 0 < computed.sum() < 4  # both branches below are exercised
    points_of = {int(i): row for row, i in enumerate(screened["point_candidate"].values)}
    for i in range(4):
        params = {
            "inertia": "uniform_rod",
            "contact_lead_rule": "quarter_period",
            "collision_coupling": "newton",
            **{k: float(points[k][i]) for k in ("k_contact", "ball_mass", "elbow_force_mass")},
        }
        expected = []
        for t in model_goal:
            res = strike(*STROKES[t.stroke], params)
            var = STRIKE_NAMES.get(t.var, t.var)
            expected.append((abs(res[var]) if t.absolute else res[var]) - t.paper)
            expected[-1] /= t.tolerance
        model_res = np.array(expected)
        rms = screened["rms"].values[0, i]
        assert rms[0] == pytest.approx(np.sqrt(np.mean(model_res**2)), rel=1e-6)  # float32
        if np.abs(model_res).max() <= 1.0:  # Table I only where Fig. 4 leaves it open
            shift = float(points["table1_tau_F"][i]) - FORCE["table1_tau_F"]
            elbow_res = []
            for t in elbow_goal:
                case = {**cases[t.stroke], "t_F": cases[t.stroke]["t_F"] + shift}
                res = strike(stroke["theta0"], stroke["delta0"], {**params, **case})
                elbow_res.append((res[STRIKE_NAMES.get(t.var, t.var)] - t.paper) / t.tolerance)
            assert rms[1] == pytest.approx(np.sqrt(np.mean(np.square(elbow_res))), rel=1e-6)
            want = np.concatenate([model_res, elbow_res])
        else:
            assert np.isnan(rms[1])
            want = model_res
        consistent = bool((np.abs(want) <= 1.0).all()) and want.size > model_res.size
        assert bool(screened["consistent"].values[0, i]) == consistent
        assert (i in points_of) == consistent  # the residuals are kept for consistent ones
        if consistent:
            got = screened["residual"].values[points_of[i]]
            np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-9)


def test_consistency_falls_back_to_the_rms_bound_only_when_no_fit_reaches_all():
    space = type(
        "S", (), {"raw": {"consistent": {"max_abs_residual": 1.0, "fallback_margin": 0.5}}}
    )
    assert mv._bound({"passed": 3, "score": 0.4}, space, 3) == (1.0, np.inf)
    assert mv._bound({"passed": 2, "score": 0.4}, space, 3) == (np.inf, 0.9)
    assert mv._bound(None, space, 3) == (1.0, np.inf)


def test_selection_is_round_robin_in_sobol_order():
    import xarray as xr

    ok = np.array([[1, 0, 1, 1], [0, 1, 0, 0], [0, 0, 0, 0], [1, 1, 0, 0]], dtype=np.int8)
    screened = xr.Dataset({"consistent": (("combination", "candidate"), ok)})
    assert mv.select(screened, 4) == [(0, 0), (1, 1), (3, 0), (0, 2)]
    assert mv.select(screened, 100) == [(0, 0), (1, 1), (3, 0), (0, 2), (3, 1), (0, 3)]
    assert mv.select(screened.assign(consistent=screened.consistent * 0), 5) == []


def test_no_consistent_reading_is_one_line(claims, tmp_path):
    import xarray as xr

    space = small_space(claims, tmp_path)
    screened = xr.Dataset({"consistent": (("combination", "candidate"), np.zeros((1, 3)))})
    with pytest.raises(mv.MultiverseError, match="no candidate"):
        mv.readings_dataset(space, screened)


def test_a_reading_sets_the_model_the_experiments_and_the_resolution(claims, tmp_path):
    space = small_space(claims, tmp_path)
    reading = {
        "inertia": "paper_text",
        "fig4_omega": "phi0",
        "k_contact": 1000.0,
        "ball_mass": 0.057,
        "table1_tau_F": 0.01,
        "fig6_L1_max": 0.6,
    }
    cfg, model = mv.experiment_config(CONFIG, space, reading)
    assert model == {"inertia": "paper_text", "k_contact": 1000.0, "ball_mass": 0.057}
    assert cfg["elbow_force"]["table1_tau_F"] == 0.01
    resolution = space.raw["multiverse"]["resolution"]
    assert cfg["torque_delay"]["fig7"]["tau"] == resolution["fig7_tau"]
    assert cfg["angle_maps"]["theta0"] == resolution["angle_maps"]["theta0"]
    assert cfg["angle_maps"]["L1"] == CONFIG["angle_maps"]["L1"]  # merged, not replaced
    assert "fig7_tau" not in cfg
    assert CONFIG["elbow_force"]["table1_tau_F"] != 0.01  # the config is not changed
