"""Compare what a ROS master says is running with the ROS-graph a configuration should have.

The expected ROS-graph (Def. 1) comes from ``rosreconf.model.validity.ros_graph``; the live one from
``rosreconf.ros.rosmaster.read_live_graph``. They speak different names: the model names nodes
after components and interfaces after labels (Omega), the master uses global ROS names. One
pair of functions maps model names to live names, and everything here goes through them::

    model                                   live (global ROS name)
    --------------------------------------  ------------------------------------------------
    component C                             <ros.namespace or />/<ros.node or C>  node_live_name
    interface label X of component C        ros.remappings[X] if given, else X;  interface_live_name
                                            a relative name is resolved in C's namespace

So NSM3 is ``/NSM3`` and its ``elbow/digital_servo_command`` is ``/arm_servo/elbow/servo_command``
(its remapping); a component with ``namespace: /arm`` and no remapping for ``joint_states``
publishes ``/arm/joint_states``.

The comparison reports (``Finding.code``): ``missing-node`` (not registered), ``dead-node``
(registered but its API does not answer: SIGKILLed nodes linger in the master),
``extra-node`` (alive, not plumbing, not in the configuration), ``missing-service`` /
``missing-topic`` (an expected node does not serve, publish or subscribe what its ROS-graph
edges say), ``wrong-type`` (the master's type of an expected topic differs), and
``unmet-requirement`` (Lemma 4: an interface a running expected node uses along its
ROS-graph edges is served or published by no live node). A ROS 2 graph (DDS discovery) also
knows the services a node calls and every endpoint's QoS, which adds ``missing-client`` (an
expected node does not call a service its edges say it calls) and ``qos-incompatible`` (the
provider's publisher offers a QoS the consumer's subscription cannot accept, by
``rosreconf.model.qos.incompatibilities``; both sides are named). ROS 2 types
(``pkg/msg/Name``) equal the library's ``pkg/Name`` (``rosreconf.model.type_key``).
Actions (``rosreconf.ros.liveactions``, ROS 1 and 2) add ``missing-action`` (the provider
does not serve it), ``missing-action-client`` (the consumer does not call it), and
``wrong-type`` and ``unmet-requirement`` as for topics.

A ROS 2 graph keeps every endpoint's own type, so ``wrong-type`` names each node whose
publisher, subscription, server or client of an expected topic or service has another type,
whichever started first. It also adds ``unserved-client`` (a live node calls a service no
live node serves), ``duplicate-node`` (two nodes announce one name; ROS 2 allows it, but
calls and parameters reach either; they are judged together) and ``not-active`` (a
component marked ``ros.lifecycle`` whose managed node is not in the active state; the
state is said).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from rosreconf.model import (
    ComponentLibrary,
    Configuration,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
)
from rosreconf.ros.edgechecks import edge_findings, unserved_findings
from rosreconf.ros.livegraph import LiveGraph, LiveNode, without_plumbing
from rosreconf.ros.livenames import Finding, interface_live_name, node_live_name, same_type

__all__ = [
    "Conformance",
    "Finding",
    "compare",
    "interface_live_name",
    "node_live_name",
    "same_type",
]


@dataclass(frozen=True)
class Conformance:
    """The outcome of comparing one configuration with a live graph.

    Attributes:
        schema: the schema's name.
        configuration: the configuration expected to run.
        live: the live graph compared (plumbing included, as read).
        expected_nodes: component -> its live node name.
        findings: every difference, in a stable order.
    """

    schema: str
    configuration: Configuration
    live: LiveGraph
    expected_nodes: dict[str, str]
    findings: tuple[Finding, ...]

    @property
    def ok(self) -> bool:
        """Tell whether the live graph conforms (no findings)."""
        return not self.findings

    @property
    def failed_components(self) -> tuple[str, ...]:
        """Return the components whose node is missing or dead, in configuration order."""
        bad = {f.component for f in self.findings if f.code in ("missing-node", "dead-node")}
        return tuple(c for c in self.configuration.components if c in bad)

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON shape ``rosreconf inspect --json`` prints."""
        return {
            "schema": self.schema,
            "conformant": self.ok,
            "master_uri": self.live.master_uri,
            "taken_at": self.live.taken_at.isoformat(),
            "configuration": self.configuration.shown,
            "expected_nodes": self.expected_nodes,
            "findings": [
                {
                    "code": f.code,
                    "component": f.component,
                    "live_name": f.live_name,
                    "message": f.message,
                }
                for f in self.findings
            ],
        }


def compare(
    configuration: Configuration,
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    live: LiveGraph,
) -> Conformance:
    """Compare ``live`` with the ROS-graph of ``configuration`` (which must be valid)."""
    graph = without_plumbing(live)
    answering: dict[str, LiveNode] = {}
    for n in graph.nodes:
        if n.answered:
            answering[n.name] = _merge(answering[n.name], n) if n.name in answering else n
    registered = {n.name for n in graph.nodes}
    comps = {c: library[c] for c in configuration.components}
    names = {c: node_live_name(comp) for c, comp in comps.items()}
    found: list[Finding] = []
    owner = {name: c for c, name in names.items()}
    for name in graph.duplicates:
        count = sum(1 for n in graph.nodes if n.name == name)
        why = (
            f"{count} nodes are named {name} (ROS 2 allows it, but service calls and "
            "parameters reach either one; give each its own name)"
        )
        found.append(Finding("duplicate-node", why, owner.get(name), name))
    for c, name in names.items():
        launch, node = comps[c].launch, answering.get(name)
        if launch is None or not launch.lifecycle or node is None:
            continue
        if node.lifecycle_state not in (None, "active"):
            why = (
                f"{c}: managed node {name} is {node.lifecycle_state}, not active: it does "
                f"nothing until activated (ros2 lifecycle set {name} activate)"
            )
            found.append(Finding("not-active", why, c, name))
    for c, name in names.items():
        role = next(r for r, x in configuration.assignment if x == c)
        if name in answering:
            continue
        if name in registered:
            why = f"{c} ({role}): {name} is registered but does not answer (killed?)"
            found.append(Finding("dead-node", why, c, name))
        else:
            found.append(Finding("missing-node", f"{c} ({role}): {name} is not running", c, name))
    for name in sorted(set(answering) - set(names.values())):
        found.append(
            Finding("extra-node", f"{name} runs but is not in the configuration", None, name)
        )
    # Calls the library declares (every option of a service requirement, under the component's
    # own name for it or under the name of any library component providing that option, as a
    # launch remapping wires it) are judged along the edges, not as unserved calls: a node
    # kept through a repair still calls the alternative it was first wired to.
    servers: dict[Interface, set[str]] = {}
    for comp in library.components:
        for iface in comp.provides:
            if iface.kind is InterfaceKind.SERVICE:
                servers.setdefault(iface, set()).add(interface_live_name(comp, iface.label))
    wired = {
        (names[c], called)
        for c, comp in comps.items()
        for req in comp.requires
        for option in req.options
        if option.kind is InterfaceKind.SERVICE
        for called in (interface_live_name(comp, option.label), *servers.get(option, ()))
    }
    found += edge_findings(configuration, library, schema, graph, answering, comps, wired)
    found += unserved_findings(answering, owner, wired)
    return Conformance(schema.name, configuration, live, names, tuple(found))


def _merge(a: LiveNode, b: LiveNode) -> LiveNode:
    """Judge two nodes of one name together: what either has, the node has."""
    return replace(
        a,
        publishes=tuple(sorted({*a.publishes, *b.publishes})),
        subscribes=tuple(sorted({*a.subscribes, *b.subscribes})),
        serves=tuple(sorted({*a.serves, *b.serves})),
        clients=tuple(sorted({*a.clients, *b.clients})),
        publish_qos={**b.publish_qos, **a.publish_qos},
        subscribe_qos={**b.subscribe_qos, **a.subscribe_qos},
        topic_types={**b.topic_types, **a.topic_types},
        service_types={**b.service_types, **a.service_types},
        lifecycle_state=a.lifecycle_state if a.lifecycle_state != "active" else b.lifecycle_state,
    )
