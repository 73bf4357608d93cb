# Simulation rules: one job per experiment (per chunk for the maps), each writing one
# netCDF file.  Threads, memory and runtime are resources: `--set-threads` or a profile
# (profiles/slurm) changes them, never the science config.


rule angle_map:
    input:
        SIMULATION_SOURCES,
    output:
        "results/chunks/angle_maps/{fig}/{chunk}-of-{chunks}.nc",
    log:
        "logs/angle_map/{fig}/{chunk}-of-{chunks}.log",
    benchmark:
        "benchmarks/workflow/angle_map_{fig}_{chunk}-of-{chunks}.tsv"
    wildcard_constraints:
        fig="fig[23]",
    threads: 1
    params:
        common=common_params(),
        L1=angle_map_L1,
        theta0=grid_spec(config["angle_maps"]["theta0"]),
        delta0=grid_spec(config["angle_maps"]["delta0"]),
    script:
        "../scripts/angle_map.py"


rule gather_map:
    input:
        chunks=chunk_files,
        code=sources("pipeline", "io", "experiments/grids.py"),
    output:
        "results/{map}.nc",
    log:
        "logs/gather_map/{map}.log",
    wildcard_constraints:
        map=CHUNKED_MAPS,
    params:
        max_failure_share=config["max_failure_share"],
    script:
        "../scripts/gather_map.py"


rule fig4_strokes:
    input:
        SIMULATION_SOURCES,
    output:
        RESULT_FILES["fig4"],
    log:
        "logs/fig4_strokes.log",
    benchmark:
        "benchmarks/workflow/fig4_strokes.tsv"
    threads: 1
    params:
        common=common_params(),
        strokes=[list(map(float, s)) for s in config["fig4"]["strokes"]],
        curves=config["figure_curves"],
        t_end=config["fig4"]["t_end"],
        samples=config["fig4"]["samples"],
    script:
        "../scripts/fig4_strokes.py"


rule k_sensitivity:
    input:
        SIMULATION_SOURCES,
    output:
        RESULT_FILES["k_sensitivity"],
    log:
        "logs/k_sensitivity.log",
    benchmark:
        "benchmarks/workflow/k_sensitivity.tsv"
    threads: 1
    params:
        common=common_params(),
        strokes=[list(map(float, s)) for s in config["fig4"]["strokes"]],
        k_contact=config["k_sensitivity"]["k_contact"],
        points=config["k_sensitivity"]["points"],
    script:
        "../scripts/k_sensitivity.py"


rule mass_length:
    input:
        SIMULATION_SOURCES,
    output:
        "results/chunks/mass_length/map/{chunk}-of-{chunks}.nc",
    log:
        "logs/mass_length/{chunk}-of-{chunks}.log",
    benchmark:
        "benchmarks/workflow/mass_length_{chunk}-of-{chunks}.tsv"
    threads: 1
    params:
        common=common_params(),
        M2=grid_spec(config["mass_length"]["M2"]),
        L1=grid_spec(config["mass_length"]["L1"]),
        theta0_range=config["mass_length"]["theta0_range"],
        delta0_range=config["mass_length"]["delta0_range"],
        coarse_step=config["mass_length"]["coarse_step"],
        fine_step=config["mass_length"]["fine_step"],
    script:
        "../scripts/mass_length.py"


rule delay_map:
    input:
        SIMULATION_SOURCES,
    output:
        "results/chunks/torque_delay/{fig}/{chunk}-of-{chunks}.nc",
    log:
        "logs/delay_map/{fig}/{chunk}-of-{chunks}.log",
    benchmark:
        "benchmarks/workflow/delay_map_{fig}_{chunk}-of-{chunks}.tsv"
    wildcard_constraints:
        fig="fig[789]",
    threads: 1
    params:
        common=common_params(),
        section=delay_section,
    script:
        "../scripts/delay_map.py"


rule delay_strokes:
    input:
        SIMULATION_SOURCES,
    output:
        RESULT_FILES["delay"],
    log:
        "logs/delay_strokes.log",
    benchmark:
        "benchmarks/workflow/delay_strokes.tsv"
    threads: 1
    params:
        common=common_params(),
        stroke=delay_stroke(),
        curves=config["figure_curves"],
    script:
        "../scripts/delay_strokes.py"


rule elbow_force_map:
    input:
        SIMULATION_SOURCES,
    output:
        "results/chunks/elbow_force/map/{chunk}-of-{chunks}.nc",
    log:
        "logs/elbow_force_map/{chunk}-of-{chunks}.log",
    benchmark:
        "benchmarks/workflow/elbow_force_map_{chunk}-of-{chunks}.tsv"
    threads: 1
    params:
        common=common_params(),
        force={k: config["elbow_force"][k] for k in ("F0", "t_d")},
        psi_F=grid_spec(config["elbow_force"]["psi_F"]),
        tau_F=grid_spec(config["elbow_force"]["tau_F"]),
        stroke=delay_stroke(),
    script:
        "../scripts/elbow_force_map.py"


rule elbow_force_strokes:
    input:
        SIMULATION_SOURCES,
    output:
        RESULT_FILES["elbow"],
    log:
        "logs/elbow_force_strokes.log",
    benchmark:
        "benchmarks/workflow/elbow_force_strokes.tsv"
    threads: 1
    params:
        common=common_params(),
        force={
            k: config["elbow_force"][k]
            for k in ("F0", "t_d", "table1_psi", "table1_tau_F")
        },
        stroke=delay_stroke(),
        curves=config["figure_curves"],
    script:
        "../scripts/elbow_force_strokes.py"


rule identification:
    input:
        INFERENCE_SOURCES,
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        **IDENTIFICATION_FILES,
    log:
        "logs/identification.log",
    benchmark:
        "benchmarks/workflow/identification.tsv"
    threads: 1
    params:
        common=common_params(),
        fig4_strokes=[list(map(float, s)) for s in config["fig4"]["strokes"]],
        force={
            k: config["elbow_force"][k]
            for k in ("F0", "t_d", "table1_psi", "table1_tau_F")
        },
        stroke=delay_stroke(),
    script:
        "../scripts/identification.py"


rule robustness_screen:
    input:
        INFERENCE_SOURCES,
        claims="config/claims.yaml",
        readings="config/readings.yaml",
        model_fits=IDENTIFICATION_FILES["model_fits"],
        elbow_force_fits=IDENTIFICATION_FILES["elbow_force_fits"],
    output:
        screen=RESULT_FILES["robustness_screen"],
        readings=RESULT_FILES["robustness_readings"],
    log:
        "logs/robustness_screen.log",
    benchmark:
        "benchmarks/workflow/robustness_screen.tsv"
    threads: 1
    params:
        common=common_params(),
        fig4_strokes=[list(map(float, s)) for s in config["fig4"]["strokes"]],
        force={
            k: config["elbow_force"][k]
            for k in ("F0", "t_d", "table1_psi", "table1_tau_F")
        },
        stroke=delay_stroke(),
    script:
        "../scripts/robustness_screen.py"


rule robustness_chunk:
    input:
        INFERENCE_SOURCES,
        kept=RESULT_FILES["robustness_readings"],
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        "results/chunks/robustness/claims/{chunk}-of-{chunks}.nc",
    log:
        "logs/robustness_chunk/{chunk}-of-{chunks}.log",
    benchmark:
        "benchmarks/workflow/robustness_chunk_{chunk}-of-{chunks}.tsv"
    threads: 1
    params:
        common=common_params(),
        experiments=paper_experiments(),
    script:
        "../scripts/robustness_chunk.py"


rule work_precision:
    input:
        STUDY_SOURCES,
    output:
        RESULT_FILES["work_precision"],
    log:
        "logs/work_precision.log",
    benchmark:
        "benchmarks/workflow/work_precision.tsv"
    threads: 1
    params:
        common=common_params(),
        study=work_precision_study(),
    script:
        "../scripts/work_precision.py"


rule stability:
    input:
        STUDY_SOURCES,
    output:
        RESULT_FILES["stability"],
    log:
        "logs/stability.log",
    benchmark:
        "benchmarks/workflow/stability.tsv"
    threads: 1
    params:
        common=common_params(),
        stability=config["solver_study"]["stability"],
    script:
        "../scripts/stability.py"


rule model_ladder:
    input:
        STUDY_SOURCES,
    output:
        ladder=RESULT_FILES["ladder"],
        optimum=RESULT_FILES["optimum_cost"],
    log:
        "logs/model_ladder.log",
    benchmark:
        "benchmarks/workflow/model_ladder.tsv"
    threads: 1
    params:
        common=common_params(),
        strokes=config["solver_study"]["strokes"],
        seed=config["solver_study"]["seed"],
        optimum=config["solver_study"]["optimum"],
    script:
        "../scripts/model_ladder.py"
