# Simulation rules: one job per file of a row of the table of experiments
# (tennis_stroke.experiments.specs.EXPERIMENTS, the {stem} of its file), per chunk for
# the maps, each writing one netCDF file, for the paper's configuration (run "": under
# results/) or a what-if scenario's (run "scenarios/NAME/", config/scenarios.yaml: under
# results/scenarios/NAME/, its params from the scenario's configuration,
# tennis_stroke.pipeline.scenarios).  A job's params are the config values its row reads
# (and the model and solver settings for a model row): changing any other key reruns
# nothing of it.  Its code inputs are the modules its job imports.  Each job asks for
# memory and time from its points (tennis_stroke.pipeline.resources): a cluster enforces
# them, `--resources mem_mb=...` bounds a machine; `--set-threads`, `--set-resources` or
# a profile (profiles/slurm) changes them, never the science config.
#
# The robustness analysis is the report's longest chain of jobs (identification ->
# screen -> chunks -> claims), so its jobs go first when they are ready, and the
# validation jobs after them; the other jobs fill the cores around them.  A priority
# orders ready jobs only: it changes no result.  Every job takes one thread: a job of
# two waits for both cores of a 2-core machine to be free at once, which the jobs
# around it seldom leave (the screen, at two threads, started 60 s after its input).

CHAIN_PRIORITY = 20


rule simulate:
    input:
        code=lambda w: CODE.simulation(ROWS[w.stem]),
    output:
        "results/{run}{stem}.nc",
    log:
        "logs/{run}{stem}.log",
    benchmark:
        "logs/benchmarks/{run}{stem}.tsv"
    wildcard_constraints:
        stem=stems(chunked=False, family="paper"),
    threads: 1
    resources:
        mem_mb=RUNS.row_resources("mem_mb"),
        runtime=RUNS.row_resources("runtime"),
    params:
        experiment=RUNS.row_param("experiment"),
        args=RUNS.row_param("args"),
        common=RUNS.row_param("common"),
    script:
        "../scripts/simulate.py"


# The solver studies: the paper's configuration only (a scenario changes the paper's
# experiments), each one file.
rule study:
    input:
        code=lambda w: CODE.simulation(ROWS[w.stem]),
    output:
        "results/{stem}.nc",
    log:
        "logs/{stem}.log",
    benchmark:
        "logs/benchmarks/{stem}.tsv"
    wildcard_constraints:
        stem=stems(chunked=False, family="study"),
    threads: 1
    resources:
        mem_mb=RUNS.row_resources("mem_mb"),
        runtime=RUNS.row_resources("runtime"),
    params:
        experiment=RUNS.row_param("experiment"),
        args=RUNS.row_param("args"),
        common=RUNS.row_param("common"),
    script:
        "../scripts/simulate.py"


rule simulate_chunk:
    input:
        code=lambda w: CODE.simulation(ROWS[w.stem]),
    output:
        "results/{run}chunks/{stem}/{chunk}-of-{chunks}.nc",
    log:
        "logs/{run}{stem}/{chunk}-of-{chunks}.log",
    benchmark:
        "logs/benchmarks/{run}{stem}_{chunk}-of-{chunks}.tsv"
    wildcard_constraints:
        stem=stems(chunked=True),
    threads: 1
    resources:
        mem_mb=RUNS.row_resources("mem_mb"),
        runtime=RUNS.row_resources("runtime"),
    params:
        experiment=RUNS.row_param("experiment"),
        args=RUNS.row_param("args"),
        common=RUNS.row_param("common"),
    script:
        "../scripts/simulate.py"


rule gather_map:
    input:
        chunks=RUNS.chunk_files,
        code=CODE("gather_map.py", labels=True),
    output:
        "results/{run}{map}.nc",
    log:
        "logs/{run}gather_map/{map}.log",
    benchmark:
        "logs/benchmarks/{run}gather_map/{map}.tsv"
    wildcard_constraints:
        map=CHUNKED_MAPS,
    resources:
        mem_mb=RUNS.map_resources("mem_mb"),
        runtime=RUNS.map_resources("runtime"),
    params:
        max_failure_share=lambda w: RUNS.configuration(w)["max_failure_share"],
        relabel=lambda w: w.map in CHUNKED,  # a map of the table: its labels again
    script:
        "../scripts/gather_map.py"


rule identification:
    input:
        code=CODE("identification.py"),
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        **IDENTIFICATION_FILES,
    log:
        "logs/identification.log",
    benchmark:
        "logs/benchmarks/identification.tsv"
    priority: CHAIN_PRIORITY
    threads: 1
    resources:
        mem_mb=RUNS.search_resources("mem_mb"),
        runtime=RUNS.search_resources("runtime"),
    params:
        **fit_set_arguments(config),
        common=job_params.common_params(config),
    script:
        "../scripts/identification.py"


rule robustness_screen:
    input:
        code=CODE("robustness_screen.py"),
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
        "logs/benchmarks/robustness_screen.tsv"
    priority: CHAIN_PRIORITY
    threads: 1
    resources:
        mem_mb=RUNS.search_resources("mem_mb", lockstep=True),
        runtime=RUNS.search_resources("runtime", lockstep=True),
    params:
        **fit_set_arguments(config),
        common=job_params.common_params(config),
    script:
        "../scripts/robustness_screen.py"


rule robustness_chunk:
    input:
        code=CODE("robustness_chunk.py", *CODE.paper_modules),
        kept=RESULT_FILES["robustness_readings"],
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        "results/chunks/robustness/claims/{chunk}-of-{chunks}.nc",
    log:
        "logs/robustness_chunk/{chunk}-of-{chunks}.log",
    benchmark:
        "logs/benchmarks/robustness_chunk_{chunk}-of-{chunks}.tsv"
    priority: CHAIN_PRIORITY
    threads: 1
    resources:
        mem_mb=RUNS.search_resources("mem_mb", lockstep=True),
        runtime=RUNS.search_resources("runtime", lockstep=True),
    params:
        common=job_params.common_params(config),
        experiments=job_params.paper_experiments(config),
    script:
        "../scripts/robustness_chunk.py"


rule claims_validation:
    input:
        code=CODE("claims_validation.py"),
        kept=RESULT_FILES["robustness_readings"],
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        "results/robustness/validation/{group}.nc",
    log:
        "logs/claims_validation/{group}.log",
    benchmark:
        "logs/benchmarks/claims_validation_{group}.tsv"
    wildcard_constraints:
        group="|".join(VALIDATION_GROUPS),
    priority: CHAIN_PRIORITY // 2
    threads: 1
    resources:
        mem_mb=RUNS.search_resources("mem_mb"),
        runtime=RUNS.search_resources("runtime"),
    params:
        common=job_params.common_params(config),
        experiments=lambda w: job_params.group_config(config, w.group),
    script:
        "../scripts/claims_validation.py"


rule model_ladder:
    input:
        code=CODE("model_ladder.py"),
        claims="config/claims.yaml",
        readings="config/readings.yaml",
    output:
        RESULT_FILES["model_ladder"],
    log:
        "logs/model_ladder.log",
    benchmark:
        "logs/benchmarks/model_ladder.tsv"
    threads: 1
    resources:
        mem_mb=RUNS.search_resources("mem_mb"),
        runtime=RUNS.search_resources("runtime"),
    params:
        common=job_params.common_params(config),
        experiments=job_params.paper_experiments(config),
        figure_curves=config["figure_curves"],
        ladder=sorted_data(config["model_ladder"]),
    script:
        "../scripts/model_ladder.py"
