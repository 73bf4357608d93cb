# Claims, assumption ledger and the HTML report.


rule claims:
    input:
        **PAPER_RESULTS,
        claims="config/claims.yaml",
        readings="config/readings.yaml",
        robustness=RESULT_FILES["robustness"],
        code=code_inputs("claims.py"),
    output:
        report("results/claims.csv", caption="../report/claims.rst", category="Claims"),
    log:
        "logs/claims.log",
    benchmark:
        "benchmarks/workflow/claims.tsv"
    threads: 1
    params:
        files=PAPER_RESULTS,
        experiments=paper_experiments(),
        common=common_params(),
    script:
        "../scripts/claims.py"


rule report:
    input:
        figures=expand("results/figures/{name}.png", name=sorted(FIGURES)),
        claims="results/claims.csv",
        statements="config/claims.yaml",
        inference=list(INFERENCE_RESULTS.values()),
        results=list(PAPER_RESULTS.values()),
        code=code_inputs("report.py"),
        # the page's template is code of the report too (not a module: no import edge)
        template=checkout_path(
            PACKAGE_DIR / "replication" / "templates" / "report.html.j2"
        ),
        assumptions=checkout_path(Path(workflow.basedir) / "docs" / "assumptions.md"),
        studies=[RESULT_FILES[k] for k in ("ladder", "optimum_cost", "stability")],
    output:
        "report/index.html",
    log:
        "logs/report.log",
    params:
        config=config,
        benchmarks="benchmarks/workflow",
    script:
        "../scripts/report.py"
