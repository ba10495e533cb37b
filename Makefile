# The two commands: `make report` and `make test`. Both set up .venv first.
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin

.PHONY: report test benchmark clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# a regular (not editable) install: setuptools warns on every editable install of a
# flat layout; the install is redone whenever a source or catalog file changes, and the
# tests import the source tree itself (pytest puts the checkout first on the path)
SOURCES := $(shell find chaingraph catalog -name '*.py' -o -name '*.toml' -o -name '*.css' -o -name '*.js')

$(VENV)/.installed: pyproject.toml $(SOURCES) | $(BIN)/python
	$(BIN)/python -m pip install --quiet .
	touch $@

$(VENV)/.installed-test: pyproject.toml $(VENV)/.installed
	$(BIN)/python -m pip install --quiet ".[test]"
	touch $@

report: $(VENV)/.installed
	$(BIN)/chaingraph report catalog -o report

# the layers first (import-linter, contract in pyproject.toml), then the types (mypy, its
# settings in pyproject.toml) beside the whole suite on both cores (pytest-xdist; a
# file's tests on one worker, so its fixtures are built once; the files in the order
# tests/conftest.py gives, the longest first, not xdist's order by number of tests);
# either failing fails the target (mypy's report is printed after the suite's)
test: $(VENV)/.installed-test
	$(BIN)/lint-imports --no-cache
	@$(BIN)/python -m mypy chaingraph > .mypy-report 2>&1 & types=$$!; \
	$(BIN)/python -m pytest -n 2 --dist loadfile --no-loadscope-reorder; suite=$$?; \
	wait $$types; checked=$$?; cat .mypy-report; rm -f .mypy-report; \
	if [ $$checked -ne 0 ]; then echo "mypy found errors (above)"; exit $$checked; fi; \
	exit $$suite

benchmark: $(VENV)/.installed
	$(BIN)/python benchmarks/classify.py

clean:
	rm -rf $(VENV) report .pytest_cache .hypothesis .mypy_cache
