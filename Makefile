# tennis-stroke: everything installs into ./.venv from the lock; only python3 is needed.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
JOBS   ?= 2
## The lock: every package the three extras install, exact versions with hashes, for
## CPython 3.11 on Linux x86_64 (make lock writes it from pyproject.toml with uv).
LOCK   := requirements.lock
UV     := uv==0.13.9
LOCKER := .venv-lock

.PHONY: install lock report test check lint api bench kernels clean

## The environment itself is checked at every use (make install, and before report, test
## and check), not only the stamp: a distribution of the lock missing or at another
## version, the project not importable or .venv/bin/python gone installs the lock again
## (tools/lock_check.py --installed: one line naming what differs).
install: $(STAMP)
	@if ! test -x $(BIN)/python; then echo "make install: $(BIN)/python is missing"; fi
	@if ! { test -x $(BIN)/python && $(BIN)/python tools/lock_check.py --installed; }; then \
	    echo "make install: installing the lock again"; rm -f $(STAMP); \
	    $(MAKE) --no-print-directory $(STAMP) && $(BIN)/python tools/lock_check.py --installed; \
	fi

## Exactly the lock (hashes checked), then the project itself without dependencies; first
## one line and nothing installed if pyproject.toml's dependencies changed after the lock.
$(STAMP): pyproject.toml $(LOCK)
	$(PYTHON) tools/lock_check.py
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --require-hashes --no-deps -r $(LOCK)
	$(BIN)/python -m pip install --quiet --no-deps --no-build-isolation -e .
	touch $(STAMP)

## Regenerate the lock from pyproject.toml: the locked versions are kept where they still
## fit (UPGRADE=1: the newest that fit).  uv runs from its own venv, not the project's.
lock:
	test -x $(LOCKER)/bin/uv || { $(PYTHON) -m venv $(LOCKER) && $(LOCKER)/bin/pip install --quiet '$(UV)'; }
	$(LOCKER)/bin/uv pip compile pyproject.toml --extra test --extra workflow --extra slurm \
	    --generate-hashes --python-version 3.11 --python-platform x86_64-manylinux_2_28 \
	    --custom-compile-command "make lock" $(if $(UPGRADE),--upgrade) -o $(LOCK)
	$(PYTHON) tools/lock_check.py --write

## The replication: every experiment, figure and claim, then report/index.html; fails
## when a claim marked `reproduce` in config/claims.yaml fails, or when the results that
## README.md, docs/inference.md and docs/assumptions.md quote are stale
## (python tools/readme_results.py writes them).  The
## target rule report names every result as an input, so one deleted by hand is rebuilt
## (docs/workflow.md, "Failing safe").
## Jobs an interrupted run left incomplete run again (--rerun-incomplete; a run still
## active in this folder is named before anything starts: docs/workflow.md, "Failing
## safe"); a cache folder that cannot be used is one line (tools/cache_check.py).
report: install
	@$(BIN)/python tools/cache_check.py
	$(BIN)/snakemake report --cores $(JOBS) --quiet rules --rerun-incomplete
	$(BIN)/tennis-stroke claims results/claims.csv --junit results/claims.xml
	$(BIN)/python tools/readme_results.py --check

## The test suite on every core (pytest-xdist; the tiny workflow run and the SLURM runs
## are built once for all workers; tests sent to a worker one at a time, --maxschedchunk
## 1: xdist's default sends the first quarter of the tests, all the long ones, to one
## worker, and the other sat idle for the last 70 % of the run), the 25 slowest named at
## the end: every test,
## including a tiny end-to-end workflow run, the browser, compile and SLURM tests
## (docs/testing.md).
test: install
	$(BIN)/python -m pytest -n $(JOBS) --maxschedchunk 1 --durations=25

## The fast tier while editing: every test that runs in the test's own process (no
## workflow run, browser, SLURM, cold compile, signal or process of its own: pytest -m
## "not slow"), on every core.
check: install
	$(BIN)/python -m pytest -n $(JOBS) --maxschedchunk 1 --durations=10 -m "not slow"

lint: install
	$(BIN)/check-jsonschema --builtin-schema vendor.github-workflows .github/workflows/replication.yml
	$(BIN)/python tools/citation_check.py
	$(BIN)/ruff check src tests tools benchmarks examples workflow/scripts
	$(BIN)/snakefmt --check workflow/Snakefile workflow/rules
	$(BIN)/python tools/generate_kernels.py --check

## The API reference of the public modules, from their docstrings (pdoc), into
## docs/api/ (generated, not in git); fails on a broken cross-reference or a pdoc warning.
api: $(STAMP)
	$(BIN)/python tools/api_reference.py docs/api

## Speed and accuracy against solve_ivp (see benchmarks/bench_sweep.py).
bench: install
	$(BIN)/python benchmarks/bench_sweep.py

## Regenerate the unrolled Runge-Kutta kernels from the tableaux.
kernels: install
	$(BIN)/python tools/generate_kernels.py

clean:
	rm -rf results report logs .snakemake docs/api benchmarks/workflow
