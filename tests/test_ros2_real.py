"""``snapshot``/``inspect --ros2`` against real ROS 2 nodes: rclpy over Fast DDS, Jazzy and Kilted.

Every node here is a real ``rclpy`` node (tests/ros2_node.py run by the distribution's own
venv, ``make ros2-venvs``), one process per node, on a private domain. Two systems run per
distribution, built from tests/data/ros2 (a four-role patrol robot using std_msgs/std_srvs):

- ``nominal``: the schema's nominal configuration as it should run (the controller is a
  lifecycle node, active);
- ``broken``: the same roles wired wrongly, started subscriber first: the controller
  publishes ``/drive`` as ``std_msgs/String`` (the base subscribes ``std_msgs/Int32``), the
  planner serves ``/plan`` as ``std_srvs/SetBool`` (not Trigger), the controller is left
  inactive, the base calls ``/nobody``, which no node serves, and two processes run a node
  named ``/lidar``.

The reference for names and types is the library file read independently (the node specs
are written by tests/ros2_harness.node_spec, not rosreconf's name mapping); for the whole
graph it is rclpy's own graph API (tests/test_ros2_real_scale.py).
"""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import ros2_harness
import ros2_real
from test_json_outputs import schema_of
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_paths
from rosreconf.resources import Bundle, bundled

DATA = Path(__file__).with_name("data") / "ros2"
LIBRARY, SCHEMA = DATA / "patrol_library.yaml", DATA / "patrol_schema.yaml"
FILES = ["-l", str(LIBRARY), "-s", str(SCHEMA)]


def _specs() -> dict[str, dict[str, Any]]:
    """Return each component's node as the library says it runs (independent mapping)."""
    library = load_paths([LIBRARY]).library
    return {c.name: ros2_harness.node_spec(c) for c in library}


@pytest.fixture(scope="module", params=ros2_real.DISTROS)
def distro(request: pytest.FixtureRequest) -> str:
    """Return the ROS 2 distribution of this round (each module-scoped system is per round)."""
    ros2_real.python_of(request.param)  # fail, never skip, when the venv is missing
    return str(request.param)


@pytest.fixture(scope="module")
def loopback() -> Iterator[None]:
    """Make rosreconf's own DDS use loopback only (as ros2_domain does per test)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CYCLONEDDS_URI", ros2_harness.loopback_config())
        yield


def _system(distro: str, tmp: Path) -> ros2_real.Ros2System:
    return ros2_real.Ros2System.on_a_free_domain(distro, tmp)


@pytest.fixture(scope="module")
def nominal(
    distro: str, loopback: None, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[ros2_real.Ros2System]:
    """Run the nominal patrol configuration, one process per node, the controller active."""
    system = _system(distro, tmp_path_factory.mktemp(f"nominal-{distro}"))
    specs = _specs()
    try:
        for comp in ("LIDAR", "PLANNER", "CONTROLLER", "BASE"):
            spec = specs[comp]
            if comp == "CONTROLLER":
                spec = {**spec, "lifecycle": "active"}
            system.start(spec)
        yield system
    finally:
        system.stop()


@pytest.fixture(scope="module")
def broken(
    distro: str, loopback: None, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[ros2_real.Ros2System]:
    """Run the patrol roles wired wrongly (module docstring), the subscriber of /drive first."""
    system = _system(distro, tmp_path_factory.mktemp(f"broken-{distro}"))
    specs = _specs()
    base = specs["BASE"]
    base = {**base, "clients": [{"name": "/nobody", "type": "std_srvs/srv/Trigger"}]}
    controller = {
        **specs["CONTROLLER"],
        "lifecycle": "inactive",
        "publishers": [{"name": "/drive", "type": "std_msgs/msg/String"}],
    }
    planner = {**specs["PLANNER"], "servers": [{"name": "/plan", "type": "std_srvs/srv/SetBool"}]}
    try:
        for spec in (base, controller, planner, specs["LIDAR"], specs["LIDAR"]):
            system.start(spec)
        yield system
    finally:
        system.stop()


@pytest.fixture(scope="module")
def broken_report(broken: ros2_real.Ros2System) -> dict[str, Any]:
    """Return ``inspect --ros2 --json`` of the broken system (read once, asserted by many)."""
    code, doc = _inspect(CliRunner(), broken.domain)
    assert code == 1
    return doc


def _inspect(runner: CliRunner, domain: int, *extra: str) -> tuple[int, dict[str, Any]]:
    result = runner.invoke(
        app, ["inspect", "--ros2", "--domain", str(domain), *FILES, "--json", *extra]
    )
    assert result.exit_code in (0, 1), result.stdout + result.stderr
    doc = json.loads(result.stdout)
    jsonschema.validate(doc, schema_of("inspect"))
    return result.exit_code, doc


def _snapshot(runner: CliRunner, domain: int, *extra: str) -> dict[str, Any]:
    result = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(domain), *extra])
    assert result.exit_code == 0, result.stdout + result.stderr
    doc: dict[str, Any] = json.loads(result.stdout)
    return doc


def _codes(doc: dict[str, Any], code: str) -> list[dict[str, Any]]:
    return [f for f in doc["findings"] if f["code"] == code]


def test_nominal_system_conforms_with_and_without_distro(
    nominal: ros2_real.Ros2System, runner: CliRunner
) -> None:
    for extra in ((), ("--distro", nominal.distro)):
        code, doc = _inspect(runner, nominal.domain, *extra)
        assert (code, doc["findings"]) == (0, []), extra
        assert doc["conformant"] is True


def test_managed_node_state_is_read(nominal: ros2_real.Ros2System, runner: CliRunner) -> None:
    doc = _snapshot(runner, nominal.domain)
    states = {n["name"]: n["lifecycle_state"] for n in doc["nodes"]}
    assert states == {
        "/lidar": None,
        "/planner": None,
        "/controller": "active",
        "/robot/base": None,
    }


def test_wrong_distro_is_refused_plainly(nominal: ros2_real.Ros2System, runner: CliRunner) -> None:
    result = runner.invoke(
        app, ["snapshot", "--ros2", "--domain", str(nominal.domain), "--distro", "humble"]
    )
    assert result.exit_code == 3, result.stdout
    assert "no node names could be read" in result.stderr
    assert "--distro humble" in result.stderr and "try without --distro" in result.stderr
    assert result.stdout == ""


def test_nothing_on_the_domain_is_said_plainly(
    loopback: None, domain_id: int, runner: CliRunner
) -> None:
    result = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(domain_id)])
    assert result.exit_code == 3
    assert "nothing seen on ROS 2 domain" in result.stderr
    assert result.stdout == ""


def test_cyclone_messages_are_said_once_per_cause(nominal: ros2_real.Ros2System) -> None:
    """Without --distro both Gid layouts are read: every Fast DDS sample fails one of them.

    That failure is rosreconf's own doing and handled, so it is never said (it was, once, in
    every watch); ``ROSRECONF_DDS_VERBOSE=1`` shows Cyclone's raw lines, and so that it
    happened. Any other cause is said once.
    """

    def snapshot(**extra: str) -> subprocess.CompletedProcess[str]:
        argv = [sys.executable, "-m", "rosreconf", "snapshot", "--ros2", "--domain"]
        return subprocess.run(
            [*argv, str(nominal.domain)],
            capture_output=True,
            text=True,
            env={**ros2_harness.dds_env(), "COLUMNS": "200", **extra},
            timeout=60,
        )

    out = snapshot()
    assert out.returncode == 0, out.stderr
    assert len(json.loads(out.stdout)["nodes"]) == 4
    raw = [line for line in out.stderr.splitlines() if re.match(r"^\d+\.\d+ +\[", line)]
    assert raw == []
    said = [line for line in out.stderr.splitlines() if "Cyclone DDS says" in line]
    assert not [line for line in said if "deserialization ros_discovery_info" in line], said
    causes = [re.sub(r"[0-9a-f]+(:[0-9a-f]+){3}|#\d+", "", line) for line in said]
    assert len(causes) == len(set(causes))
    verbose = snapshot(ROSRECONF_DDS_VERBOSE="1")
    assert verbose.returncode == 0, verbose.stderr
    assert "deserialization ros_discovery_info" in verbose.stderr  # it happened, unsaid


def test_user_cyclone_config_is_merged_not_replaced(
    nominal: ros2_real.Ros2System, tmp_path: Path
) -> None:
    """The user's tracing is in effect, and so is rosreconf's Kilted setting (nodes seen)."""
    trace = tmp_path / "cyclone.log"
    user = ros2_harness.loopback_config().replace(
        "</Domain>",
        f"<Tracing><Verbosity>config</Verbosity><OutputFile>{trace}</OutputFile></Tracing></Domain>",
    )
    out = subprocess.run(
        [sys.executable, "-m", "rosreconf", "snapshot", "--ros2", "--domain", str(nominal.domain)],
        capture_output=True,
        text=True,
        env={**ros2_harness.dds_env(), "CYCLONEDDS_URI": user},
        timeout=60,
    )
    assert out.returncode == 0, out.stderr
    assert {n["name"] for n in json.loads(out.stdout)["nodes"]} == {
        "/lidar", "/planner", "/controller", "/robot/base"
    }  # fmt: skip
    log = trace.read_text(errors="replace")
    assert "IgnoreTypeInformation" in log and "127.0.0.1" in log


def test_wrong_topic_type_is_found_when_the_subscriber_started_first(
    broken_report: dict[str, Any],
) -> None:
    doc = broken_report
    wrong = [f for f in _codes(doc, "wrong-type") if f["live_name"] == "/drive"]
    assert len(wrong) == 1, doc["findings"]
    assert "std_msgs/msg/String at /controller" in wrong[0]["message"]


def test_service_types_are_compared(broken_report: dict[str, Any]) -> None:
    doc = broken_report
    wrong = [f for f in _codes(doc, "wrong-type") if f["live_name"] == "/plan"]
    assert len(wrong) == 1, doc["findings"]
    assert "std_srvs/srv/SetBool at /planner" in wrong[0]["message"]
    assert "not std_srvs/Trigger" in wrong[0]["message"]


def test_client_without_server_is_a_finding(broken_report: dict[str, Any]) -> None:
    doc = broken_report
    (unserved,) = _codes(doc, "unserved-client")
    assert (unserved["component"], unserved["live_name"]) == ("BASE", "/nobody")


def test_duplicate_node_names_are_reported_not_merged(
    broken: ros2_real.Ros2System, broken_report: dict[str, Any], runner: CliRunner
) -> None:
    (dup,) = _codes(broken_report, "duplicate-node")
    assert (dup["component"], dup["live_name"]) == ("LIDAR", "/lidar")
    snap = _snapshot(runner, broken.domain)
    assert [n["name"] for n in snap["nodes"]].count("/lidar") == 2


def test_inactive_managed_node_is_not_conformant(broken_report: dict[str, Any]) -> None:
    (state,) = _codes(broken_report, "not-active")
    assert state["component"] == "CONTROLLER"
    assert "/controller is inactive" in state["message"]


def test_qos_depth_is_unknown_not_made_up(broken: ros2_real.Ros2System, runner: CliRunner) -> None:
    snap = _snapshot(runner, broken.domain, "--distro", broken.distro)
    schema = bundled(Bundle.DATA, "live_graph.schema.json").read_text(encoding="utf-8")
    jsonschema.validate(snap, json.loads(schema))
    depths = {
        q["depth"] for n in snap["nodes"] for side in n["qos"].values() for q in side.values()
    }
    assert depths == {None}


def test_forged_gid_of_another_participant_is_ignored(
    nominal: ros2_real.Ros2System, tmp_path: Path, runner: CliRunner
) -> None:
    """Imitation (real nodes cannot forge): a DDS participant writes ros_discovery_info
    carrying a real node's participant GID and no nodes, over and over."""
    attacker = ros2_harness.start(
        tmp_path, nominal.domain, [], forge="other", ros_participant=False
    )
    try:
        result = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(nominal.domain)])
    finally:
        ros2_harness.stop([attacker])
    assert result.exit_code == 0, result.stderr
    names = {n["name"] for n in json.loads(result.stdout)["nodes"]}
    assert names == {"/lidar", "/planner", "/controller", "/robot/base"}
    assert "named another participant's GID and were ignored" in result.stderr


def test_a_participant_that_answers_late_is_read_not_called_absent(
    distro: str, loopback: None, tmp_path: Path, runner: CliRunner
) -> None:
    """A participant whose process gets no CPU answers discovery late: a first read that
    ended on 1 s of stillness once returned 24 of 40 real nodes with exit 0 on a loaded
    machine. Here the only node's process is stopped (SIGSTOP, a fault provoked on a real
    node) before ``snapshot`` starts and continued 2.4 s later, after the 2 s in which an
    empty domain used to be called empty: its node must be in the snapshot."""
    from rosreconf.ros.ros2.discovery import FIRST_READ_AT_LEAST

    system = _system(distro, tmp_path)
    try:
        late = system.start(_specs()["PLANNER"]).process
        late.send_signal(signal.SIGSTOP)
        timer = threading.Timer(2.4, late.send_signal, [signal.SIGCONT])
        begun = time.monotonic()
        timer.start()
        result = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(system.domain)])
        took = time.monotonic() - begun
        timer.join()
        assert result.exit_code == 0, (
            f"{result.stderr} (took {took:.2f} s; the first read listens at least "
            f"{FIRST_READ_AT_LEAST} s)"
        )
        assert [n["name"] for n in json.loads(result.stdout)["nodes"]] == ["/planner"]
    finally:
        for p in system.processes:
            p.process.send_signal(signal.SIGCONT)
        system.stop()


def test_spin_time_waits_for_a_participant_later_than_the_default_listen(
    distro: str, loopback: None, tmp_path: Path, runner: CliRunner
) -> None:
    """``--spin-time`` (as ros2cli's) is the least a read listens: on a host loaded enough
    that a participant answers after the default 3.5 s, a user asks for longer. The only
    node's process is stopped (SIGSTOP) before ``snapshot`` starts and continued 6 s later,
    past the default listen (which would call the domain empty, exit 3); with
    ``--spin-time 10`` its node is in the snapshot."""
    system = _system(distro, tmp_path)
    try:
        late = system.start(_specs()["PLANNER"]).process
        late.send_signal(signal.SIGSTOP)
        timer = threading.Timer(6.0, late.send_signal, [signal.SIGCONT])
        timer.start()
        argv = ["snapshot", "--ros2", "--domain", str(system.domain), "--spin-time", "10"]
        result = runner.invoke(app, argv)
        timer.join()
        assert result.exit_code == 0, result.stderr
        assert [n["name"] for n in json.loads(result.stdout)["nodes"]] == ["/planner"]
    finally:
        for p in system.processes:
            p.process.send_signal(signal.SIGCONT)
        system.stop()
