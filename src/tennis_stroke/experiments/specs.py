"""The one table of result files, by the key that claims (``config/claims.yaml``),
figures and the workflow use.  Pure data: the Snakefile imports it.
"""

from __future__ import annotations

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
