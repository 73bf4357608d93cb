# Plotting rules: separate from the simulations, so restyling never re-simulates.  A
# figure's registry entry is a param of its job (not the registry as code), so adding or
# editing one figure reruns that figure only.


# A figure of the paper's run, or of a scenario's (one of the paper's figures: drawn from
# the scenario's files where it changes them, from the paper's elsewhere; its title says
# what the scenario changes).
rule figure:
    input:
        RUNS.figure_inputs,
        lambda w: CODE.drawing(FIGURES[w.name].draw),
    output:
        report(
            "results/{run}figures/{name}.png",
            caption="../report/figure.rst",
            category="Figures",
        ),
    log:
        "logs/{run}figure_{name}.log",
    benchmark:
        "logs/benchmarks/{run}figure_{name}.tsv"
    wildcard_constraints:
        name="(fig|study|inference|ladder)[0-9][0-9]_[A-Za-z0-9_.]+",
    resources:
        **LIGHT,
    params:
        figure=RUNS.figure_entry,
        marks=RUNS.figure_marks,
        note=RUNS.figure_note,
    script:
        "../scripts/figure.py"


# A scenario's figure read against the paper's: the figure from the paper's files and
# from the scenario's on shared scales, and their difference (scenario minus paper), in
# one image for the scenario's page.
rule scenario_comparison:
    input:
        paper=RUNS.paper_figure_inputs,
        scenario=RUNS.figure_inputs,
        code=lambda w: CODE.drawing(FIGURES[w.name].draw, "compare.py"),
    output:
        "results/scenarios/{scenario}/compare/{name}.png",
    log:
        "logs/scenarios/{scenario}/compare_{name}.log",
    benchmark:
        "logs/benchmarks/scenarios/{scenario}/compare_{name}.tsv"
    wildcard_constraints:
        name="|".join(PAPER_FIGURES),
    resources:
        **LIGHT,
    params:
        figure=RUNS.figure_entry,
        marks=RUNS.figure_marks,
        note=RUNS.figure_note,
    script:
        "../scripts/compare.py"
