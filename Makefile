# tennis-stroke: everything installs into ./.venv from pyproject.toml; only python3 is needed.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
JOBS   ?= 2

.PHONY: install report test lint bench kernels clean

install: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test,workflow,slurm]'
	touch $(STAMP)

## The replication: every experiment, figure and claim, then report/index.html; fails
## when a claim marked `reproduce` in config/claims.yaml fails, or when README.md's
## results at a glance are stale (python tools/readme_results.py writes them).  Every
## result is named as a target, so one deleted by hand is rebuilt (src/tennis_stroke/
## pipeline/targets.py).
report: $(STAMP)
	$(BIN)/snakemake --cores $(JOBS) report $$($(BIN)/python -m tennis_stroke.pipeline.targets)
	$(BIN)/tennis-stroke claims results/claims.csv
	$(BIN)/python tools/readme_results.py --check

## The test suite (includes a tiny end-to-end workflow run).
test: $(STAMP)
	$(BIN)/python -m pytest

lint: $(STAMP)
	$(BIN)/ruff check src tests tools benchmarks workflow/scripts
	$(BIN)/snakefmt --check Snakefile workflow/rules
	$(BIN)/python tools/generate_kernels.py --check

## Speed and accuracy against solve_ivp (see benchmarks/bench_sweep.py).
bench: $(STAMP)
	$(BIN)/python benchmarks/bench_sweep.py

## Regenerate the unrolled Runge-Kutta kernels from the tableaux.
kernels: $(STAMP)
	$(BIN)/python tools/generate_kernels.py

clean:
	rm -rf results report .snakemake
