"""``inspect --ros2`` reads the wiring on real rclpy nodes, never assumes it (issue 29).

Every node is a real rclpy process (rosreconf's stand-in, ``ros/ros2/scripts/standin_node.py``,
run by the distribution's own venv), Jazzy and Kilted, on a private domain. A node is wired the
way ROS 2 wires it: ``--ros-args -r FROM:=TO`` on its command line, which rcl applies when the
node starts. The reference for what is unwired is the library file read by hand (the server's
``ros.remappings``) and rclpy's own graph: what a node calls and subscribes to.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import ros2_real
from ros2_team import STANDIN, Member, Team, wait_ready
from test_json_outputs import schema_of
from typer.testing import CliRunner

from rosreconf.cli.app import app

ROOT = Path(__file__).resolve().parent.parent
DATA = Path(__file__).with_name("data") / "wiring"
PAIR = ["-l", str(DATA / "pair_library.yaml"), "-s", str(DATA / "pair_schema.yaml")]
TRIGGER, STRING = "std_srvs/srv/Trigger", "std_msgs/msg/String"
SERVER = {"name": "server", "namespace": "/", "subscribe": [], "call": [], "lifecycle": False,
          "publish": [{"topic": "/real/t_data", "type": STRING}],
          "serve": [{"service": "/real/svc_a", "type": TRIGGER}]}  # fmt: skip
CLIENT = {"name": "client", "namespace": "/", "publish": [], "serve": [],
          "subscribe": [{"topic": "/t_data", "type": STRING}],
          "call": [{"service": "/svc_a", "type": TRIGGER}], "lifecycle": False}  # fmt: skip
WIRED = ["--ros-args", "-r", "svc_a:=/real/svc_a", "-r", "t_data:=/real/t_data"]


class Nodes:
    """Stand-in processes of one distribution on one domain, stopped at the end.

    Each is its own process, forked from one warm process of the distro's venv
    (``ros2_team``), as a launch file would start it: its own pid and DDS participant, its
    remappings on its command line.
    """

    def __init__(self, distro: str, domain: int, tmp: Path) -> None:
        self.distro, self.domain, self.tmp = distro, domain, tmp
        self.processes: dict[str, Member] = {}
        env = ros2_real.node_env(domain, tmp / "home")
        self.team = Team(ros2_real.python_of(distro), env, tmp / "team")

    def start(self, key: str, spec: dict[str, Any], *ros_args: str) -> None:
        """Start one stand-in acting out ``spec``; return once its node exists."""
        argv = [str(ros2_real.python_of(self.distro)), str(STANDIN), json.dumps(spec), *ros_args]
        node = self.team.start(key, argv)
        try:
            wait_ready({key: node}, ros2_real.START_TIMEOUT)
        except AssertionError as exc:
            node.kill()
            pytest.fail(f"stand-in {key} did not start: {exc} {node.log.read_text()[-2000:]}")
        self.processes[key] = node

    def stop(self, *keys: str) -> None:
        """Stop the given processes (all without keys): their participants say goodbye."""
        ros2_real.stop_all([self.processes.pop(k) for k in (keys or list(self.processes))])

    def close(self) -> None:
        """Stop every process left, then the process they were forked from."""
        self.stop()
        self.team.close()


@pytest.fixture(params=ros2_real.DISTROS)
def nodes(request: pytest.FixtureRequest, ros2_domain: int, tmp_path: Path) -> Iterator[Nodes]:
    """Return an empty set of stand-ins of one distribution (Jazzy, then Kilted)."""
    ros2_real.python_of(request.param)  # fail, never skip, when the venv is missing
    started = Nodes(str(request.param), ros2_domain, tmp_path)
    try:
        yield started
    finally:
        started.close()


def _inspect(domain: int, *files: str) -> tuple[int, dict[str, Any]]:
    result = CliRunner().invoke(
        app, ["inspect", "--ros2", "--domain", str(domain), *files, "--json"]
    )
    assert result.exit_code in (0, 1), result.stdout + result.stderr
    doc = json.loads(result.stdout)
    jsonschema.validate(doc, schema_of("inspect"))
    return result.exit_code, doc


def _settled(domain: int, *files: str, tries: int = 3) -> tuple[int, dict[str, Any]]:
    """Return ``inspect``'s answer once the graph conforms, or its last of ``tries``.

    Nodes just restarted are discovered over seconds on a loaded machine, and a first read
    can end before one of them has announced every endpoint: conforming is a claim about
    the settled graph, so it is read again a few times before the test says no.
    """
    for _ in range(tries - 1):
        code, doc = _inspect(domain, *files)
        if code == 0:
            return code, doc
    return _inspect(domain, *files)


def test_a_client_of_its_own_unremapped_names_is_unwired_and_wired_it_conforms(
    nodes: Nodes,
) -> None:
    nodes.start("server", SERVER)
    nodes.start("client", CLIENT)
    code, doc = _inspect(nodes.domain, *PAIR)
    found = sorted((f["code"], f["component"], f["live_name"]) for f in doc["findings"])
    assert (code, found) == (1, [("unwired", "CLIENT", "/svc_a"), ("unwired", "CLIENT", "/t_data")])
    messages = " ".join(f["message"] for f in doc["findings"])
    assert "SERVER serves it as /real/svc_a" in messages
    assert "SERVER publishes it as /real/t_data" in messages
    assert "-r svc_a:=/real/svc_a" in messages and "-r t_data:=/real/t_data" in messages
    assert doc["checked"]["calls"] == [{"node": "/client", "service": "/svc_a"}]
    nodes.stop("client")
    nodes.start("client", CLIENT, *WIRED)  # rcl rewrites its names as it starts
    code, doc = _settled(nodes.domain, *PAIR)
    assert (code, doc["findings"]) == (0, []), [f["message"] for f in doc["findings"]]
    checked = doc["checked"]
    assert checked["nodes"] == ["/server", "/client"] and checked["edges"] == 2
    assert checked["calls"] == [{"node": "/client", "service": "/real/svc_a"}]
    assert checked["subscriptions"] == [{"node": "/client", "topic": "/real/t_data"}]


def test_a_plain_node_the_library_calls_managed_is_not_managed(nodes: Nodes) -> None:
    nodes.start("server", SERVER)
    nodes.start("client", CLIENT, *WIRED)
    files = ["-l", str(DATA / "pair_library.yaml"), "-s", str(DATA / "pair_managed_schema.yaml")]
    code, doc = _inspect(nodes.domain, *files)
    found = [(f["code"], f["component"], f["live_name"]) for f in doc["findings"]]
    assert (code, found) == (1, [("not-managed", "MANAGED_CLIENT", "/client")])
    assert "/client/get_state" in doc["findings"][0]["message"]
    nodes.stop("client")
    nodes.start("client", {**CLIENT, "lifecycle": True}, *WIRED)  # managed, unconfigured
    code, doc = _inspect(nodes.domain, *files)
    found = [(f["code"], f["component"]) for f in doc["findings"]]
    # unconfigured, a managed stand-in has made none of its endpoints yet
    assert code == 1 and ("not-active", "MANAGED_CLIENT") in found
    assert "not-managed" not in {c for c, _ in found}
    assert doc["checked"]["lifecycle_states"] == {"/client": "unconfigured"}


def test_the_bundled_example_started_unwired_is_not_conformant_and_wired_it_is(
    nodes: Nodes,
) -> None:
    from rosreconf.formats.loader import load_bundled
    from rosreconf.model import Configuration
    from rosreconf.ros.launchfiles import ros2_node_arguments, wiring
    from rosreconf.ros.standin_spec import ros2_standin_spec

    bundle = load_bundled()
    library = bundle.library
    schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    for c in nominal.components:  # each node acting out only its library entry
        nodes.start(c, ros2_standin_spec(library[c]))
    only = ["--only", "object_repositioning"]
    code, doc = _inspect(nodes.domain, *only)
    codes = {f["code"] for f in doc["findings"]}
    assert (code, codes) == (1, {"unwired"}), doc["findings"]
    # the paper's reasoner calls the elbow servo by its own label; NSM3 serves its remapping
    said = {(f["component"], f["live_name"]): f["message"] for f in doc["findings"]}
    elbow = said["NREA", "/elbow/digital_servo_command"]
    assert "NSM3 serves it as /arm_servo/elbow/servo_command" in elbow
    assert "start NREA with -r elbow/digital_servo_command:=/arm_servo/elbow/servo_command" in elbow
    remaps = wiring(library, schema, nominal)
    assert len(doc["findings"]) == sum(len(r) for r in remaps.values())  # one per -r rule
    nodes.stop(*remaps)
    for c in remaps:  # the consumers again, wired as their launch would start them
        nodes.start(c, ros2_standin_spec(library[c]), *ros2_node_arguments(library, c, remaps))
    code, doc = _settled(nodes.domain, *only)
    assert (code, doc["findings"]) == (0, []), [f["message"] for f in doc["findings"]]
    assert len(doc["checked"]["nodes"]) == len(nominal.components)
