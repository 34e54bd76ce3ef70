# Two commands do everything on a fresh Debian machine with Python 3.11 (see README):
#   make demo   - create/reuse .venv, install, start the panel in demo mode (ARGS="..." reach it)
#   make test   - create/reuse .venv, install with test extras, lint, run the whole test suite
PYTHON ?= python3
VENV   := .venv
VPY    := $(VENV)/bin/python
ARGS   ?=

.PHONY: demo test explore lint bench sysdeps clean

# Debian packages Qt needs even offscreen (GL, EGL, fonts, xkb) and iproute2 for the
# EtherCAT link tests. Installed only when something is missing, and only as root.
sysdeps:
	@missing=""; \
	for lib in libEGL.so.1 libGL.so.1 libxkbcommon.so.0 libfontconfig.so.1 libdbus-1.so.3; do \
	  ldconfig -p 2>/dev/null | grep -q "$$lib" || missing="$$missing $$lib"; done; \
	command -v ip >/dev/null 2>&1 || missing="$$missing ip"; \
	command -v gcc >/dev/null 2>&1 || missing="$$missing gcc"; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing Debian packages for:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
	      libegl1 libgl1 libxkbcommon0 libfontconfig1 libdbus-1-3 iproute2 gcc >/dev/null; \
	  else \
	    echo "missing system libraries:$$missing"; \
	    echo "install them with: sudo apt-get install libegl1 libgl1 libxkbcommon0 libfontconfig1 libdbus-1-3 iproute2 gcc"; \
	    exit 1; \
	  fi; \
	fi
	@# the third-party slave of the EtherCAT link tests (../shared/thirdparty/kickcat) needs
	@# libtinyxml2; those tests need root anyway, so only root installs it (others skip them)
	@if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && ! ldconfig -p 2>/dev/null | grep -q libtinyxml2.so.9; then \
	  echo "installing Debian's libtinyxml2-9 for the EtherCAT link tests"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libtinyxml2-9 >/dev/null; \
	fi
	@if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && ! command -v npm >/dev/null; then \
	  echo "installing Debian's nodejs and npm for the OPC UA tests' second client (node-opcua)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null \
	    || echo "nodejs and npm not installed: the node-opcua tests skip"; \
	fi
	@# LinuxCNC's own interpreter (rs274) reads the random programs of the G-code tests beside
	@# ours; only root installs it (others skip those tests, saying how to install it)
	@if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && ! command -v rs274 >/dev/null; then \
	  echo "installing Debian's linuxcnc-uspace for LinuxCNC's rs274 (G-code reference)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
	    linuxcnc-uspace >/dev/null || echo "linuxcnc-uspace not installed: the tests against rs274 skip"; \
	fi

# node-opcua, an OPC UA client written by others, for the server's tests (tests/opcua/node_client);
# without node and npm those tests skip saying so (as root, sysdeps installs Debian's nodejs and npm)
NODE_CLIENT := tests/opcua/node_client
$(NODE_CLIENT)/node_modules/.installed: $(NODE_CLIENT)/package.json $(NODE_CLIENT)/package-lock.json
	@if command -v npm >/dev/null 2>&1; then \
	  npm ci --prefix $(NODE_CLIENT) --no-audit --no-fund --loglevel=error >/dev/null && touch $@ \
	    || echo "npm ci in $(NODE_CLIENT) failed: the node-opcua tests skip"; \
	else echo "npm not found: the node-opcua tests skip (apt-get install nodejs npm)"; fi

$(VPY):
	@$(PYTHON) -m venv $(VENV) 2>/dev/null || { \
	  echo "python3 -m venv failed; installing Debian's python3-venv"; \
	  apt-get update -qq && apt-get install -y -qq python3-venv >/dev/null && $(PYTHON) -m venv $(VENV); }
	@$(VPY) -m pip install -q --upgrade pip

$(VENV)/.installed: pyproject.toml planner/_passes.c planner/geometry/_kernels.c planner/motion/_meter.c planner/_buffers.h | $(VPY)
	$(VPY) -m pip install -q -e .
	@touch $@

$(VENV)/.installed-test: pyproject.toml planner/_passes.c planner/geometry/_kernels.c planner/motion/_meter.c planner/_buffers.h | $(VPY)
	$(VPY) -m pip install -q -e '.[test]'
	@touch $@ $(VENV)/.installed

demo: sysdeps $(VENV)/.installed
	$(VPY) -m app --demo $(ARGS)

# ruff, the import-linter layering contracts (pyproject.toml), and the type checker
lint: $(VENV)/.installed-test
	$(VENV)/bin/ruff check app planner ethercat cli opcua_server machine_status resources tools tests bench
	$(VENV)/bin/lint-imports
	$(VENV)/bin/mypy

# the suite a test file per worker, one worker per core (4 at most); then the EtherCAT link
# tests (marker "root": network namespaces, a slave process, 100 ms watchdogs) alone
test: sysdeps $(VENV)/.installed-test $(NODE_CLIENT)/node_modules/.installed lint
	QT_QPA_PLATFORM=$${QT_QPA_PLATFORM:-offscreen} $(VPY) -m pytest -n auto --maxprocesses 4 --dist loadfile -m "not root"
	QT_QPA_PLATFORM=$${QT_QPA_PLATFORM:-offscreen} $(VPY) -m pytest -m root

# the property tests with new random examples each run (make test draws the same ones every run)
explore: $(VENV)/.installed-test
	HYPOTHESIS_PROFILE=explore QT_QPA_PLATFORM=$${QT_QPA_PLATFORM:-offscreen} $(VPY) -m pytest -n auto --maxprocesses 4 --dist loadfile -m "not root" $(ARGS) $$(grep -rl "@given" tests)

bench: $(VENV)/.installed-test
	$(VPY) -m bench

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .hypothesis $(NODE_CLIENT)/node_modules
