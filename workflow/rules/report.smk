# Claims, assumption ledger and the HTML report.

CLAIM_FILES = {
    "fig2": "results/angle_maps/L1_0.3.nc",
    "fig3": "results/angle_maps/L1_0.4.nc",
    "fig4": "results/strokes/fig4.nc",
    "ml": "results/mass_length/map.nc",
    "fig7": "results/torque_delay/fig7.nc",
    "fig8": "results/torque_delay/fig8.nc",
    "fig9": "results/torque_delay/fig9.nc",
    "delay": "results/strokes/delay.nc",
    "elbow_map": "results/elbow_force/map.nc",
    "elbow": "results/strokes/elbow_force.nc",
}


rule claims:
    input:
        **CLAIM_FILES,
        claims="config/claims.yaml",
        code=sources("replication/claims.py"),
    output:
        report("results/claims.csv", caption="../report/claims.rst", category="Claims"),
    log:
        "logs/claims.log",
    params:
        files=CLAIM_FILES,
    script:
        "../scripts/claims.py"


rule report:
    input:
        figures=expand("results/figures/{name}.png", name=sorted(FIGURES)),
        claims="results/claims.csv",
        readings="results/identification/readings.csv",
        results=list(CLAIM_FILES.values()),
        code=sources("replication/report.py"),
        assumptions=str(Path(workflow.basedir) / "docs" / "assumptions.md"),
        studies=[
            "results/solver_study/ladder.nc",
            "results/solver_study/optimum_cost.nc",
            "results/solver_study/stability.nc",
        ],
    output:
        "report/index.html",
    log:
        "logs/report.log",
    params:
        config=config,
        benchmarks="benchmarks/workflow",
    script:
        "../scripts/report.py"
