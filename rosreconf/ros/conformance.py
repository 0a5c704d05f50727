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
(``pkg/msg/Name``) equal the library's ``pkg/Name``.

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
    Component,
    ComponentLibrary,
    Configuration,
    InterfaceKind,
    InteroperabilitySchema,
    VertexKind,
)
from rosreconf.model.qos import incompatibilities
from rosreconf.model.validity import ros_graph
from rosreconf.ros.livegraph import LiveGraph, LiveNode, without_plumbing


def _join(namespace: str, name: str) -> str:
    """Return the global name of ``name`` in ``namespace`` (``/arm`` + ``x`` -> ``/arm/x``)."""
    parts = [p for p in (*namespace.split("/"), *name.split("/")) if p]
    return "/" + "/".join(parts)


def node_live_name(component: Component) -> str:
    """Return the global name the node of ``component`` has on the master.

    The node's own name (``ros.node``) in its namespace, never the library name: ``import``
    names two live ``scan_listener`` nodes ``scan_listener`` and ``robot_scan_listener``, and
    only the second has a namespace to tell them apart.
    """
    return _join(component.namespace or "/", component.node_name)


def interface_live_name(component: Component, label: str) -> str:
    """Return the global ROS name ``component`` uses for its interface ``label``.

    The remapping (``ros.remappings``, label -> real name) wins; a relative name is resolved
    in the component's namespace, as ROS resolves it for a node started there.
    """
    launch = component.launch
    target = launch.remappings.get(label, label) if launch else label
    if target.startswith("/"):
        return _join("/", target)
    return _join((launch.namespace if launch else None) or "/", target)


@dataclass(frozen=True)
class Finding:
    """One way the live graph differs from the expected ROS-graph.

    Attributes:
        code: ``missing-node``, ``dead-node``, ``extra-node``, ``missing-service``,
            ``missing-topic``, ``wrong-type``, ``unmet-requirement``, and from a ROS 2
            graph ``missing-client``, ``qos-incompatible``, ``unserved-client``,
            ``duplicate-node`` and ``not-active``.
        message: the difference in plain words.
        component: the component concerned, if any (None for extra nodes).
        live_name: the global ROS name concerned (node, topic or service).
    """

    code: str
    message: str
    component: str | None
    live_name: str


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
            "configuration": self.configuration.mapping,
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
    # own name for it) are judged along the edges, not as unserved calls.
    wired = {
        (names[c], interface_live_name(comp, option.label))
        for c, comp in comps.items()
        for req in comp.requires
        for option in req.options
        if option.kind is InterfaceKind.SERVICE
    }
    found += _edges(configuration, library, schema, graph, answering, comps, wired)
    found += _unserved(answering, owner, wired)
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


def _unserved(
    answering: dict[str, LiveNode], owner: dict[str, str], wired: set[tuple[str, str]]
) -> list[Finding]:
    """Report every live call of a service that no live node serves (a ROS 2 graph only).

    Calls along the configuration's own service edges (``wired``: consumer node, the name it
    calls) are judged there (``unmet-requirement``, with the consumer's own name accepted as
    a launch remapping would set it), not again here.
    """
    served = {s for n in answering.values() for s in n.serves}
    out = []
    for node in answering.values():
        for service in node.clients:
            comp = owner.get(node.name)
            if service in served or (node.name, service) in wired:
                continue
            msg = f"{node.name} calls service {service}, which no live node serves"
            out.append(Finding("unserved-client", msg, comp, service))
    return out


def _wrong_types(
    what: str, name: str, label: str, typ: str, provider: str, graph: LiveGraph, nodes: list[str]
) -> list[Finding]:
    """Report each live endpoint of ``name`` whose type is not ``typ``.

    A ROS 2 graph knows every node's own type (``nodes`` are the ones using ``name``); a
    ROS 1 master knows one type per topic.
    """
    if graph.ros_version != 2:
        live_type = graph.topic_types.get(name)
        if what == "topic" and live_type is not None and not same_type(live_type, typ):
            msg = f"topic {name} ({label}) carries {live_type}, not {typ}"
            return [Finding("wrong-type", msg, provider, name)]
        return []
    bad: dict[str, list[str]] = {}
    for n in graph.nodes:
        if n.name not in nodes:
            continue
        own = (n.topic_types if what == "topic" else n.service_types).get(name)
        if own is not None and not same_type(own, typ):
            bad.setdefault(own, []).append(n.name)
    return [
        Finding(
            "wrong-type",
            f"{what} {name} ({label}) is {live} at {', '.join(sorted(set(who)))}, not {typ}",
            provider,
            name,
        )
        for live, who in sorted(bad.items())
    ]


def _edges(
    configuration: Configuration,
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    graph: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    wired: set[tuple[str, str]],
) -> list[Finding]:
    """Check every topic/service vertex of the expected ROS-graph against the live nodes.

    Adds to ``wired`` each (consumer node, service name) an expected service edge explains.
    """
    found: list[Finding] = []
    served = {s for n in answering.values() for s in n.serves}
    published = {t for n in answering.values() for t in n.publishes}
    expected = ros_graph(configuration, library, schema)
    for vertex, data in sorted(expected.nodes(data=True)):
        kind = vertex[0]
        if kind is VertexKind.NODE:
            continue
        label, typ = str(data["label"]), str(data["type"])
        (provider,) = (p for _, p in expected.predecessors(vertex))
        consumers = sorted(c for _, c in expected.successors(vertex))
        name = interface_live_name(comps[provider], label)
        node = answering.get(node_live_name(comps[provider]))
        what = "service" if kind is VertexKind.SERVICE else "topic"
        if node is not None and name not in (node.serves if what == "service" else node.publishes):
            verb = "serve" if what == "service" else "publish"
            msg = f"{provider} does not {verb} {what} {name} ({label})"
            found.append(Finding(f"missing-{what}", msg, provider, name))
        using = [
            n.name
            for n in graph.nodes
            if name in (*n.publishes, *n.subscribes, *n.serves, *n.clients)
        ]
        found += _wrong_types(what, name, label, typ, provider, graph, using)
        for consumer in consumers:
            user = answering.get(node_live_name(comps[consumer]))
            own = interface_live_name(comps[consumer], label)
            if what == "service":
                wired |= {
                    (node_live_name(comps[consumer]), name),
                    (node_live_name(comps[consumer]), own),
                }
            if what == "topic" and user is not None and not {name, own} & set(user.subscribes):
                msg = f"{consumer} does not subscribe to topic {name} ({label})"
                found.append(Finding("missing-topic", msg, consumer, name))
            if (
                what == "service"
                and graph.ros_version == 2
                and user is not None
                and not {name, own} & set(user.clients)
            ):
                msg = f"{consumer} does not call service {name} ({label})"
                found.append(Finding("missing-client", msg, consumer, name))
            if what == "topic" and node is not None and user is not None:
                found += _qos(provider, node, consumer, user, name, own, label)
            if user is not None and name not in (served if what == "service" else published):
                how = "serves" if what == "service" else "publishes"
                msg = (
                    f"{consumer} uses {what} {name} ({label}, {typ}) of {provider}, "
                    f"which nothing live {how} (Lemma 4)"
                )
                found.append(Finding("unmet-requirement", msg, consumer, name))
    return found


def same_type(live: str, library: str) -> bool:
    """Tell whether a live type names the library's (ROS 2 ``pkg/msg/Name`` = ``pkg/Name``)."""

    def short(t: str) -> str:
        parts = t.split("/")
        return f"{parts[0]}/{parts[-1]}" if len(parts) == 3 else t

    return live == library or short(live) == short(library)


def _qos(
    provider: str,
    node: LiveNode,
    consumer: str,
    user: LiveNode,
    name: str,
    own: str,
    label: str,
) -> list[Finding]:
    """Report a publisher's offered QoS that the consumer's subscription cannot accept."""
    offered = node.publish_qos.get(name)
    requested = user.subscribe_qos.get(name, user.subscribe_qos.get(own))
    if offered is None or requested is None:
        return []  # ROS 1, or an endpoint missing (reported as such)
    why = incompatibilities(offered, requested)
    if not why:
        return []
    msg = (
        f"topic {name} ({label}): {provider} offers [{offered}] but {consumer} requests "
        f"[{requested}]: {'; '.join(w.message for w in why)} (no messages will flow)"
    )
    return [Finding("qos-incompatible", msg, consumer, name)]
