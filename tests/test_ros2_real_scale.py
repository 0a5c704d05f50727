"""``snapshot --ros2`` equals rclpy's own graph API at 40 real nodes, on Jazzy and Kilted.

Forty nodes as forty processes would take this 2-core machine a minute to start, so here
(and only here) each process holds eight nodes, each its own ``rclpy.node.Node`` in one
rclpy context: still real rclpy over Fast DDS, five participants. The nodes publish,
subscribe, serve and call with std_msgs/std_srvs types, in namespaces, with varied QoS
(best effort, transient local, deadlines, manual liveliness with a lease), and one of
them is a lifecycle node. The reference is rclpy's graph API, asked from a separate
process (``ros2_node.py --graph``): ``get_node_names_and_namespaces``,
``get_{publisher,subscriber,service,client}_names_and_types_by_node``, and
``get_{publishers,subscriptions}_info_by_topic`` for QoS (history depth left out:
discovery does not carry it, and rosreconf says null).
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from typing import Any

import pytest
import ros2_harness
import ros2_real
from typer.testing import CliRunner

from rosreconf.cli.app import app

NODES, PER_PROCESS = 40, 8
TYPES = ("std_msgs/msg/String", "std_msgs/msg/Int32", "std_msgs/msg/Float64")
QOS: tuple[dict[str, Any], ...] = (
    {},
    {"reliability": "best_effort"},
    {"durability": "transient_local", "depth": 1},
    {"deadline": 0.5},
    {"liveliness": "manual_by_topic", "lease_duration": 2.0},
)


def _node(i: int) -> dict[str, Any]:
    """Return node ``i`` of the 40: a deterministic mix of endpoints, names and QoS."""
    ns = ("/", "/robot", "/robot/arm")[i % 3]
    topic = f"/t{i % 7}"
    node: dict[str, Any] = {
        "name": f"n{i}",
        "namespace": ns,
        "publishers": [{"name": topic, "type": TYPES[i % 7 % 3], "qos": QOS[i % 5]}],
        "subscriptions": [
            {"name": f"/t{(i + 1) % 7}", "type": TYPES[(i + 1) % 7 % 3], "qos": QOS[(i + 2) % 5]}
        ],
        "servers": [{"name": f"srv{i}", "type": "std_srvs/srv/Trigger"}] if i % 4 == 0 else [],
        "clients": [{"name": f"/robot/srv{i - 1}", "type": "std_srvs/srv/Trigger"}]
        if i % 4 == 1
        else [],
    }
    if i == 7:
        node["lifecycle"] = "inactive"
    return node


@pytest.fixture(scope="module", params=ros2_real.DISTROS)
def forty(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[ros2_real.Ros2System]:
    """Run the 40 nodes, eight per process, on a private domain of the round's distro."""
    distro = str(request.param)
    system = ros2_real.Ros2System.on_a_free_domain(
        distro, tmp_path_factory.mktemp(f"forty-{distro}")
    )
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CYCLONEDDS_URI", ros2_harness.loopback_config())
        try:
            for first in range(0, NODES, PER_PROCESS):
                system.start(*(_node(i) for i in range(first, first + PER_PROCESS)))
            yield system
        finally:
            system.stop()


def _ours(snapshot: dict[str, Any]) -> tuple[list[Any], dict[str, Any]]:
    """Return the snapshot in the reference's shape: per node endpoints with types, QoS."""
    nodes, qos = [], {}
    for n in snapshot["nodes"]:
        topics, services = n["types"]["topics"], n["types"]["services"]
        nodes.append(
            {
                "name": n["name"],
                "publishes": [[t, [topics[t]]] for t in n["publishes"]],
                "subscribes": [[t, [topics[t]]] for t in n["subscribes"]],
                "serves": [[s, [services[s]]] for s in n["serves"]],
                "clients": [[s, [services[s]]] for s in n["clients"]],
            }
        )
        qos[n["name"]] = {
            side: {t: {k: v for k, v in q.items() if k != "depth"} for t, q in by.items()}
            for side, by in n["qos"].items()
            if by
        }
    return sorted(nodes, key=lambda n: n["name"]), qos


def _second_look(domain: int, ours: list[Any], theirs: list[Any], stderr: str) -> str:
    """Describe a short snapshot: which nodes it missed, and what a fresh read sees now.

    A diagnosis, not a retry: the test still fails. It tells a participant lost for a while
    (the fresh read sees all) from one whose nodes stay unseen (counts of DDS participants,
    ROS participants and endpoints; stale and undecodable participants).
    """
    from rosreconf.ros.ros2.discovery import Ros2Discovery

    names = {n["name"] for n in ours}
    missing = sorted(n["name"] for n in theirs if n["name"] not in names)
    with Ros2Discovery(domain) as again:
        graph = again.read()
        seen = (
            f"{len(graph.nodes)} nodes, {again.participants} DDS participants, "
            f"{again.ros_participants} ROS participants, {again.endpoints} ROS endpoints, "
            f"{len(again.stale)} stale, {len(again.undecodable)} undecodable"
        )
    return (
        f"snapshot saw {len(ours)} of {NODES} nodes; missing {missing}; a fresh read now sees "
        f"{seen}; snapshot's stderr: {stderr!r}"
    )


def _differences(ours: list[Any], theirs: list[Any]) -> str:
    """Say, per node and field, what the snapshot has that rclpy has not, and the reverse."""
    said = []
    for mine, ref in zip(ours, theirs, strict=True):
        for field in ("publishes", "subscribes", "serves", "clients"):
            extra = [e for e in mine[field] if e not in ref[field]]
            lack = [e for e in ref[field] if e not in mine[field]]
            if extra or lack:
                said.append(f"{mine['name']} {field}: only ours {extra}, only rclpy's {lack}")
    return "; ".join(said)


def test_snapshot_equals_rclpy_graph_at_40_nodes(
    forty: ros2_real.Ros2System, runner: CliRunner
) -> None:
    reference = forty.rclpy_graph(NODES)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CYCLONEDDS_URI", ros2_harness.loopback_config())
        started = time.monotonic()
        result = runner.invoke(app, ["snapshot", "--ros2", "--domain", str(forty.domain)])
        took = time.monotonic() - started
    assert result.exit_code == 0, result.stderr
    snapshot = json.loads(result.stdout)
    nodes, qos = _ours(snapshot)
    if len(nodes) != NODES:  # rare (1 fresh clone in 16): say what a second look sees
        pytest.fail(_second_look(forty.domain, nodes, reference["nodes"], result.stderr))
    assert len(nodes) == len(reference["nodes"]) == NODES
    assert nodes == reference["nodes"], _differences(nodes, reference["nodes"])
    assert qos == reference["qos"]
    states = {n["name"]: n["lifecycle_state"] for n in snapshot["nodes"] if n["lifecycle_state"]}
    assert states == {"/robot/n7": "inactive"}
    print(
        f"{forty.distro}: {len(nodes)} nodes equal rclpy's; snapshot took {took:.2f} s in-process"
    )
