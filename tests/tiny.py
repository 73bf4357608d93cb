"""The tiny configuration of the end-to-end workflow tests (small grids, every rule)."""

TINY = {
    "angle_maps": {
        "L1": [0.3, 0.4],
        "theta0": {"start": 60.0, "stop": 120.0, "step": 30.0},
        "delta0": {"start": 0.0, "stop": 90.0, "step": 30.0},
    },
    "fig4": {"strokes": [[120.0, 81.5], [75.0, 39.0]], "t_end": 0.32, "samples": 33},
    "k_sensitivity": {"k_contact": [188.0, 19000.0], "points": 3},
    "mass_length": {
        "M2": {"start": 0.2, "stop": 0.5, "step": 0.3},
        "L1": {"start": 0.2, "stop": 0.5, "step": 0.3},
        "theta0_range": [60.0, 120.0],
        "delta0_range": [0.0, 100.0],
        "coarse_step": 20.0,
        "tolerance": 2.0,
    },
    "torque_delay": {
        "L1": 0.4,
        "theta0": 90.0,
        "fig7": {
            "delta0": 26.1,
            "C2": {"start": 0.0, "stop": 10.0, "step": 5.0},
            "tau": {"start": 0.0, "stop": 0.2, "step": 0.1},
        },
        "fig8": {
            "delta0": {"start": 0.0, "stop": 100.0, "step": 50.0},
            "tau": {"start": 0.0, "stop": 0.2, "step": 0.1},
        },
        "base_stroke": {"C2": 5.0, "delta0": 52.5},
        "fig9": {"tau": {"start": 0.0, "stop": 0.2, "step": 0.05}},
        "strokes": {"tau_L": 0.0, "tau_H": 0.185, "t_end": 0.32, "samples": 33},
    },
    "solver_study": {
        "strokes": 2,
        "seed": 1,
        "scene_strokes": 2,
        "scenes": {"contact": {}, "swing": {"contact_model": "swing_speed"}},
        "compiled_tolerances": [1e-6, 5e-8],
        "scipy_methods": ["DOP853"],
        "scipy_tolerances": [1e-6],
        "rk4_steps": [1e-3],
        "state_times": 4,
        "requirement": {"v_out": 1e-4, "event_time": 1e-6},
        "repeats": 1,
        "convergence": {
            "theta0": 100.0,
            "delta0": 40.0,
            "t_end": 0.15,
            "counts": {"DP54": [10, 20], "RK4": [10, 20]},
        },
        "stability": {
            "k_contact": {"start": 2.0, "stop": 7.0, "num": 2},
            "cases": [["tennis_stroke.DOP853", 5e-8], ["fixed.RK4", 1e-3]],
        },
        "optimum": {
            "M2": [0.3],
            "L1": [0.4],
            "steps": [[20.0, 5.0]],
            "searches": [[20.0, 2.0]],
            "reference_step": 2.0,
        },
    },
    "elbow_force": {
        "F0": 20.0,
        "t_d": 0.05,
        "psi_F": {"start": 0.0, "stop": 270.0, "step": 90.0},
        "tau_F": {"start": -0.05, "stop": 0.05, "step": 0.05},
        "table1_psi": [180.0, 275.0, 76.0],
        "table1_tau_F": -0.027,
    },
    "model_ladder": {
        "rungs": [
            {"name": "swing_omega2", "contact_model": "swing_omega2"},
            {"name": "impact", "contact_model": "impact"},
            {"name": "spring", "contact_model": "spring"},
            {"name": "lossy", "contact_model": "spring", "restitution": 0.8},
            {"name": "dp54", "contact_model": "spring", "solver": {"method": "DP54"}},
        ],
        "reference": "spring",
        "adoption_agreement": 0.1,
    },
    "search": {
        "angle_step": 30.0,
        "tau_step": 0.1,
        "psi_F_step": 90.0,
        "tau_F_step": 0.05,
        "angle_tolerance": 2.0,
        "time_tolerance": 0.01,
        "C2_step": 5.0,
        "C2_tolerance": 0.5,
    },
}

#: A small robustness analysis for the tiny run: a few candidates, every one consistent
#: (a plumbing test: the rules' physics is tested in tests/test_robustness.py), at the
#: tiny run's own grids.
TINY_READINGS = {
    "consistent": {"max_abs_residual": 1000.0},
    # the fits' plumbing: one start each and short profiles (the fits' numerics are
    # tests/inference/test_identification.py's)
    "fits": {"model": {"starts": 1}, "elbow_force": {"starts": 1}, "profile_points": 5},
    "multiverse": {
        "candidates": 4,
        "readings": 3,
        "chunks": 2,
        "resolution": {
            "angle_maps": {"theta0": TINY["angle_maps"]["theta0"]},
            "mass_length": {k: TINY["mass_length"][k] for k in ("M2", "L1")},
            "fig7_tau": TINY["torque_delay"]["fig7"]["tau"],
        },
        "validation": {"readings": 2, "ml_steps": [20.0, 10.0]},
    },
}
#: Chunk files of the tiny run's robustness analysis.
ROBUSTNESS_CHUNKS = 2

#: The maps (gathered from chunks).
MAPS = [
    "results/angle_maps/fig2.nc",
    "results/angle_maps/fig3.nc",
    "results/mass_length/map.nc",
    "results/torque_delay/fig7.nc",
    "results/torque_delay/fig8.nc",
    "results/torque_delay/fig9.nc",
    "results/elbow_force/map.nc",
]
