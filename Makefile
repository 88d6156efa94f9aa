# Two commands for a fresh machine (see README):
#   make demo   set up .venv, derive the PUMA 560 and write its derivation to build/
#   make test   set up .venv and run the whole test suite
#   make notebooks [NB=notebooks/03_puma560.py]   rebuild notebooks from their .py sources
#   make docs   build the documentation site into build/docs (warnings are errors);
#               make docs VENV=/path/to/venv builds it with that environment as it is
# and, once set up:
#   make lab    JupyterLab on the course notebooks, from .venv
#   make shell  a shell with .venv activated (dhsym, jupyter, python on the PATH)
PYTHON ?= python3
DEFAULT_VENV := .venv
VENV   ?= $(DEFAULT_VENV)
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-stamp
# the set-up a target needs: none when VENV names another, already made, environment
SETUP  := $(if $(filter $(DEFAULT_VENV),$(VENV)),$(STAMP))

.PHONY: demo test lint bench notebooks docs setup clean lab shell

setup: $(STAMP)

$(STAMP): pyproject.toml scripts/system-deps.sh
	PYTHON="$(PYTHON)" bash scripts/system-deps.sh
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,notebooks,dask,widgets,graders,docs,peers]'
	$(PY) -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/dhsym derive puma560 --format text
	$(VENV)/bin/dhsym derive puma560 --format markdown -o build/puma560.md
	$(VENV)/bin/dhsym handout puma560 -o build/puma560.tex --pdf

# the whole suite in two steps: the quick tests, then the few marked slow (compiling every
# export, the general 6R, the class through Dask, ...) on their own. Both steps and all
# their workers share one disk cache (DHSYM_TEST_CACHE: a robot is derived once for the
# whole run), and the tests of a module with a shared fixture (the docs site, the wheel,
# the exports of every robot) run on one worker (tests/conftest.py). Python's compiled
# modules (dhsym's, the test modules pytest rewrites) are kept for the run in a folder of
# their own (PYTHONPYCACHEPREFIX; even where PYTHONDONTWRITEBYTECODE is set), so that every
# worker of both steps, and every command or notebook kernel a test starts, reads them
# instead of compiling them again; the checkout gets no __pycache__.
test: $(STAMP)
	cache=$$(mktemp -d "$${TMPDIR:-/tmp}/dhsym-test-cache-XXXXXX") && \
	pyc=$$(mktemp -d "$${TMPDIR:-/tmp}/dhsym-test-pyc-XXXXXX") && \
	unset PYTHONDONTWRITEBYTECODE && export PYTHONPYCACHEPREFIX=$$pyc && \
	DHSYM_TEST_CACHE=$$cache $(PY) -m pytest -q -n auto --durations=15 -m "not slow" && \
	DHSYM_TEST_CACHE=$$cache $(PY) -m pytest -q -n auto --durations=15 -m slow; \
	status=$$?; rm -rf "$$cache" "$$pyc"; exit $$status

lint: $(STAMP)
	$(VENV)/bin/ruff check dhsym tests benchmarks
	$(VENV)/bin/ruff format --check dhsym tests benchmarks
	$(VENV)/bin/mypy

notebooks: $(STAMP)
	$(VENV)/bin/dhsym notebooks build $(NB)

docs: $(SETUP)
	$(PY) scripts/build_docs.py build/docs

bench: $(STAMP)
	$(PY) benchmarks/bench_core.py
	$(PY) benchmarks/bench_cli.py
	$(PY) benchmarks/bench_inverse.py

lab: $(STAMP)
	$(VENV)/bin/jupyter lab notebooks/

shell: $(STAMP)
	@echo "dhsym's environment is active; leave it with exit" >&2
	@bash --init-file $(VENV)/bin/activate -i

clean:
	rm -rf $(VENV) build .pytest_cache
