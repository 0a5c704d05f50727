"""Nodes in namespaces, started as ``rosreconf launch --ros2`` writes them, are wired on real rclpy.

Each component runs as its executable would: a stand-in whose names are spelled as the
node's code spells them (``scan``, ``~/odom``, ``/scan``), written here by hand from the
library's ``ros.remappings`` (``tests/data/namespaces``), so that rcl, not rosreconf, resolves
them in the node's namespace. Its node name, namespace and remappings are read off the
launch file ``rosreconf launch --ros2`` writes, and passed as launch_ros passes them
(``--ros-args -r __node:= -r __ns:= -r from:=to``). The reference for what is wired is
rclpy's own graph (``tests/ros2_probe.py``): each node's endpoints under the names rcl
resolved for it. Jazzy and Kilted, on a private domain.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import ros2_real
from test_ros2_wiring import Nodes, _inspect, _settled
from test_watch_namespaces import _uses
from test_watch_ros2 import probe
from typer.testing import CliRunner

from rosreconf.cli.app import app

DATA = Path(__file__).with_name("data") / "namespaces"
FILES = ["-l", str(DATA / "library.yaml"), "-s", str(DATA / "schema.yaml")]
SCAN, ODOM = "sensor_msgs/msg/LaserScan", "nav_msgs/msg/Odometry"
TRIGGER, GOAL = "std_srvs/srv/Trigger", "test_msgs/action/Fibonacci"
CODE: dict[str, dict[str, Any]] = {
    "lidar": {"publish": [{"topic": "/scan", "type": SCAN}]},
    "sonar": {"publish": [{"topic": "scan", "type": SCAN}]},
    "wheel_odom": {"publish": [{"topic": "~/odom", "type": ODOM}],
                   "serve": [{"service": "reset_odom", "type": TRIGGER}]},
    "estimator": {"subscribe": [{"topic": "scan", "type": SCAN}, {"topic": "odom", "type": ODOM}],
                  "action_serve": [{"action": "relocalize", "type": GOAL}]},
    "tracker": {"subscribe": [{"topic": "~/scan_in", "type": SCAN}],
                "call": [{"service": "reset_odom", "type": TRIGGER}],
                "action_call": [{"action": "relocalize", "type": GOAL}]},
    "monitor": {"subscribe": [{"topic": "scan", "type": SCAN}]},
}  # fmt: skip
"""Component -> the names its executable's code asks rclpy for (the library, read by hand)."""
BASE = {"publish": [], "subscribe": [], "serve": [], "call": [], "lifecycle": False}
RUNS = {"": ["lidar", "wheel_odom", "estimator", "tracker", "monitor"],
        "lidar": ["sonar", "wheel_odom", "estimator", "tracker", "monitor"]}  # fmt: skip
"""Failed component ("" for none) -> the components of the configuration that replaces it."""
WIRED = {
    "": {"/estimator": (["/base/wheel_odom/odom", "/scan"], []),
         "/nav/tracker": (["/scan"], ["/base/reset_odom", "/relocalize"]),
         "/sensors/monitor": (["/scan"], [])},
    "lidar": {"/estimator": (["/base/wheel_odom/odom", "/sensors/scan"], []),
              "/nav/tracker": (["/sensors/scan"], ["/base/reset_odom", "/relocalize"]),
              "/sensors/monitor": (["/sensors/scan"], [])},
}  # fmt: skip
"""Failed component -> consumer node -> (what it subscribes to, what it calls), read by rclpy."""


def _launch(tmp: Path, failed: str) -> ET.Element:
    """Return the root of the launch file ``rosreconf launch --ros2 [--fail failed]`` writes."""
    out = tmp / f"fail-{failed or 'none'}.launch.xml"
    fail = ["--fail", failed] if failed else []
    result = CliRunner().invoke(app, ["launch", "--ros2", *FILES, *fail, "-o", str(out)])
    assert result.exit_code == 0, result.stdout + result.stderr
    return ET.parse(out).getroot()


def _ros_args(node: ET.Element) -> list[str]:
    """Return the ``--ros-args`` launch_ros gives a ``<node>``: name, namespace, remappings."""
    args = ["--ros-args", "-r", f"__node:={node.get('name')}"]
    if node.get("namespace"):
        args += ["-r", f"__ns:={node.get('namespace')}"]
    for remap in node.iter("remap"):
        args += ["-r", f"{remap.get('from')}:={remap.get('to')}"]
    return args


def _spec(node: ET.Element) -> dict[str, Any]:
    """Return the stand-in spec of a ``<node>``'s executable: its code's own names."""
    name = node.get("name")
    comp = {"sonar_array": "sonar"}.get(str(name), str(name))
    return {**BASE, "name": name, "namespace": node.get("namespace") or "/", **CODE[comp]}


def _configuration(tmp: Path, failed: str) -> list[str]:
    """Write the configuration file of ``RUNS[failed]``; return inspect's options for it."""
    roles = ["ranger", "odometry", "estimator", "tracker", "monitor"]
    chosen = dict(zip(roles, RUNS[failed], strict=True))
    doc = {
        "format": "rosreconf/configuration",
        "version": 1,
        "configurations": {"namespaces": chosen},
    }
    path = tmp / f"configuration-{failed or 'none'}.json"
    path.write_text(json.dumps(doc))
    return [*FILES, "--configuration", str(path)]


@pytest.fixture(params=ros2_real.DISTROS)
def nodes(request: pytest.FixtureRequest, ros2_domain: int, tmp_path: Path) -> Iterator[Nodes]:
    """Return an empty set of stand-ins of one distribution (Jazzy, then Kilted)."""
    ros2_real.python_of(request.param)  # fail, never skip, when the venv is missing
    started = Nodes(str(request.param), ros2_domain, tmp_path)
    try:
        yield started
    finally:
        started.close()


@pytest.mark.parametrize("failed", ["", "lidar"], ids=["nominal", "lidar-failed"])
def test_nodes_launched_as_written_use_the_names_rosreconf_resolves(
    nodes: Nodes,
    failed: str,
    tmp_path: Path,
) -> None:
    root = _launch(tmp_path, failed)
    started = []
    for node in root.iter("node"):
        nodes.start(str(node.get("name")), _spec(node), *_ros_args(node))
        started.append(f"{(node.get('namespace') or '').rstrip('/')}/{node.get('name')}")
    code, doc = _settled(nodes.domain, *_configuration(tmp_path, failed))
    assert (code, doc["findings"]) == (0, []), [f["message"] for f in doc["findings"]]
    env = ros2_real.node_env(nodes.domain, tmp_path / "probe")
    python = ros2_real.python_of(nodes.distro)
    seen = probe(env, nodes.domain, wait_for=started, python=python, until_wired=True)
    assert {n: _uses(seen, n) for n in WIRED[failed]} == WIRED[failed]
    assert seen["dangling"] == {"calls": [], "subscriptions": []}


def test_unwired_namespaced_nodes_are_told_the_rules_that_wire_them(
    nodes: Nodes,
    tmp_path: Path,
) -> None:
    root = _launch(tmp_path, "lidar")
    for node in root.iter("node"):  # every node as its executable starts with no remapping
        bare = ET.Element("node", {k: v for k, v in node.attrib.items()})
        nodes.start(str(node.get("name")), _spec(node), *_ros_args(bare))
    code, doc = _inspect(nodes.domain, *_configuration(tmp_path, "lidar"))
    assert code == 1
    unwired = sorted((f["component"], f["live_name"]) for f in doc["findings"]
                     if f["code"] == "unwired")  # fmt: skip
    assert unwired == [
        ("estimator", "/odom"),
        ("estimator", "/scan"),
        ("tracker", "/nav/relocalize"),
        ("tracker", "/nav/reset_odom"),
        ("tracker", "/nav/tracker/scan_in"),
    ], [f["message"] for f in doc["findings"]]
    told: dict[str, list[str]] = {}
    for f in doc["findings"]:
        if f["code"] == "unwired":
            rules = re.findall(r"-r (\S+:=[^\s)]+)", f["message"])
            told.setdefault(f["component"], []).extend(rules)
    assert "scan:=/sensors/scan" in told["estimator"]
    assert "~/scan_in:=/sensors/scan" in told["tracker"]
    parts = ("send_goal", "cancel_goal", "get_result", "feedback", "status")
    assert {f"relocalize/_action/{p}:=/relocalize/_action/{p}" for p in parts} <= set(
        told["tracker"]
    )
    for consumer, rules in told.items():  # restarted with exactly the rules it was told
        nodes.stop(consumer)
        node = next(n for n in root.iter("node") if n.get("name") == consumer)
        bare = ET.Element("node", {k: v for k, v in node.attrib.items()})
        args = _ros_args(bare) + [a for r in rules for a in ("-r", r)]
        nodes.start(consumer, _spec(node), *args)
    code, doc = _settled(nodes.domain, *_configuration(tmp_path, "lidar"))
    assert (code, doc["findings"]) == (0, []), [f["message"] for f in doc["findings"]]
