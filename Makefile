# sitegen: `make site` builds the book into build/; `make test` runs every test.
# Both set up what they need on a fresh machine (.venv, node_modules; for the tests Debian's chromium and Java).

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
SUDO   := $(if $(filter 0,$(shell id -u)),,sudo)
PORT   ?= 8000
export OPENBLAS_NUM_THREADS := 1
# The tests start many Python processes: let them keep compiled bytecode (in __pycache__, ignored by
# git and left out of the wheel) rather than compile the package's sources in every one.
unexport PYTHONDONTWRITEBYTECODE

.PHONY: site test check lint pdf serve bench clean tools-node tools-chromium tools-check tools-test review accept-figures
# One target at a time: the tool targets may each run apt, which takes a lock (the tests run in parallel by themselves).
.NOTPARALLEL:

site: $(VENV)/.site-installed tools-node
	$(BIN)/sitegen build

# Tests run in several processes (pytest-xdist), each test file in one of them, so that a file's
# shared pages and builds are made once; the books every file reads are built once per run. The
# browser tests mostly wait on Chromium, so `make test` runs one process more than this machine's
# two cores; `make check` is busy computing and runs one per core. The files with browser and slow tests are
# handed out first (tests/conftest.py orders them by their marks), so that no long file starts last.
TEST_WORKERS ?= 3
CHECK_WORKERS ?= 2
test: tools-test $(VENV)/.test-installed node_modules/.installed
	$(BIN)/pytest -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder

# The inner loop: every test but those that drive Chromium or build the project's own book
# (the end-to-end tests run on the tiny book in tests/book/), with each property-based test on the
# first fifth of its examples (`make test` runs them all).
check: tools-check $(VENV)/.test-installed node_modules/.installed lint
	SITEGEN_EXAMPLE_SHARE=0.2 $(BIN)/pytest -q -p no:cacheprovider -m "not browser and not slow" -n $(CHECK_WORKERS) --dist loadfile --no-loadscope-reorder

# ruff (pinned in the dev extras): the lint rules and the format are in ruff.toml.
lint: $(VENV)/.test-installed
	$(BIN)/ruff check --quiet src tests bench
	$(BIN)/ruff format --check --quiet src tests bench

# The whole book as one PDF (book.pdf), printed by Debian's chromium.
pdf: $(VENV)/.site-installed tools-chromium
	$(BIN)/sitegen pdf

# Build, serve on 127.0.0.1 and rebuild on every change to the book; open pages reload by themselves.
serve: $(VENV)/.site-installed tools-node
	$(BIN)/sitegen serve --watch --port $(PORT)

bench: tools-chromium $(VENV)/.test-installed node_modules/.installed
	$(BIN)/python bench/run.py
	$(BIN)/python bench/shelf.py
	$(BIN)/python bench/preview.py
	$(BIN)/sitegen bench
	$(BIN)/python bench/lighthouse.py

# Build revision BASE (default HEAD) in a temporary git worktree, build the working tree, and write
# build-review/index.html and build-review/summary.md. Exits 1 when anything changed (for CI).
BASE ?= HEAD
review: tools-chromium $(VENV)/.test-installed node_modules/.installed
	$(BIN)/sitegen build
	$(BIN)/sitegen review --base $(BASE)

# Rewrite the book's figure goldens (goldens/) from a fresh build, deliberately (refused when CI=true).
accept-figures: $(VENV)/.site-installed tools-node
	$(BIN)/sitegen build
	$(BIN)/sitegen accept-figures

clean:
	rm -rf build .build.new-* .build.old build-bench .cache build-review

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# --no-compile: pip would byte-compile every module of every package (scipy's, matplotlib's, numba's), which doubles
# the time of an install (55 s against 26 s on a 2-core machine); Python compiles what is imported, on first use.
PIP_INSTALL := $(BIN)/pip install --quiet --disable-pip-version-check --no-compile

$(VENV)/.site-installed: pyproject.toml | $(BIN)/python
	$(PIP_INSTALL) -e .
	touch $@

# One pip run installs the package with its test tools, so it stands for the site's install too
# (on a fresh clone, `make test` resolves and installs everything once).
$(VENV)/.test-installed: pyproject.toml | $(BIN)/python
	$(PIP_INSTALL) -e '.[dev]'
	touch $(VENV)/.site-installed $@

node_modules/.installed: package.json package-lock.json | tools-node
	npm ci --ignore-scripts --no-audit --no-fund --loglevel=error
	touch $@

# Debian packages, each named only while what it provides is missing. A target installs all it needs in one apt
# run, so that on a fresh machine `make test` updates the package lists once rather than once per tool.
NODE_PKGS     = $(if $(shell command -v node >/dev/null && command -v npm >/dev/null && echo found),,nodejs npm)
JAVA_PKGS     = $(if $(shell command -v java),,default-jre-headless)
CHROMIUM_PKGS = $(if $(shell test -x /usr/bin/chromium && echo found),,chromium)
# sudo resets the environment: DEBIAN_FRONTEND is handed to apt through env, so that it never asks a question.
APT           = $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get
apt_install   = @packages="$(strip $(1))"; test -z "$$packages" || { $(APT) update -q && $(APT) install -y -q $$packages; }

# Temml (TeX -> MathML, vendored in the package) runs on node at build time; npm installs the test tools.
tools-node:
	$(call apt_install,$(NODE_PKGS))

# Browser tests drive Debian's chromium through Playwright (Playwright cannot download browsers here); node too.
tools-chromium:
	$(call apt_install,$(NODE_PKGS) $(CHROMIUM_PKGS))

# What `make check` needs: node, and Java for the HTML checker (its tests are not left out of the inner loop).
tools-check:
	$(call apt_install,$(NODE_PKGS) $(JAVA_PKGS))

# Everything `make test` needs: node, chromium, and Java for the HTML checker (vnu.jar, from npm's vnu-jar:
# npm ci runs no install scripts, so its postinstall never tries to download a Java runtime).
tools-test:
	$(call apt_install,$(NODE_PKGS) $(CHROMIUM_PKGS) $(JAVA_PKGS))
