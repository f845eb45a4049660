# tactcad: `make export` and `make test` do all set-up on a fresh machine
# (Python 3.11 to 3.13 + pip): they create .venv with the pinned CAD stack first.
# `./tactcad ...` runs the command line from that .venv (and sets it up if needed).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
DESIGN ?= hardware/macro_array/macro_array.toml
OUT    ?= exports

.PHONY: help env lower-bounds typecheck vendor-three system-deps export docs docs-images check ci-example test test-deep test-fast bench-tests bench fuzz clean

help: ## list the targets
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | awk -F':.*## ' '{printf "  %-12s %s\n", $$1, $$2}'

# the ranges of pyproject.toml, at the exact versions of constraints.txt
$(STAMP): pyproject.toml constraints.txt
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -c constraints.txt -e ".[test,docs]"
	touch $(STAMP)

env: $(STAMP) ## create .venv with the pinned CAD stack (build123d + cadquery on one OCP)

lower-bounds: ## install the lowest versions pyproject.toml allows into a throwaway venv and run the fast mechanics tests there
	sh scripts/check_lower_bounds.sh $(PYTHON)

typecheck: $(STAMP) ## mypy over the public API (tactcad, tactcad.api, tactcad.errors)
	$(BIN)/python -m mypy

vendor-three: $(STAMP) ## refresh src/tactcad/data/three from the npm release web/package-lock.json pins (needs npm)
	$(BIN)/python scripts/vendor_three.py

export: $(STAMP) ## build the default design (DESIGN=...) into exports/ (OUT=...)
	$(BIN)/tactcad export --design $(DESIGN) --out $(OUT)

# Sphinx, every warning an error; no network: the equations are MathML written at build time
DOCS_OUT ?= docs/_build/html
docs: $(STAMP) ## build the documentation site (docs/) into docs/_build/html; open its index.html
	$(BIN)/python -m sphinx -W --keep-going -q -b html docs $(DOCS_OUT)

docs-images: export ## refresh the pictures of README and the docs (docs/images) from the export: images, drawing sheets, review page, the paper's plots
	$(BIN)/python scripts/docs_images.py $(OUT) --review

check: $(STAMP) ## run the checks on exports/ (reused as it is after `make export`)
	$(BIN)/tactcad check --design $(DESIGN) --out $(OUT)

CI_OUT ?= ci-example
ci-example: $(STAMP) ## the steps of the CI workflow `tactcad new` writes, here: export, check --junit, diff against HEAD (into ci-example/)
	rm -rf $(CI_OUT)/base $(CI_OUT)/diff && mkdir -p $(CI_OUT)/base
	$(BIN)/tactcad export --design $(DESIGN) --out $(CI_OUT)/exports
	$(BIN)/tactcad check --design $(DESIGN) --out $(CI_OUT)/exports --junit $(CI_OUT)/check-report.xml --failures-only
	git archive HEAD $(dir $(DESIGN)) | tar -x -C $(CI_OUT)/base
	$(BIN)/tactcad diff $(CI_OUT)/base/$(DESIGN) $(CI_OUT)/exports --out $(CI_OUT)/diff || [ $$? -eq 1 ]

# pytest-xdist processes, one per core (0: all in this process); the tests that
# drive Chromium or the FreeCAD GUI share one process (xdist_group "browser",
# tests/conftest.py), so two browsers never run at once
FAST_JOBS ?= auto
TEST_JOBS ?= auto
XDIST = --dist loadgroup
# one single-threaded process per core: BLAS threads of two workers on two cores
# only contend (about 6 % of the suite's time)
ONE_THREAD = OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
# Python's bytecode cache on: a shell that sets PYTHONDONTWRITEBYTECODE would make every
# pytest worker and every command a test starts compile the sources again (collection
# alone took 28 CPU s a worker without the cache, 11 s with it)
unexport PYTHONDONTWRITEBYTECODE

system-deps: ## install the system packages the tests need (FreeCAD's freecadcmd, via apt as root)
	@sh scripts/install-system-deps.sh

test: $(STAMP) system-deps ## run the whole test suite (FreeCAD review included; one process per core, TEST_JOBS=0 for one; lists every test over 5 s)
	$(ONE_THREAD) $(BIN)/python -m pytest -q -n $(TEST_JOBS) $(XDIST) --durations=0 --durations-min=5

test-deep: $(STAMP) system-deps ## make test with every random design the property tests were written with (30 exported, 30 designed; nightly or before a release)
	TACTCAD_TEST_DEPTH=deep $(ONE_THREAD) $(BIN)/python -m pytest -q -n $(TEST_JOBS) $(XDIST)

test-fast: $(STAMP) ## the inner loop: every test not marked slow (no full export, no FreeCAD, no fem3d)
	$(ONE_THREAD) $(BIN)/python -m pytest -q -n $(FAST_JOBS) $(XDIST) -m "not slow"

bench-tests: $(STAMP) system-deps ## time make test-fast and make test (wall seconds, test counts, cores, load)
	$(BIN)/python scripts/bench_tests.py --fast-jobs $(FAST_JOBS) --test-jobs $(TEST_JOBS)

FUZZ_N ?= 1000
FUZZ_DATA ?= $(FUZZ_N)
FUZZ_OPTIONS ?= 300
fuzz: $(STAMP) ## random designs (FUZZ_N=1000), calibration data files (FUZZ_DATA=FUZZ_N) and command lines (FUZZ_OPTIONS=300); prints the counts
	$(BIN)/python scripts/fuzz.py -n $(FUZZ_N) --quiet; \
	  a=$$?; $(BIN)/python scripts/fuzz_inputs.py --data $(FUZZ_DATA) --options $(FUZZ_OPTIONS) --quiet; \
	  b=$$?; exit $$(( a || b ))

bench: $(STAMP) ## print the speed/accuracy benchmarks (export speed, stiffness and modal ladders)
	$(BIN)/tactcad bench export
	$(BIN)/tactcad bench stiffness
	$(BIN)/tactcad bench modal

clean: ## remove generated files (exports/) and the environment
	rm -rf $(OUT) $(VENV) .pytest_cache .hypothesis .tactcad-cache $(CI_OUT) docs/_build docs/_generated
