# `make demo` and `make test` set themselves up on a fresh machine (Python + apt only).
# Re-running them reuses the virtual environment: it is rebuilt only when pyproject.toml changes.

# PYTHON picks the interpreter (3.11 gets Drake 1.51, 3.12 and 3.13 the newest Drake); give
# each interpreter its own VENV, e.g. `make test PYTHON=python3.12 VENV=.venv-3.12`.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
PYTHON_VERSION := $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])')
STAMP := $(VENV)/.installed-$(PYTHON_VERSION)
DEMO_SCENARIO ?= coexistence

.PHONY: demo test lint format graphviz clean

demo: $(STAMP) graphviz
	$(BIN)/hrc-drake run $(DEMO_SCENARIO)

test: $(STAMP) graphviz lint
	$(BIN)/python -m pytest $(PYTEST_ARGS)

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

format: $(STAMP)
	$(BIN)/ruff format .
	$(BIN)/ruff check --fix .

$(STAMP): pyproject.toml
	@test -n "$(PYTHON_VERSION)" || { echo "no Python interpreter '$(PYTHON)'"; exit 1; }
	@if [ -x $(BIN)/python ] && [ "$$($(BIN)/python -c 'import sys; print("%d.%d" % sys.version_info[:2])')" \
	    != "$(PYTHON_VERSION)" ]; then \
	  echo "$(VENV) holds another Python than $(PYTHON) ($(PYTHON_VERSION)): rebuilding it"; rm -rf $(VENV); fi
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev,dist]'
	touch $(STAMP)

# Graphviz's `dot` renders system diagrams and trees; it comes from apt, not PyPI.
graphviz:
	@command -v dot >/dev/null 2>&1 || { \
	  if command -v apt-get >/dev/null 2>&1 && [ "$$(id -u)" = 0 ]; then \
	    apt-get update -qq && apt-get install -y -qq graphviz >/dev/null; \
	  elif command -v apt-get >/dev/null 2>&1 && sudo -n true 2>/dev/null; then \
	    sudo apt-get update -qq && sudo apt-get install -y -qq graphviz >/dev/null; \
	  else \
	    echo "Graphviz is missing: run 'sudo apt-get install graphviz'"; exit 1; \
	  fi; }

clean:
	rm -rf $(VENV) build dist *.egg-info runs
