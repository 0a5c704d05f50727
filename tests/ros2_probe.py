#!/usr/bin/env python3
"""Read a ROS 2 graph with rclpy itself, the tests' independent reference (run under rclpy).

Usage: ros2_probe.py SECONDS [--wait-for NAME ...] [--until-wired [--wired NODE ...]] [NODE ...].
Prints one JSON
document:
{"nodes": [full names], "topics": {name: [types]}, "services": {name: [types]},
 "states": {node: lifecycle state label, via its get_state service},
 "dangling": {"calls": [[node, service]], "subscriptions": [[node, topic]]},
 "endpoints": {node: {"publishes": [...], "subscribes": [...], "serves": [...], "calls": [...]}}}:
each service a node calls that no node serves, and each topic it subscribes that no node
publishes (the probe itself, /rosout and /parameter_events left out), read per node from
rclpy's graph; and every node's own endpoints under the names rcl resolved for it (hidden
nodes, /rosout, /parameter_events and a node's own parameter services left out).

It reads once every ``--wait-for`` name (a node, topic or service) is seen and the graph has
then not changed for 1 s, or after SECONDS at most: discovery takes longer on a busy machine,
so a fixed sleep would make the tests that read it fail by chance. ``--until-wired`` then reads
again until nothing dangles (of the NODEs, when some are named: nodes taken out of service
may keep calling a dead provider for good, and waiting on them ran out the whole SECONDS);
``--wired NODE`` names the nodes it waits on instead, without asking their states (a plain
node has no get_state to ask, and a node that calls an unchosen alternative dangles for good).
"""

from __future__ import annotations

import argparse
import faulthandler
import json
import sys
import time
from typing import Any

import rclpy
from lifecycle_msgs.srv import GetState


def _graph(node: Any) -> tuple[list[str], dict[str, Any], dict[str, Any]]:
    names = sorted((ns.rstrip("/") + "/" + n) for n, ns in node.get_node_names_and_namespaces())
    topics = {k: sorted(v) for k, v in node.get_topic_names_and_types()}
    services = {k: sorted(v) for k, v in node.get_service_names_and_types()}
    return names, topics, services


def _dangling(node: Any) -> dict[str, list[list[str]]]:
    """Return each node's calls that nothing serves and subscriptions nothing publishes."""
    calls, subscriptions = [], []
    nodes = [(n, ns) for n, ns in node.get_node_names_and_namespaces()]
    served = {
        s for n, ns in nodes for s, _ in node.get_service_names_and_types_by_node(n, ns)
    }  # servers only: the graph-wide service list holds clients' names too
    for name, ns in nodes:
        full = ns.rstrip("/") + "/" + name
        if name.startswith("_"):  # hidden: this probe, rosreconf's lifecycle agent
            continue
        for service, _ in node.get_client_names_and_types_by_node(name, ns):
            if service not in served:
                calls.append([full, service])
        for topic, _ in node.get_subscriber_names_and_types_by_node(name, ns):
            if topic.startswith(("/rosout", "/parameter_events")):
                continue
            if node.count_publishers(topic) == 0:
                subscriptions.append([full, topic])
    return {"calls": sorted(calls), "subscriptions": sorted(subscriptions)}


PLUMBING = ("/rosout", "/parameter_events")
PARAMETER_SERVICES = ("describe_parameters", "get_parameter_types", "get_parameters",
                      "get_type_description", "list_parameters", "set_parameters",
                      "set_parameters_atomically")  # fmt: skip


def _endpoints(node: Any) -> dict[str, dict[str, list[str]]]:
    """Return each node's publishers, subscriptions, servers and clients, by full name."""
    out = {}
    for name, ns in node.get_node_names_and_namespaces():
        if name.startswith("_"):
            continue
        full = ns.rstrip("/") + "/" + name
        own = {f"{full}/{p}" for p in PARAMETER_SERVICES}
        reads = {
            "publishes": node.get_publisher_names_and_types_by_node(name, ns),
            "subscribes": node.get_subscriber_names_and_types_by_node(name, ns),
            "serves": node.get_service_names_and_types_by_node(name, ns),
            "calls": node.get_client_names_and_types_by_node(name, ns),
        }
        out[full] = {
            k: sorted(n for n, _ in v if not n.startswith(PLUMBING) and n not in own)
            for k, v in reads.items()
        }
    return out


def _of(dangling: dict[str, list[list[str]]], nodes: list[str]) -> list[list[str]]:
    """Return the dangling calls and subscriptions of ``nodes`` (of every node if none)."""
    return [d for found in dangling.values() for d in found if not nodes or d[0] in nodes]


def main() -> int:
    """Print what rclpy's graph API and the nodes' get_state services say."""
    faulthandler.enable()  # a crash of rclpy (Kilted's SIGSEGV) leaves its stacks on stderr
    ap = argparse.ArgumentParser()
    ap.add_argument("seconds", type=float)
    ap.add_argument("--wait-for", action="append", default=[])
    ap.add_argument("--until-wired", action="store_true")
    ap.add_argument("--wired", action="append", default=[])
    ap.add_argument("nodes", nargs="*")
    args = ap.parse_intermixed_args()
    nodes = args.nodes
    rclpy.init()
    node = rclpy.create_node("_rosreconf_probe")
    deadline = time.monotonic() + args.seconds
    last, since = None, time.monotonic()
    while time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.2)
        graph = _graph(node)
        if graph != last:
            last, since = graph, time.monotonic()
        seen = {*graph[0], *graph[1], *graph[2]}
        if set(args.wait_for) <= seen and time.monotonic() - since >= 1.0:
            break
    # "nothing dangles" is a claim about the settled graph: a provider's endpoints that this
    # reader has not discovered yet are read again until they are, or the deadline passes
    dangling = _dangling(node)
    while args.until_wired and _of(dangling, args.wired or nodes) and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.2)
        dangling = _dangling(node)
    names, topics, services = _graph(node)
    states = {}
    for name in nodes:
        client = node.create_client(GetState, f"{name}/get_state")
        if not client.wait_for_service(timeout_sec=10.0):
            states[name] = None
            continue
        future = client.call_async(GetState.Request())
        rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
        states[name] = future.result().current_state.label if future.done() else None
    doc = {"nodes": names, "topics": topics, "services": services, "states": states}
    doc["dangling"] = dangling
    doc["endpoints"] = _endpoints(node)
    print(json.dumps(doc))
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
