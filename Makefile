# tactcad: `make export` and `make test` do all set-up on a fresh machine
# (Python 3.11 + pip): they create .venv with the pinned CAD stack first.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
DESIGN ?= hardware/macro_array.toml
OUT    ?= exports

.PHONY: help env export check test bench clean

help: ## list the targets
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | awk -F':.*## ' '{printf "  %-8s %s\n", $$1, $$2}'

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

env: $(STAMP) ## create .venv with the pinned CAD stack (build123d + cadquery on one OCP)

export: $(STAMP) ## build the default design (DESIGN=...) into exports/ (OUT=...)
	$(BIN)/tactcad export --design $(DESIGN) --out $(OUT)

check: $(STAMP) ## run the geometry, DXF and STEP checks on the design
	$(BIN)/tactcad check --design $(DESIGN)

test: $(STAMP) ## run the whole test suite
	$(BIN)/python -m pytest -q

bench: $(STAMP) ## print the speed/accuracy benchmarks
	$(BIN)/tactcad bench stiffness

clean: ## remove generated files (exports/) and the environment
	rm -rf $(OUT) $(VENV) .pytest_cache .hypothesis
