# Plotting rules: separate from the simulations, so restyling never re-simulates.


rule figure:
    input:
        figure_inputs,
        code_inputs("figure.py"),
    output:
        report(
            "results/figures/{name}.png",
            caption="../report/figure.rst",
            category="Figures",
        ),
    log:
        "logs/figure_{name}.log",
    wildcard_constraints:
        name="(fig|study|inference|ladder)[0-9][0-9]_[A-Za-z0-9_.]+",
    script:
        "../scripts/figure.py"
