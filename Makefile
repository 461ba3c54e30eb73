# bonered_alg -- `make derive` and `make test` are the two set-up commands (see README).
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-$(shell cat pyproject.toml constraints.txt | sha256sum | cut -c1-12)

.PHONY: install system-deps derive derive-force test bench report lint lock clean

# the pinned packages (constraints.txt) installed with uv, ten times faster than pip (about 5 s
# against 55 s from a warm cache); with pip where uv cannot run.  --compile-bytecode: uv writes
# no .pyc by default (pip does), and where PYTHONDONTWRITEBYTECODE is set nothing caches them
# later, so every process (derive's and the scans' workers, the test workers) compiled
# sympy, scipy and matplotlib from source again: about 1.9 s per process on this project's
# machine, for about 6 s once at install
$(STAMP): pyproject.toml constraints.txt
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	( $(PY) -m pip install -q -c constraints.txt uv \
	  && $(VENV)/bin/uv pip install -q --compile-bytecode --python $(PY) -c constraints.txt \
	       -e '.[dev]' ) \
	  || $(PY) -m pip install -q -c constraints.txt -e '.[dev]'
	rm -f $(VENV)/.installed-* && touch $(STAMP)

system-deps:
	@bash scripts/install-system-deps.sh

install: $(STAMP) system-deps

# the comparison study starts as soon as the three mechanisms it scans are derived, while
# the workers derive the others (cli derive --comparison)
derive: install
	$(PY) -m bonered_alg.cli derive --comparison

derive-force: install
	$(PY) -m bonered_alg.cli derive --force --comparison

# one worker per core; each test module (or group of them, tests/conftest.py) on one worker
test: install
	$(PY) -m pytest -q -n auto --dist loadgroup

bench: install
	$(PY) bench/run.py --out bench/results.json

report: install
	@bash scripts/install-system-deps.sh --latex
	$(PY) -m bonered_alg.cli derive --comparison
	$(PY) -m bonered_alg.cli report
	cd derivations && latexmk -c -quiet >/dev/null

# the pinned Python packages: the newest versions pyproject.toml allows, on purpose only
lock:
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade uv -e '.[dev]'
	{ head -3 constraints.txt; $(PY) -m pip freeze --exclude-editable; } > constraints.txt.new
	mv constraints.txt.new constraints.txt

lint: install
	$(VENV)/bin/ruff check bonered_alg tests bench examples

clean:
	rm -rf .cache .pytest_cache derivations/*.pdf
	cd derivations && rm -f *.aux *.log *.fls *.fdb_latexmk *.out
