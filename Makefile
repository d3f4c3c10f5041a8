# Two commands for users (README): `make run` and `make test`. Both set up .venv on a fresh machine.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# Shared libraries the Qt wheels need but do not ship (present on most desktops; installed here if missing).
QT_SYSLIBS := libegl1 libgl1 libxkbcommon0 libfontconfig1 libdbus-1-3 libglib2.0-0
# What Qt's xcb platform plugin (the window on an X display) loads: `ldd …/platforms/libqxcb.so` on Debian 12.
XCB_SYSLIBS := libx11-xcb1 libxcb-cursor0 libxcb-icccm4 libxcb-image0 libxcb-keysyms1 libxcb-randr0 \
	libxcb-render-util0 libxcb-shape0 libxcb-sync1 libxcb-xfixes0 libxcb-xkb1 libxkbcommon-x11-0
XCB_SONAMES := libX11-xcb.so.1 libxcb-cursor.so.0 libxcb-icccm.so.4 libxcb-image.so.0 libxcb-keysyms.so.1 \
	libxcb-randr.so.0 libxcb-render-util.so.0 libxcb-shape.so.0 libxcb-sync.so.1 libxcb-xfixes.so.0 libxcb-xkb.so.1 \
	libxkbcommon-x11.so.0

# Tests: `make test` runs everything (what CI runs), `make test-fast` the inner loop (docs/testing.md).
HEADLESS := .venv-headless
HSTAMP   := $(HEADLESS)/.installed
# pytest-xdist workers: the suite waits on drives, timers and paced lines far more than it computes, so more
# workers than cores overlap the waits
WORKERS  ?= 4
PYTEST   := QT_QPA_PLATFORM=offscreen $(BIN)/python -m pytest -n $(WORKERS)
# Test runs write bytecode even where the environment says not to: pytest then keeps its rewritten test modules
# (collecting the suite otherwise rewrites every assert, ~15 s per worker), and each drive process a test starts
# loads compiled modules instead of compiling the sources again.
unexport PYTHONDONTWRITEBYTECODE

.PHONY: run test test-fast test-headless lint bench sysdeps guideps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $@

sysdeps:
	@if ! ldconfig -p | grep -q 'libEGL.so.1' || ! ldconfig -p | grep -q 'libxkbcommon.so.0'; then \
	  if command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
	    apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q $(QT_SYSLIBS); \
	  else echo "Qt needs the system libraries: $(QT_SYSLIBS) (install them with your package manager)"; fi; \
	fi

guideps: sysdeps
	@missing=""; for lib in $(XCB_SONAMES); do ldconfig -p | grep -q "$$lib" || missing="$$missing $$lib"; done; \
	if [ -n "$$missing" ]; then \
	  if command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
	    apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q $(XCB_SYSLIBS); \
	  else echo "The IDE's window needs:$$missing — on Debian/Ubuntu: sudo apt-get install $(XCB_SYSLIBS)"; fi; \
	fi

run: guideps $(STAMP)
	$(BIN)/motiontool

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/lint-imports
	$(BIN)/python -m mypy

# The Qt-free packages' tests run in an environment without Qt (PySide6, pyqtgraph, pytest-qt left out): the
# rule "models never import Qt" is proven by running, not only by the import contracts.
$(HSTAMP): pyproject.toml
	$(PYTHON) -m venv $(HEADLESS)
	$(HEADLESS)/bin/python -m pip install -q --upgrade pip
	$(HEADLESS)/bin/python -c 'import tomllib; p = tomllib.load(open("pyproject.toml", "rb"))["project"]; \
	  qt = ("pyside6", "pyqtgraph", "pytest-qt", "ruff", "import-linter"); \
	  print("\n".join(d for d in p["dependencies"] + p["optional-dependencies"]["test"] \
	                  if not d.lower().startswith(qt)))' > $(HEADLESS)/requirements.txt
	$(HEADLESS)/bin/python -m pip install -q -r $(HEADLESS)/requirements.txt
	$(HEADLESS)/bin/python -m pip install -q --no-deps -e .
	touch $@

# Every test, in two runs: the tests marked gui (tests/conftest.py: everything under a ui/ test package and
# every test using qtbot) with Qt, the rest without it.
test: sysdeps lint $(HSTAMP)
	$(MAKE) --no-print-directory test-headless
	$(PYTEST) -m gui --durations=25

test-headless: $(HSTAMP)
	QT_QPA_PLATFORM=offscreen $(HEADLESS)/bin/python -m pytest -n $(WORKERS) -m "not gui" --durations=25 \
	  --ignore=tests/ui --ignore=tests/scope/ui --ignore=tests/cameditor/ui

# The inner loop: no soak, no slow test, nothing on a wire (goal: 90 s on two cores).
test-fast: $(STAMP)
	$(PYTEST) -m "not (soak or slow or wire)"

bench: $(STAMP)
	@for f in benchmarks/*.py; do echo "# $$f"; $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) $(HEADLESS) build src/*.egg-info .pytest_cache .ruff_cache .hypothesis
