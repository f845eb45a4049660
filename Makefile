# tactcad: `make export` and `make test` do all set-up on a fresh machine
# (Python 3.11 + pip): they create .venv with the pinned CAD stack first.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
DESIGN ?= hardware/macro_array.toml
OUT    ?= exports

.PHONY: help env system-deps export docs-images check test bench fuzz clean

help: ## list the targets
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | awk -F':.*## ' '{printf "  %-12s %s\n", $$1, $$2}'

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $(STAMP)

env: $(STAMP) ## create .venv with the pinned CAD stack (build123d + cadquery on one OCP)

export: $(STAMP) ## build the default design (DESIGN=...) into exports/ (OUT=...)
	$(BIN)/tactcad export --design $(DESIGN) --out $(OUT)

docs-images: export ## refresh README's pictures (docs/images) from exports/images
	cp $(OUT)/images/array.png $(OUT)/images/element_a4mm_drawing.png docs/images/

check: $(STAMP) ## run the geometry, DXF and STEP checks on the design
	$(BIN)/tactcad check --design $(DESIGN)

system-deps: ## install the system packages the tests need (FreeCAD's freecadcmd, via apt as root)
	@sh scripts/install-system-deps.sh

test: $(STAMP) system-deps ## run the whole test suite (FreeCAD review included)
	$(BIN)/python -m pytest -q

FUZZ_N ?= 1000
fuzz: $(STAMP) ## random designs end to end (FUZZ_N=1000): validate, build, assemble, check; prints a summary
	$(BIN)/python scripts/fuzz.py -n $(FUZZ_N) --quiet

bench: $(STAMP) ## print the speed/accuracy benchmarks (export speed, stiffness ladder)
	$(BIN)/tactcad bench export
	$(BIN)/tactcad bench stiffness

clean: ## remove generated files (exports/) and the environment
	rm -rf $(OUT) $(VENV) .pytest_cache .hypothesis
