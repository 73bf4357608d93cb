"""The one registry of result files and figures, read by the workflow and the report.

:data:`RESULT_FILES` names every result file by the key that claims
(``config/claims.yaml``) and figures use.  :data:`FIGURES` gives every figure its
section of the paper, the files it is drawn from, the drawing function of
:mod:`tennis_stroke.replication.figures` with its extra arguments, and its title.  What
the paper says about a figure, with its numbers, is in ``config/claims.yaml``
(``statements``), the only home of the paper's numbers.

Pure data: the Snakefile imports it without loading the plotting libraries.
"""

from __future__ import annotations

from dataclasses import dataclass

#: The paper's figures of the angle maps, in the order of the config's ``angle_maps.L1``
#: (the rod-1 length of each): Fig. 2 first, Fig. 3 second.
ANGLE_MAP_FIGURES = ("fig2", "fig3")
#: The paper's result files (the claims read these), by key.  A file is named by the
#: paper's figure, never by a parameter value the config can change (the value is in the
#: file's attributes and the figure's title).
PAPER_RESULTS = {
    **{fig: f"results/angle_maps/{fig}.nc" for fig in ANGLE_MAP_FIGURES},
    "fig4": "results/strokes/fig4.nc",
    "k_sensitivity": "results/strokes/k_sensitivity.nc",
    "ml": "results/mass_length/map.nc",
    "fig7": "results/torque_delay/fig7.nc",
    "fig8": "results/torque_delay/fig8.nc",
    "fig9": "results/torque_delay/fig9.nc",
    "delay": "results/strokes/delay.nc",
    "elbow_map": "results/elbow_force/map.nc",
    "elbow": "results/strokes/elbow_force.nc",
}
#: The speed-against-accuracy studies' result files, by key.
STUDY_RESULTS = {
    "work_precision": "results/solver_study/work_precision.nc",
    "stability": "results/solver_study/stability.nc",
    "ladder": "results/solver_study/ladder.nc",
    "optimum_cost": "results/solver_study/optimum_cost.nc",
}
#: The identification's files (config/readings.yaml), by ``{fit set}_{kind}``.
IDENTIFICATION_FILES = {
    f"{fit}_{kind}": f"results/identification/{fit}_{kind}.nc"
    for fit in ("model", "elbow_force")
    for kind in ("fits", "profiles", "loo")
}
#: The robustness analysis' files: the screen of the candidate readings, the kept
#: consistent readings, and every claim under each of them (claims x readings).
ROBUSTNESS_FILES = {
    "robustness_screen": "results/robustness/screen.nc",
    "robustness_readings": "results/robustness/readings.nc",
    "robustness": "results/robustness/claims.nc",
}
#: The inference's files (identification and robustness), by key.
INFERENCE_RESULTS = {**IDENTIFICATION_FILES, **ROBUSTNESS_FILES}
RESULT_FILES = {**PAPER_RESULTS, **STUDY_RESULTS, **INFERENCE_RESULTS}


@dataclass(frozen=True)
class Figure:
    """One figure: file name (without ``.png``), section of the paper (``III`` ... ``VI``,
    ``inference`` or ``study``), result files (keys of :data:`RESULT_FILES`), drawing function of
    :mod:`tennis_stroke.replication.figures` and its extra arguments, and its title: a
    template filled from the first file's attributes (``{L1}`` is ``param_L1``), so a
    title never states a value the file does not hold."""

    name: str
    section: str
    files: tuple[str, ...]
    draw: str
    title: str
    args: tuple = ()

    @property
    def inputs(self) -> list[str]:
        """The result files it is drawn from (paths relative to the workflow)."""
        return [RESULT_FILES[key] for key in self.files]


FIGURES: dict[str, Figure] = {
    f.name: f
    for f in [
        Figure(
            "fig02_angle_map",
            "III",
            ("fig2",),
            "angle_map",
            "Fig. 2: v_out over the initial angles: L1 = {L1:g} m",
        ),
        Figure(
            "fig03_angle_map",
            "III",
            ("fig3",),
            "angle_map",
            "Fig. 3: v_out over the initial angles: L1 = {L1:g} m",
        ),
        Figure(
            "fig04_omegas", "III", ("fig4",), "omegas", "Fig. 4: angular velocities of two strokes"
        ),
        Figure(
            "fig05_mass_length_vout",
            "IV",
            ("ml",),
            "mass_length",
            "Fig. 5: fastest v_out over (M2, L1)",
            ("v_out_best",),
        ),
        Figure(
            "fig06_mass_length_theta_c",
            "IV",
            ("ml",),
            "mass_length",
            "Fig. 6: theta_c of the fastest stroke",
            ("theta_c",),
        ),
        Figure(
            "fig07_torque_delay",
            "V",
            ("fig7",),
            "delay_map",
            "Fig. 7: v_out over (C2, tau), theta0 = {theta0_deg:g}, delta0 = {delta0_deg:g}",
        ),
        Figure(
            "fig08_delay_delta0",
            "V",
            ("fig8",),
            "delay_map",
            "Fig. 8: v_out over (delta0, tau), C2 = {C2:g} N m",
        ),
        Figure("fig09_v_tau", "V", ("fig9",), "v_tau", "Fig. 9: v_out over the delay tau"),
        Figure(
            "fig10_omegas_delay",
            "V",
            ("delay",),
            "omegas",
            "Fig. 10: angular velocities for tau_L and tau_H",
        ),
        Figure(
            "fig11_strobe_tau_H",
            "V",
            ("delay",),
            "strobe",
            "Fig. 11: stroke with tau_H",
            ("tau_H",),
        ),
        Figure(
            "fig12_strobe_tau_L",
            "V",
            ("delay",),
            "strobe",
            "Fig. 12: stroke with tau_L",
            ("tau_L",),
        ),
        Figure(
            "fig13_elbow_force",
            "VI",
            ("elbow_map",),
            "elbow_force",
            "Fig. 13: v_out over the elbow force direction and delay",
        ),
        Figure(
            "fig14_elbow_paths",
            "VI",
            ("elbow",),
            "elbow_paths",
            "Fig. 14: elbow paths until the contact",
        ),
        Figure(
            "inference01_score_profiles",
            "inference",
            ("model_profiles", "elbow_force_profiles"),
            "score_profiles",
            "Identification: score along each unknown (the others refitted)",
        ),
        Figure(
            "inference02_claims_readings",
            "inference",
            ("robustness",),
            "claims_readings",
            "Robustness: each claim under each consistent reading",
        ),
        Figure(
            "study01_work_precision",
            "study",
            ("work_precision",),
            "work_precision",
            "Work-precision: error against cost per stroke",
        ),
        Figure(
            "study02_stability",
            "study",
            ("stability",),
            "stability",
            "Stability: isolated contact against stiffness",
        ),
        Figure(
            "study03_ladder",
            "study",
            ("ladder",),
            "ladder",
            "Model ladder: instantaneous impact vs spring contact",
        ),
    ]
}
