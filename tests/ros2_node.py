"""Run real ROS 2 nodes (rclpy over Fast DDS) from a JSON spec for the tests, or dump rclpy's graph.

Run with a ROS 2 venv's python (``.venv-ros2-jazzy/bin/python tests/ros2_node.py SPEC.json``),
never with rosreconf's own: the ROS 2 wheels re-execute their interpreter with their own
library path. One process is one rclpy context (one DDS participant) holding every node of
the spec, each its own ``rclpy.node.Node``::

    {"nodes": [{"name": "talker", "namespace": "/demo",
                "publishers": [{"name": "/chatter", "type": "std_msgs/msg/String",
                                "qos": {"reliability": "best_effort", "depth": 5}}],
                "subscriptions": [...], "servers": [{"name": "/reset",
                "type": "std_srvs/srv/Trigger"}], "clients": [...],
                "lifecycle": "inactive"}]}

``lifecycle`` (unconfigured, inactive or active) makes the node an
``rclpy.lifecycle.LifecycleNode`` taken to that state; ``configure_seconds`` makes its
``on_configure`` take that long (a node slow to configure, as on a loaded robot). The script
prints ``ready`` once every node exists and spins until SIGTERM or SIGINT (then it leaves the
domain cleanly).

``--graph N SECONDS`` instead joins the domain with one node of its own (``_rclpy_graph``,
hidden), waits until at least N other nodes are seen and the graph has not changed for 3.5 s
(at most SECONDS), and prints rclpy's own view as one JSON document: per node its
publishers, subscriptions, services and clients with types (``get_*_names_and_types_by_node``)
and per topic each endpoint's QoS (``get_publishers_info_by_topic``,
``get_subscriptions_info_by_topic``). It is the reference rosreconf's reading is held to.
"""

from __future__ import annotations

import importlib
import json
import signal
import sys
import time
from typing import Any

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import (
    DurabilityPolicy,
    Duration,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)


def _type(name: str) -> Any:
    """Return the rclpy class of ``pkg/msg/Type`` or ``pkg/srv/Type``."""
    pkg, kind, typ = name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), typ)


def _qos(doc: dict[str, Any]) -> QoSProfile:
    """Return the rclpy profile of a rosreconf-style QoS mapping (defaults: rmw's)."""
    depth = int(doc.get("depth", 10))
    qos = QoSProfile(
        history=HistoryPolicy.KEEP_ALL if depth == 0 else HistoryPolicy.KEEP_LAST,
        depth=max(depth, 1),
        reliability=ReliabilityPolicy.BEST_EFFORT
        if doc.get("reliability") == "best_effort"
        else ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL
        if doc.get("durability") == "transient_local"
        else DurabilityPolicy.VOLATILE,
        liveliness=LivelinessPolicy.MANUAL_BY_TOPIC
        if doc.get("liveliness") == "manual_by_topic"
        else LivelinessPolicy.AUTOMATIC,
    )
    if doc.get("deadline") is not None:
        qos.deadline = Duration(seconds=float(doc["deadline"]))
    if doc.get("lease_duration") is not None:
        qos.liveliness_lease_duration = Duration(seconds=float(doc["lease_duration"]))
    return qos


def _make(spec: dict[str, Any], context: Any) -> Node:
    """Create one node of ``spec`` with its endpoints, in its lifecycle state if it has one."""
    ns = spec.get("namespace", "/")
    state = spec.get("lifecycle")
    if state is not None:
        from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn

        delay = float(spec.get("configure_seconds", 0.0))

        class Managed(LifecycleNode):  # type: ignore[misc]
            def on_configure(self, state: Any) -> Any:
                time.sleep(delay)  # in the node's executor, as a slow real configure is
                return TransitionCallbackReturn.SUCCESS

        node: Node = Managed(spec["name"], namespace=ns, context=context)
    else:
        node = Node(spec["name"], namespace=ns, context=context)
    for p in spec.get("publishers", []):
        node.create_publisher(_type(p["type"]), p["name"], _qos(p.get("qos", {})))
    for s in spec.get("subscriptions", []):
        node.create_subscription(
            _type(s["type"]), s["name"], lambda _m: None, _qos(s.get("qos", {}))
        )
    for s in spec.get("servers", []):
        typ = _type(s["type"])
        node.create_service(typ, s["name"], lambda _rq, rs: rs)
    for c in spec.get("clients", []):
        node.create_client(_type(c["type"]), c["name"])
    if state in ("inactive", "active"):
        node.trigger_configure()  # type: ignore[attr-defined]
    if state == "active":
        node.trigger_activate()  # type: ignore[attr-defined]
    return node


def serve(path: str) -> None:
    """Create the spec's nodes in one context, say ``ready``, spin until told to stop."""
    with open(path, encoding="utf-8") as f:
        spec = json.load(f)
    context = rclpy.Context()
    rclpy.init(context=context)
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    executor = SingleThreadedExecutor(context=context)
    nodes = [_make(n, context) for n in spec["nodes"]]
    for n in nodes:
        executor.add_node(n)
    print("ready", flush=True)
    while not stop:
        executor.spin_once(timeout_sec=0.1)
    for n in nodes:
        n.destroy_node()
    rclpy.shutdown(context=context)


def _endpoint_qos(info: Any) -> dict[str, Any]:
    """Return one endpoint's QoS as rosreconf writes it (depth left out: not discovered)."""
    q = info.qos_profile

    def seconds(d: Any) -> float | None:
        ns = d.nanoseconds
        return None if ns == 0 or ns >= (1 << 31) * 10**9 else ns / 1e9  # rmw's "infinite"

    return {
        "reliability": "best_effort"
        if q.reliability == ReliabilityPolicy.BEST_EFFORT
        else "reliable",
        "durability": "transient_local"
        if q.durability == DurabilityPolicy.TRANSIENT_LOCAL
        else "volatile",
        "deadline": seconds(q.deadline),
        "liveliness": "manual_by_topic"
        if q.liveliness == LivelinessPolicy.MANUAL_BY_TOPIC
        else "automatic",
        "lease_duration": seconds(q.liveliness_lease_duration),
    }


QUIET = 3.5
"""Seconds rclpy's graph must stay unchanged before it is the reference: one Fast DDS
announcement period (3 s) and a margin, as rosreconf's own first read. Quiet for 1 s, a
loaded machine once gave a reference that differed from rosreconf's snapshot in one node's
endpoints, all 40 nodes present (which side was short was not recorded)."""


def graph(at_least: int, seconds: float) -> None:
    """Print rclpy's graph once it has ``at_least`` other nodes and is quiet for ``QUIET`` s."""
    rclpy.init()
    node = Node("_rclpy_graph")
    deadline = time.monotonic() + seconds
    last: Any = None
    quiet_since = time.monotonic()
    doc: dict[str, Any] = {}
    while time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
        doc = _snapshot(node)
        key = json.dumps(doc, sort_keys=True)
        if key != last:
            last, quiet_since = key, time.monotonic()
        elif len(doc["nodes"]) >= at_least and time.monotonic() - quiet_since >= QUIET:
            break
    print(json.dumps(doc, sort_keys=True), flush=True)
    node.destroy_node()
    rclpy.shutdown()


def _snapshot(node: Node) -> dict[str, Any]:
    """Return rclpy's graph now: nodes with endpoints and types, topic QoS per node."""
    nodes = []
    topics: set[str] = set()
    for name, ns in node.get_node_names_and_namespaces():
        if name == "_rclpy_graph":
            continue
        full = (ns.rstrip("/") + "/" + name) if ns != "/" else "/" + name
        try:
            entry = {
                "name": full,
                "publishes": sorted(
                    (t, list(ty)) for t, ty in node.get_publisher_names_and_types_by_node(name, ns)
                ),
                "subscribes": sorted(
                    (t, list(ty)) for t, ty in node.get_subscriber_names_and_types_by_node(name, ns)
                ),
                "serves": sorted(
                    (t, list(ty)) for t, ty in node.get_service_names_and_types_by_node(name, ns)
                ),
                "clients": sorted(
                    (t, list(ty)) for t, ty in node.get_client_names_and_types_by_node(name, ns)
                ),
            }
        except Exception:  # the node left between the two calls
            continue
        nodes.append(entry)
        topics |= {t for t, _ in (*entry["publishes"], *entry["subscribes"])}
    qos: dict[str, Any] = {}
    for topic in sorted(topics):
        for kind, infos in (
            ("publishes", node.get_publishers_info_by_topic(topic)),
            ("subscribes", node.get_subscriptions_info_by_topic(topic)),
        ):
            for info in infos:
                if info.node_name == "_rclpy_graph":
                    continue
                ns = info.node_namespace
                full = (
                    (ns.rstrip("/") + "/" + info.node_name) if ns != "/" else "/" + info.node_name
                )
                qos.setdefault(full, {}).setdefault(kind, {})[topic] = _endpoint_qos(info)
    return {"nodes": sorted(nodes, key=lambda n: n["name"]), "qos": qos}


if __name__ == "__main__":
    if sys.argv[1] == "--graph":
        graph(int(sys.argv[2]), float(sys.argv[3]))
    else:
        serve(sys.argv[1])
