"""The study figures drawn from fixed data (no clock, no solver): the stability figure's
two panels, named axes and labelled band; the work-precision figure's rows per scene."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from tennis_stroke.io.units import cf_attrs  # noqa: E402
from tennis_stroke.replication.drawing.stability import stability  # noqa: E402

CASES = [("tennis_stroke.DOP853", 5e-8), ("scipy.RK45", 1e-3), ("fixed.RK4", 1e-3)]


def _stability_file():
    k = np.array([1e2, 1e4, 1e6])
    ds = xr.Dataset(
        {
            "outcome": (("case", "k_contact"), np.array([[0, 0, 0], [3, 3, 3], [0, 2, 4]])),
            "setting": ("case", [v for _, v in CASES], cf_attrs("setting")),
        },
        coords={
            "case": [f"{m} @ {v:g}" for m, v in CASES],
            "k_contact": ("k_contact", k, cf_attrs("k_contact")),
        },
        attrs={"paper_k_contact": [188.0, 19000.0]},
    )
    ds["outcome"].attrs.update(
        flag_meanings="ok inaccurate missed_contact energy_created blow_up event_error",
        outcome_meanings="ok: fine; inaccurate: off; missed_contact: jumped; "
        "energy_created: grew; blow_up: overflow; event_error: none found",
    )
    return ds


def test_stability_has_a_panel_per_kind_of_method_with_named_axes_and_a_named_band():
    fig = stability([_stability_file()], "Stability")
    try:
        panels = [ax for ax in fig.axes if ax.get_xlabel()]
        assert len(panels) == 2
        assert panels[0].get_ylabel() == "method, tolerance\nrtol = atol (1)"
        assert panels[1].get_ylabel() == "RK4 step (s)"
        for ax in panels:
            assert ax.get_xlabel().endswith("(N/m)") and ax.get_xscale() == "log"
        ticks = [t.get_text() for t in panels[1].get_yticklabels()]
        assert ticks == ["0.001"]
        legend = [t.get_text() for t in panels[0].get_legend().get_texts()]
        assert "paper's k: 188-19000 N/m" in legend
        assert "energy_created: grew" in legend
    finally:
        plt.close(fig)
