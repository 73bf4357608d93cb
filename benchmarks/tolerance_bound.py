"""The accuracy bound of the solver settings (``MAX_RTOL``, ``MAX_ATOL`` in
``tennis_stroke.solver.settings``): the largest error of every stroke of the paper's maps
against rtol = atol = 1e-12, for both methods at loose tolerances.

Run: ``.venv/bin/python benchmarks/tolerance_bound.py`` (about 10 s on 2 cores).
The claims' tolerances are 1 km/h, 0.5 rad/s, 1 degree and 2 ms; the bound is the
loosest tolerance whose errors stay well inside them on every map.
"""

from __future__ import annotations

import numpy as np

from tennis_stroke import SolverSettings, strike_batch

#: The maps: (theta0, delta0, parameters), broadcast to their grids (degrees, SI).
MAPS = {
    "Fig. 2 (L1 0.3 m)": (
        np.linspace(60.0, 120.0, 241)[:, None],
        np.linspace(0.0, 90.0, 181)[None, :],
        {"L1": 0.3},
    ),
    "Fig. 3 (L1 0.4 m)": (
        np.linspace(60.0, 120.0, 241)[:, None],
        np.linspace(0.0, 90.0, 181)[None, :],
        {"L1": 0.4},
    ),
    "Fig. 8 (delta0, tau)": (
        90.0,
        np.linspace(0.0, 100.0, 201)[:, None],
        {"L1": 0.4, "C2": 5.0, "tau": np.linspace(0.0, 0.3, 121)[None, :]},
    ),
    "Fig. 13 (psi_F, tau_F)": (
        90.0,
        52.5,
        {
            "L1": 0.4,
            "C2": 5.0,
            "tau": 0.185,
            "F0": 20.0,
            "t_d": 0.05,
            "psi_F_deg": np.linspace(0.0, 360.0, 181)[:, None],
            "t_F": 0.185 + np.linspace(-0.1, 0.1, 41)[None, :],
        },
    ),
}
GROUPS = {
    "v_out km/h": ("v_out_kmh",),
    "omega rad/s": ("omega1_contact", "omega2_contact", "omega1_phi0", "omega2_phi0"),
    "theta deg": ("theta_deg_at_phi0", "theta_deg_contact"),
    "times ms": ("t_phi0", "t_contact_start", "t_separation"),
}
TOLERANCES = (1e-5, 1e-4, 1e-3, 1e-2)


def main() -> None:
    print(f"{'map':24s} {'method':7s} {'rtol=atol':>9s} " + " ".join(f"{g:>12s}" for g in GROUPS))
    for name, (theta0, delta0, params) in MAPS.items():
        tight = SolverSettings(rtol=1e-12, atol=1e-12, history=4096)
        ref = strike_batch(theta0, delta0, params, tight, threads=2)
        for method in ("DOP853", "DP54"):
            for tol in TOLERANCES:
                loose = SolverSettings(method=method, rtol=tol, atol=tol, accuracy_bound=False)
                out = strike_batch(theta0, delta0, params, loose, threads=2)
                both = (ref["status"] == 0) & (out["status"] == 0)
                errors = []
                for group, fields in GROUPS.items():
                    err = max(float(np.nanmax(np.abs(out[f] - ref[f])[both])) for f in fields)
                    errors.append(err * (1e3 if group == "times ms" else 1.0))
                mismatched = int((out["status"] != ref["status"]).sum())
                print(
                    f"{name:24s} {method:7s} {tol:9.0e} "
                    + " ".join(f"{e:12.3g}" for e in errors)
                    + (f"  ({mismatched} statuses differ)" if mismatched else "")
                )


if __name__ == "__main__":
    main()
