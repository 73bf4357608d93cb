"""Measurements of the paper's claims: functions of result datasets returning a number.

A claim of ``config/claims.yaml`` names one of :data:`MEASUREMENTS` (without the
``measure_`` prefix) and its arguments.  Qualitative claims are measurements returning 1
(true) or 0 (false).  The figures use some of them to mark what the claims read.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np
import xarray as xr

from ..solver.results import OK


def valid_v_out(ds: xr.Dataset) -> xr.DataArray:
    """v_out (km/h) of a result dataset with failed strokes as NaN."""
    return ds["v_out"].where(ds["status"] == OK)


def valid_values(ds: xr.Dataset, var: str) -> xr.DataArray:
    """Variable ``var`` as a view or a difference shows it: v_out of a file with
    statuses with its failed strokes NaN (:func:`valid_v_out`), any other as it is."""
    return valid_v_out(ds) if var == "v_out" and "status" in ds else ds[var]


def measure_delay_threshold(ds: xr.Dataset) -> float:
    """Fig. 7: the torque C2 above which the best delay is no longer 0 (N m).

    The first C2 of the grid from which on the best tau stays above 0 (more than half a
    tau step), interpolated half-way to the previous C2; C2 = 0 is skipped (v_out does not
    depend on tau there).
    """
    c2 = ds["C2"].values
    tau_step = float(ds["tau"][1] - ds["tau"][0])
    positive = (ds["best_tau"].values > 0.5 * tau_step) & (c2 > 0)
    for i in range(len(c2)):
        if c2[i] > 0 and positive[i:].all():
            return float(0.5 * (c2[i] + c2[i - 1])) if i > 0 else float(c2[i])
    return float("nan")


def measure_below_threshold_tau_zero(ds: xr.Dataset) -> float:
    """Fig. 7: 1 if the best tau is 0 for every C2 in (0, threshold)."""
    thr = measure_delay_threshold(ds)
    tau_step = float(ds["tau"][1] - ds["tau"][0])
    sel = (ds["C2"] > 0) & (ds["C2"] < thr)
    return float(bool((ds["best_tau"].where(sel, 0.0) <= 0.5 * tau_step).all()))


def measure_optimum(ds: xr.Dataset, coord: str) -> float:
    """The coordinate ``coord`` of the largest v_out of a map (grid point)."""
    v = valid_v_out(ds)
    index = np.unravel_index(int(np.argmax(v.fillna(-np.inf).values)), v.shape)
    return float(ds[coord][index[v.dims.index(coord)]])


def measure_minimum(ds: xr.Dataset, coord: str) -> float:
    """The coordinate ``coord`` of the smallest v_out of a map (grid point)."""
    v = valid_v_out(ds)
    index = np.unravel_index(int(np.argmin(v.fillna(np.inf).values)), v.shape)
    return float(ds[coord][index[v.dims.index(coord)]])


def measure_fig9(ds: xr.Dataset, what: Literal["v_L", "v_H", "tau_H", "gain_percent"]) -> float:
    """Fig. 9: ``v_L`` (tau = 0), ``v_H`` (max), ``tau_H`` or the ``gain_percent``."""
    d = ds.isel(delta0=0)
    v_l = float(valid_v_out(d)[0])
    v_h, tau_h = float(d["best_v_out"]), float(d["best_tau"])
    return {"v_L": v_l, "v_H": v_h, "tau_H": tau_h, "gain_percent": 100 * (v_h / v_l - 1)}[what]


def measure_best_delta0(ds: xr.Dataset, theta0: float) -> float:
    """Figs. 2-3: the best delta0 at ``theta0`` (the red line)."""
    return float(ds["best_delta0"].sel(theta0=theta0, method="nearest"))


def measure_best_delta0_decreases(ds: xr.Dataset) -> float:
    """Figs. 2-3: 1 if the best delta0 falls from theta0 = 60 to 90 to 120 degrees."""
    b = [measure_best_delta0(ds, t) for t in (60.0, 90.0, 120.0)]
    return float(b[0] > b[1] > b[2])


def measure_delta0_smaller_for_longer_arm(short: xr.Dataset, long: xr.Dataset) -> float:
    """Fig. 3 vs 2: 1 if the best delta0 is smaller for L1 = 0.4 m at 90 % of theta0."""
    diff = long["best_delta0"].values - short["best_delta0"].values
    return float(np.mean(diff < 0) >= 0.9)


def measure_stroke(ds: xr.Dataset, var: str, stroke: int, absolute: bool = False) -> float:
    value = float(ds[var].isel(stroke=stroke))
    return abs(value) if absolute else value


def measure_greater(ds: xr.Dataset, var: str, first: int, second: int) -> float:
    """1 if ``var`` of stroke ``first`` exceeds that of stroke ``second``."""
    return float(measure_stroke(ds, var, first) > measure_stroke(ds, var, second))


def measure_omega2_peak_greater(ds: xr.Dataset, first: int, second: int) -> float:
    """Fig. 4: 1 if the whole-stroke maximum of omega2 of ``first`` exceeds ``second``'s."""
    peaks = ds["omega2"].max("t")
    return float(float(peaks[first]) > float(peaks[second]))


def measure_omega2_rises_after_contact(ds: xr.Dataset, stroke: int) -> float:
    """Fig. 4: 1 if omega2 is larger 10 ms after separation than at the contact start."""
    d = ds.isel(stroke=stroke)
    later = float(d["omega2"].interp(t=float(d["t_separation"]) + 0.01))
    return float(later > float(d["omega2_contact"]))


def measure_peak_after_contact(ds: xr.Dataset, stroke: int) -> float:
    """Fig. 10: 1 if omega2 peaks after the contact start (the ball is hit before)."""
    d = ds.isel(stroke=stroke)
    t_peak = float(d["t"][int(np.argmax(d["omega2"].fillna(-np.inf).values))])
    return float(t_peak > float(d["t_contact_start"]))


def measure_omega1_at_omega2_peak(ds: xr.Dataset, stroke: int) -> float:
    """Fig. 10: |omega1| (rad/s) when omega2 has its maximum."""
    d = ds.isel(stroke=stroke)
    return abs(float(d["omega1"][int(np.argmax(d["omega2"].fillna(-np.inf).values))]))


def measure_contact_time_difference(ds: xr.Dataset) -> float:
    """Fig. 10: |t_c(tau_H) - t_c(tau_L)| (s)."""
    return abs(float(ds["t_contact_start"][1] - ds["t_contact_start"][0]))


def measure_k_spread(ds: xr.Dataset) -> float:
    """Sec. II: the largest change of v_out over the spring constants of a
    ``(stroke, k_contact)`` map, per stroke in % of its largest v_out (the largest of
    the strokes)."""
    v = valid_v_out(ds)
    spread = (v.max("k_contact") - v.min("k_contact")) / v.max("k_contact") * 100.0
    return float(spread.max())


def measure_mass_trend(ds: xr.Dataset, m2: float, sign: Literal[-1, 1]) -> float:
    """Fig. 5: 1 if the fastest v_out at ``M2`` changes with L1 (largest vs smallest) in
    the direction ``sign``."""
    row = ds["v_out_best"].sel(M2=m2, method="nearest")
    return float(np.sign(float(row[-1] - row[0])) == sign)


def measure_theta_c(ds: xr.Dataset, end: Literal["small", "large"]) -> float:
    """Fig. 6: mean over M2 of theta_c at the smallest or largest L1 (degree)."""
    return float(ds["theta_c"].isel(L1={"small": 0, "large": -1}[end]).mean())


def measure_theta_c_decreases(ds: xr.Dataset) -> float:
    """Fig. 6: 1 if theta_c at the largest L1 is below that at the smallest, for every M2."""
    tc = ds["theta_c"]
    return float(bool((tc.isel(L1=-1) < tc.isel(L1=0)).all()))


def measure_table1_minimum(ds: xr.Dataset) -> float:
    """Table I: 1 if psi_F = 275 deg gives the slowest rebound of the four cases."""
    v = ds["v_out"].values
    psi = ds["psi_F"].values
    return float(np.nanargmin(v) == int(np.flatnonzero(psi == 275.0)[0]))


#: Named measurements: function(datasets..., **args) -> float.  The parameters annotated
#: ``xr.Dataset`` take the claim's files in order, the others its arguments; the
#: annotations (``float``, ``int``, ``str``, ``Literal[...]``) are checked before any job
#: (:func:`tennis_stroke.inference.claims.claim_errors`).
MEASUREMENTS: dict[str, Callable[..., float]] = {
    name.removeprefix("measure_"): fn
    for name, fn in globals().items()
    if name.startswith("measure_") and callable(fn)
}
