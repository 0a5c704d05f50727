"""The ROS 2 graph reader against real DDS participants announcing what rmw announces.

Each announcer (tests/ros2_announcer.py) is a separate process with a real cyclonedds
participant on loopback, built from the rmw sources independently of the decoder. These
tests check that ``rosreconf.ros.ros2.discovery`` reads back exactly what was announced, in
both Gid layouts, and ignores what is not ROS.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import ros2_harness
from conftest import Announce
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.model.qos import Durability, Liveliness, QosProfile, Reliability
from rosreconf.ros.livegraph import from_json, to_json, without_plumbing
from rosreconf.ros.ros2.discovery import read_ros2_graph

TALKER: dict[str, Any] = {
    "namespace": "/demo",
    "name": "talker",
    "publishers": [
        {
            "name": "/chatter",
            "type": "std_msgs/msg/String",
            "qos": {"reliability": "best_effort", "deadline": 0.5, "depth": 5},
        },
        {
            "name": "/demo/map",
            "type": "nav_msgs/msg/OccupancyGrid",
            "qos": {"durability": "transient_local", "depth": 1},
        },
    ],
    "subscriptions": [
        {
            "name": "/cmd",
            "type": "geometry_msgs/msg/Twist",
            "qos": {"liveliness": "manual_by_topic", "lease_duration": 3},
        }
    ],
    "servers": [{"name": "/demo/reset", "type": "std_srvs/srv/Trigger"}],
    "clients": [{"name": "/add_two_ints", "type": "example_interfaces/srv/AddTwoInts"}],
}
LISTENER: dict[str, Any] = {
    "namespace": "/",
    "name": "listener",
    "subscriptions": [{"name": "/chatter", "type": "std_msgs/msg/String"}],
}


@pytest.mark.parametrize(("distro", "gid_size"), [("humble", 24), ("jazzy", 16)])
def test_reads_nodes_endpoints_types_and_qos(
    announce: Announce, ros2_domain: int, distro: str, gid_size: int
) -> None:
    announce([TALKER, LISTENER], gid_size=gid_size)
    announce([{"name": "not_ros", "publishers": [{"name": "/chatter", "type": "a/msg/B"}]}],
             gid_size=gid_size, ros_participant=False)  # fmt: skip

    for which in (distro, None):  # named distribution, and both layouts tried
        graph = read_ros2_graph(ros2_domain, distro=which)
        assert graph.ros_version == 2 and graph.master_uri == f"ros2://domain/{ros2_domain}"
        assert graph.names == ("/demo/talker", "/listener"), which
        talker = graph.node("/demo/talker")
        assert talker.answered
        assert talker.publishes == ("/chatter", "/demo/map", "/parameter_events", "/rosout")
        assert talker.subscribes == ("/cmd", "/parameter_events")
        assert "/demo/reset" in talker.serves and "/demo/talker/get_parameters" in talker.serves
        assert talker.clients == ("/add_two_ints",)
        assert graph.topic_types["/chatter"] == "std_msgs/msg/String"
        assert graph.service_types["/add_two_ints"] == "example_interfaces/srv/AddTwoInts"
        assert talker.publish_qos["/chatter"] == QosProfile(
            reliability=Reliability.BEST_EFFORT, deadline=0.5, depth=None
        )  # announced with depth 5: DDS discovery does not carry it (unknown, not made up)
        assert talker.publish_qos["/demo/map"].durability is Durability.TRANSIENT_LOCAL
        cmd = talker.subscribe_qos["/cmd"]
        assert (cmd.liveliness, cmd.lease_duration) == (Liveliness.MANUAL_BY_TOPIC, 3.0)

        clean = without_plumbing(graph)
        talker = clean.node("/demo/talker")
        assert talker.publishes == ("/chatter", "/demo/map")
        assert talker.serves == ("/demo/reset",)
        assert set(clean.topic_types) == {"/chatter", "/demo/map", "/cmd"}
        assert set(clean.service_types) == {"/demo/reset", "/add_two_ints"}
        assert from_json(to_json(graph)) == graph


def test_wrong_distro_sees_no_nodes(announce: Announce, ros2_domain: int) -> None:
    announce([LISTENER], gid_size=24)
    assert read_ros2_graph(ros2_domain, distro="jazzy", timeout=2).names == ()
    assert read_ros2_graph(ros2_domain, distro="humble").names == ("/listener",)


def test_killed_participant_leaves_the_graph(announce: Announce, ros2_domain: int) -> None:
    from rosreconf.ros.ros2.discovery import Ros2Discovery

    talker = announce([TALKER])
    announce([LISTENER])
    with Ros2Discovery(ros2_domain) as session:
        assert session.read().names == ("/demo/talker", "/listener")
        talker.kill()
        import time

        deadline = time.monotonic() + 15
        while "/demo/talker" in session.read().names:
            assert time.monotonic() < deadline, "the killed participant never left"
            time.sleep(0.1)
        assert session.read().names == ("/listener",)


PATROL = Path(__file__).with_name("data") / "ros2"


def test_node_names_from_the_network_are_escaped(
    announce: Announce, ros2_domain: int, runner: CliRunner
) -> None:
    """Imitation (rclpy refuses such names): a node named with terminal escape sequences
    that would retitle and clear the terminal and forge a verdict line."""
    evil = "x\x1b]0;pwned\x07\x1b[2J\rrosreconf: conformant (0 problems)\x9b31m"
    announce([{**LISTENER, "name": evil, "plumbing": False}])
    files = ["-l", str(PATROL / "patrol_library.yaml"), "-s", str(PATROL / "patrol_schema.yaml")]
    result = runner.invoke(app, ["inspect", "--ros2", "--domain", str(ros2_domain), *files])
    assert result.exit_code == 1
    assert "extra-node: /x\\x1b]0;pwned\\x07" in result.stdout
    assert not any(c in result.stdout for c in "\x1b\x07\r\x9b")
    snap = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(ros2_domain)])
    assert not any(c in snap.stdout for c in "\x1b\x07\r\x9b")


def test_empty_node_name_is_hidden_and_a_slash_in_one_escaped(
    announce: Announce, ros2_domain: int, runner: CliRunner
) -> None:
    """Imitation (rcl refuses such names): nodes named ``""`` and ``/`` in ``/``, ``a/b`` in
    ``/ns``. Reference: ``ros2 node list`` hides a node whose base name is empty
    (ros2cli's ``get_node_names`` keeps ``t[0] and not t[0].startswith("_")``); a ``/`` in a
    base name is shown escaped, as other characters no ROS name can hold, never as ``//`` or
    as a node ``b`` of namespace ``/ns/a``."""
    forged = [{"namespace": ns, "name": name, "plumbing": False}
              for ns, name in (("/", ""), ("/", "/"), ("/ns", "a/b"))]  # fmt: skip
    announce([*forged, LISTENER])
    graph = read_ros2_graph(ros2_domain)
    assert graph.names == ("/", "/\\x2f", "/listener", "/ns/a\\x2fb")
    assert without_plumbing(graph).names == ("/\\x2f", "/listener", "/ns/a\\x2fb")
    files = ["-l", str(PATROL / "patrol_library.yaml"), "-s", str(PATROL / "patrol_schema.yaml")]
    result = runner.invoke(app, ["inspect", "--ros2", "--domain", str(ros2_domain), *files])
    extra = sorted(re.findall(r"extra-node: (\S+)", result.stdout))
    assert extra == ["/\\x2f", "/listener", "/ns/a\\x2fb"], result.stdout


def _snapshot(domain: int) -> subprocess.CompletedProcess[str]:
    """Run ``snapshot --ros2`` as a process (its stderr is what a user sees, C library included)."""
    return subprocess.run(
        [sys.executable, "-m", "rosreconf", "snapshot", "--ros2", "--domain", str(domain)],
        capture_output=True,
        text=True,
        env={**ros2_harness.dds_env(), "COLUMNS": "200"},
        timeout=60,
    )


def test_undecodable_discovery_is_counted_and_said_once(
    announce: Announce, ros2_domain: int
) -> None:
    """Imitation: a participant writes, five times, a ros_discovery_info sample no reader
    can decode (a node name longer than the message's bound); another is fine. (Cyclone
    drops these without a message; real Fast DDS samples that fail do make one, which
    test_ros2_real's test_cyclone_messages_are_said_once_per_cause covers.)"""
    announce([{**LISTENER, "name": "n" * 300, "plumbing": False}], unbounded_names=True, repeat=5)
    announce([LISTENER])
    out = _snapshot(ros2_domain)
    assert out.returncode == 0, out.stderr
    assert [n["name"] for n in json.loads(out.stdout)["nodes"]] == ["/listener"]
    lines = out.stderr.splitlines()
    assert [line for line in lines if re.match(r"^\d+\.\d+ +\[", line)] == []
    said = [line for line in lines if "could not be decoded" in line]
    assert len(said) == 1, out.stderr
    assert "1 ROS 2 participant(s)" in said[0]


def test_a_participant_whose_newest_node_list_never_arrives_is_exit_3_not_a_partial_graph(
    announce: Announce, ros2_domain: int
) -> None:
    """Fake (provokes what Cyclone did once at 40 real Jazzy nodes: it failed to decode one
    Fast DDS participant's newest ros_discovery_info after an older one had decoded). The
    announcer's info names all its nodes but the last, whose endpoints exist: what a reader
    holds when the newest sample never arrives. ``snapshot`` returned the older list with
    exit 0; a partial answer is now refused with exit 3, saying why."""
    late = {
        "name": "late",
        "plumbing": False,
        "publishers": [{"name": "/late", "type": "std_msgs/msg/String"}],
    }
    announce([LISTENER, late], stale_newest=True)
    out = _snapshot(ros2_domain)
    assert out.returncode == 3, (out.stdout, out.stderr)
    assert out.stdout == ""
    assert "1 ROS 2 participant(s) announce endpoints that no node" in out.stderr
    assert "Traceback" not in out.stderr
