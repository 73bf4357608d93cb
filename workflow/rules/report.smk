# Claims, the HTML report and the article, of the paper's run and of a scenario's.


# The claims of a run: the paper's (with its robustness across the consistent readings)
# or a scenario's (the same evaluation under its configuration, from its files where it
# changes them and the paper's elsewhere; no robustness analysis: a scenario is an
# exploration, not graded).
rule claims:
    input:
        unpack(RUNS.claim_inputs),
        claims="config/claims.yaml",
        readings="config/readings.yaml",
        code=CODE("claims.py"),
    output:
        claims=report(
            "results/{run}claims.csv",
            caption="../report/claims.rst",
            category="Claims",
        ),
        configuration="results/{run}configuration.yaml",
    log:
        "logs/{run}claims.log",
    benchmark:
        "logs/benchmarks/{run}claims.tsv"
    threads: 1
    resources:
        **LIGHT,
    params:
        files=RUNS.files,
        experiments=lambda w: job_params.paper_experiments(RUNS.configuration(w)),
        common=lambda w: job_params.common_params(RUNS.configuration(w)),
        scenario=RUNS.record,
    script:
        "../scripts/claims.py"


# What users ask for: the page and every result (see rule all in the Snakefile).
rule report:
    input:
        targets(),
    resources:
        **LIGHT,


rule report_page:
    input:
        figures=expand("results/figures/{name}.png", name=sorted(FIGURES)),
        claims="results/claims.csv",
        configuration="results/configuration.yaml",
        statements="config/claims.yaml",
        inference=list(INFERENCE_RESULTS.values()),
        results=list(PAPER_RESULTS.values()),
        code=CODE("report.py"),
        # the page's template is code of the report too (not a module: no import edge)
        template=CODE.template("report.html.j2"),
        assumptions=CODE.checkout_file("docs", "assumptions.md"),
        studies=list(STUDY_RESULTS.values()),
    output:
        "report/index.html",
    log:
        "logs/report.log",
    benchmark:
        "logs/benchmarks/report_page.tsv"
    resources:
        **LIGHT,
    params:
        config=config,
        benchmarks="logs/benchmarks",
    script:
        "../scripts/report.py"


# A scenario's page: each of the paper's figures beside the scenario's where the
# scenario changes it, and every claim under both configurations (no scoreboard).  The
# paper configuration's figures and claims are shown when they exist (not inputs: a
# scenario never asks for the paper's whole run).
rule scenario_report:
    input:
        figures=RUNS.report_figures,
        claims="results/scenarios/{scenario}/claims.csv",
        configuration="results/scenarios/{scenario}/configuration.yaml",
        statements="config/claims.yaml",
        code=CODE("scenario_report.py"),
        template=CODE.template("scenario.html.j2"),
    output:
        "report/scenarios/{scenario}/index.html",
    log:
        "logs/scenarios/{scenario}/report.log",
    benchmark:
        "logs/benchmarks/scenarios/{scenario}/report_page.tsv"
    resources:
        **LIGHT,
    params:
        scenario=RUNS.record,
        figures=RUNS.figure_table,
    script:
        "../scripts/scenario_report.py"


# A scenario's file asked for under a name no scenario declares: one line naming the
# declared ones, before any job (Snakemake's own message for a target no rule makes is
# a traceback).
rule unknown_scenario:
    input:
        RUNS.refuse_unknown,
    output:
        "{top}/scenarios/{unknown}/{path}",
    wildcard_constraints:
        top="results|report",
        unknown=RUNS.unknown_pattern,
        path=".+",
    resources:
        **LIGHT,


# Before the rules that make any file of a run: a scenario's path they do not make for a
# scenario (a solver study, the robustness analysis) is refused in one line.
ruleorder: unknown_scenario_file > gather_map
ruleorder: unknown_scenario_file > figure
ruleorder: unknown_figure > figure


# A path no rule makes under a declared scenario (a study figure, a misspelt name): one
# line naming what a scenario makes.
rule unknown_scenario_file:
    input:
        RUNS.refuse_unknown_file,
    output:
        "{top}/scenarios/{declared}/{path}",
    wildcard_constraints:
        top="results|report",
        declared=RUNS.declared_names,
        path=UNKNOWN_SCENARIO_PATH,
    resources:
        **LIGHT,


# A figure the registry does not have (fig9.png for fig09_v_tau.png): one line naming the
# nearest figures.
rule unknown_figure:
    input:
        refuse_unknown_figure,
    output:
        "results/figures/{name}.png",
    wildcard_constraints:
        name=UNKNOWN_FIGURE,
    resources:
        **LIGHT,


# The replication as an article (ReScience C style) and its metadata, written from the
# results: every number read from the claims table, the figures and the files.
rule article:
    input:
        figures=expand("results/figures/{name}.png", name=PAPER_FIGURES),
        claims="results/claims.csv",
        statements="config/claims.yaml",
        results=list(PAPER_RESULTS.values()),
        work_precision=STUDY_RESULTS["work_precision"],
        code=CODE("article.py"),
        template=CODE.checkout_file(
            "src/tennis_stroke/replication/templates/article.typ"
        ),
        lock=CODE.checkout_file("requirements.lock"),
        pyproject=CODE.checkout_file("pyproject.toml"),
        # the authors, keywords and code URL (the article's byline and its metadata)
        citation=CODE.checkout_file("CITATION.cff"),
        # the equations it prints are read from this module's source, never imported
        equations=CODE.checkout_file("src/tennis_stroke/model/dynamics.py"),
    output:
        pdf="report/article.pdf",
        metadata="report/metadata.yaml",
    log:
        "logs/article.log",
    benchmark:
        "logs/benchmarks/article.tsv"
    resources:
        **LIGHT,
    params:
        benchmarks="logs/benchmarks",
    script:
        "../scripts/article.py"


# A scenario's article: an exploration beside the paper, never a replication (its
# changes, the figures it changes against the paper's, every claim under both).
rule scenario_article:
    input:
        comparisons=RUNS.comparisons,
        claims="results/scenarios/{scenario}/claims.csv",
        statements="config/claims.yaml",
        code=CODE("scenario_article.py"),
        template=CODE.checkout_file(
            "src/tennis_stroke/replication/templates/scenario_article.typ"
        ),
    output:
        "report/scenarios/{scenario}/article.pdf",
    log:
        "logs/scenarios/{scenario}/article.log",
    benchmark:
        "logs/benchmarks/scenarios/{scenario}/article.tsv"
    resources:
        **LIGHT,
    params:
        scenario=RUNS.record,
    script:
        "../scripts/scenario_article.py"
