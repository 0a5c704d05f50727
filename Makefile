# The two Quick start commands (README): `make demo` and `make test`. Both create .venv when
# it is missing and install rosreconf with everything the tests need.
VENV   ?= .venv
PY     := $(VENV)/bin/python
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp

.PHONY: demo test test-cpu lint typecheck pytest explore system-deps ros2-venvs bench architecture clean

$(STAMP): pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,planners,plot,dask,ros2]'
	touch $(STAMP)

## Install the Debian packages the tests need (ROS 1, Graphviz); a no-op when present.
system-deps:
	bash scripts/system-deps.sh

demo: $(STAMP)
	$(BIN)/rosreconf validate
	$(BIN)/rosreconf enumerate --only object_repositioning --only disc_loading
	@# With NSM3 failed, Disc Loading has no configuration: exit 1 is the expected answer there,
	@# while 2 (usage) or 3 (planner) must still stop the demo.
	$(BIN)/rosreconf enumerate --only object_repositioning --only disc_loading --fail NSM3; \
	  test $$? -le 1
	$(BIN)/rosreconf analyse --only object_repositioning
	@# The M-solution: will each configuration perform? Indoor Navigation has a valid but
	@# unstable configuration; exit 1 would mean a schema where none performs.
	$(BIN)/rosreconf simulate --only object_repositioning --only indoor_navigation --pareto settling_time,cost
	$(BIN)/rosreconf plan --fail NSM3 --only object_repositioning --only disc_loading; \
	  test $$? -le 1

## Real ROS 2 (rclpy over Fast DDS) from PyPI, one venv per distro (.venv-ros2-jazzy,
## .venv-ros2-kilted), pinned in requirements/ros2-<distro>.txt. The ROS 2 tests start real rclpy
## nodes with these interpreters; ros-wheels-bootstrapper re-executes every Python of such a venv
## with LD_LIBRARY_PATH set, so the wheels never share a venv with rosreconf.
ROS2_DISTROS := jazzy kilted
ros2-venvs: $(foreach d,$(ROS2_DISTROS),.venv-ros2-$(d)/.installed-stamp)

## The stamp holds the requirements it was built from: a checkout that only renews the file's
## time (a fresh branch, a worktree whose venvs are links to another's) installs nothing.
.venv-ros2-%/.installed-stamp: requirements/ros2-%.txt
	@if cmp -s $< $@; then touch $@; else \
	  set -ex; python3 -m venv .venv-ros2-$*; \
	  .venv-ros2-$*/bin/python -m pip install --quiet -r $<; \
	  HOME=$${HOME:-/tmp} .venv-ros2-$*/bin/python -c 'import rclpy, rclpy.lifecycle, rclpy.action'; \
	  cp $< $@; fi

## Setup and checks two at a time (.venv, the two ROS 2 venvs, lint and mypy: about 120 CPU s,
## one pip or mypy uses one core), then the suite. Output by line, so two jobs never mix one.
test: system-deps
	$(MAKE) --no-print-directory -j2 --output-sync=line ros2-venvs lint typecheck
	$(MAKE) --no-print-directory pytest

lint: $(STAMP)
	$(BIN)/lint-imports
	$(BIN)/ruff check rosreconf tests benchmarks scripts
	$(BIN)/ruff format --check rosreconf tests benchmarks scripts

typecheck: $(STAMP)
	$(BIN)/mypy

# The property tests draw the same examples on every run (hypothesis profile "ci", set in
# tests/conftest.py), and the hash seed is fixed so that set and dict-of-set iteration orders
# are the same too: `make test` passes or fails the same way on every clean checkout.
# Four worker processes (pytest-xdist): a live test mostly waits on real nodes, so on 2 cores
# the suite takes half the wall time of one process. Each worker takes its own DDS domain ids
# and ROS master ports (tests/ros2_harness.py, tests/ros_harness.py); the tests on many real
# ROS 2 nodes run in two lanes (tests/conftest.py, LIVE_ROS2_LANES). TEST_WORKERS=0: one process.
# Bytecode is written even where PYTHONDONTWRITEBYTECODE is set: otherwise every worker and
# every `python -m rosreconf` the tests start compiles the same sources again. The 40 slowest
# tests are listed at the end: where the suite's time goes, in every CI log.
TEST_WORKERS ?= 4
pytest: $(STAMP)
	HYPOTHESIS_PROFILE=ci PYTHONHASHSEED=0 PYTHONDONTWRITEBYTECODE= \
	  $(BIN)/pytest -n $(TEST_WORKERS) --dist loadgroup --durations=40

## Where the suite's CPU goes: each test's CPU seconds (its worker's and the children it
## waited for) in test-cpu.jsonl, summed per file. ROSRECONF_TEST_LANES sets the live lanes.
test-cpu: $(STAMP)
	rm -f test-cpu.jsonl
	ROSRECONF_TEST_CPU=$(CURDIR)/test-cpu.jsonl $(MAKE) --no-print-directory pytest
	$(PY) scripts/test_cpu.py test-cpu.jsonl

## Search for new counterexamples by hand: only the property tests, random seeds, 50 times the
## examples. Pin what it finds with @example; failures replay from .hypothesis until fixed.
explore: $(STAMP)
	HYPOTHESIS_PROFILE=explore PYTHONHASHSEED=random $(BIN)/pytest -m hypothesis $(EXPLORE_ARGS)

## Measure count, first, optimal, whatif and clingo alone over the R x K grid.
bench: $(STAMP)
	$(PY) benchmarks/selfcheck.py
	$(PY) benchmarks/run.py

## Redraw docs/img/architecture.svg: the stages and their imports, read from the code.
architecture: $(STAMP)
	$(PY) scripts/architecture.py docs/img/architecture.dot
	dot -Tsvg docs/img/architecture.dot -o docs/img/architecture.svg

clean:
	rm -rf $(VENV) .venv-ros2-* build dist *.egg-info .mypy_cache .ruff_cache .pytest_cache
