# Two commands a fresh machine (python3 + pip) needs: `make demo` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin

.PHONY: demo test docs docs-update bench install clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

# Reinstall when pyproject.toml changes.
$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e '.[test,plot,sensitivity,dask]'
	touch $@ $(VENV)/.installed

install: $(VENV)/.installed

demo: $(VENV)/.installed
	$(BIN)/mdcalc hoist cases/hoist/crane.toml

test: $(VENV)/.installed-test
	$(BIN)/ruff check mdcalc tests bench
	$(BIN)/ruff format --check mdcalc tests bench
	$(BIN)/mypy mdcalc  # the API (mdcalc/__init__.py, mdcalc/api) strict: pyproject.toml
	$(BIN)/pytest -n auto --maxprocesses 4  # one worker per core (CI: 2), at most 4
	$(BIN)/mdcalc check cases --jobs 0

$(VENV)/.installed-docs: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e '.[docs]'
	touch $@

# The documentation site (docs/, mkdocs.yml) into site/; a warning is an error.
docs: $(VENV)/.installed-docs
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --quiet

# Rewrite the console examples' outputs in README.md and docs/ from the program (review
# with git diff); `make test` checks them.
docs-update: $(VENV)/.installed-test
	MDCALC_DOCS_UPDATE=1 $(BIN)/pytest -q -p no:randomly tests/test_docs.py

# Figures for the performance page (docs/performance.md); not part of `make test` (timings
# are printed, never asserted). `make bench AGAINST=../old-checkout` also compares the
# start-up of every problem with another checkout, in the same run.
bench: $(VENV)/.installed-test
	$(BIN)/python bench/bench.py $(if $(AGAINST),--against $(AGAINST))

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .mypy_cache .ruff_cache
