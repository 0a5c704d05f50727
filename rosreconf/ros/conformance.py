"""Compare the live graph of a running system with the ROS-graph a configuration should have.

The expected ROS-graph (Def. 1) comes from ``rosreconf.model.validity.ros_graph``; the live one
from the middleware: what a ROS 1 master lists (``rosreconf.ros.ros1.rosmaster``) or what ROS 2
nodes announce over DDS discovery (``rosreconf.ros.ros2.discovery``), both as a ``LiveGraph``.
They speak different names: the model names nodes after components and interfaces after labels
(Omega), the live graph uses global ROS names. One
pair of functions maps model names to live names, and everything here goes through them::

    model                                   live (global ROS name)
    --------------------------------------  ------------------------------------------------
    component C                             <ros.namespace or />/<ros.node or C>  node_live_name
    interface label X of component C        ros.remappings[X] if given, else X,  interface_live_name
                                            resolved for C's node as ROS does (resolve_name):
                                            /x as is; x in C's namespace; ~/x, ~x under C's node

So NSM3 is ``/NSM3`` and its ``elbow/digital_servo_command`` is ``/arm_servo/elbow/servo_command``
(its remapping); a component with ``namespace: /arm`` and no remapping for ``joint_states``
publishes ``/arm/joint_states``, and one whose remapping says ``~/state`` publishes
``/arm/<node>/state``. The module that owns the mapping, ``rosreconf.model.wiring``, writes
the launch files' remappings and the stand-ins' names with the same resolver.

It reads the wiring, never assumes it: along an edge provider P -> interface (label L) ->
consumer C of the ROS-graph, C must use P's live name ``interface_live_name(P, L)`` on the
live graph; its own name for L counts only when it is that name. Findings (``Finding.code``)::

    code                      ROS   what
    ------------------------  ----  ------------------------------------------------------------
    missing-node              1, 2  a node of the configuration is not running
    dead-node                 1     registered but its API does not answer (SIGKILLed nodes
                                    linger in a ROS 1 master)
    extra-node                1, 2  alive, not plumbing, not in the configuration (a managed
                                    node of the library parked inactive or unconfigured is a
                                    standby instead, listed: ``rosreconf.ros.parked``; a node
                                    publishing a context topic the library declares is the
                                    sensor context is read from, not an extra node)
    duplicate-node            2     two nodes announce one name (calls reach either; judged
                                    together)
    missing-service /         1, 2  a provider does not serve / publish / subscribe what its
    missing-topic                   ROS-graph edges say
    missing-client            2     a consumer does not call a service its edges say it calls
    missing-action /          1, 2  a provider does not serve the action / a consumer does not
    missing-action-client           send it goals
    unwired                   1, 2  a consumer uses another name it may have for an edge's
                                    interface (its own, or another library provider's), not the
                                    provider's: no call or message can flow (the -r rule said)
    unmet-requirement         1, 2  Lemma 4: an interface a running node uses along its edges is
                                    served or published by no live node
    unserved-client           2     a node of the configuration calls a service nobody serves
    unpublished-subscription  1, 2  ... subscribes to a topic nobody publishes, and
    unserved-action-client    1, 2  ... sends goals to an action nobody serves: both only for
                                    names tied to its requirements (``rosreconf.ros.dangling``)
    wrong-type                1, 2  an endpoint's type differs from the library's (ROS 2: every
                                    node's own; ROS 1: the master's one per topic)
    qos-incompatible          2     the publisher offers a QoS the subscription cannot accept
                                    (``rosreconf.model.qos.incompatibilities``; both named)
    not-active                2     a managed node (``ros.lifecycle``) is not in the active
                                    state (the state is said)
    not-managed               2     ``ros.lifecycle: true`` but the node is live as a plain node
                                    (it serves no ``<node>/get_state``)

Dangling uses name who serves or publishes the interface instead. A node's own name for an
unchosen alternative of an ``any_of`` requirement is not a finding while another option of it
is on the node's edges (a node that can use either arm keeps both clients). ROS 2 types
(``pkg/msg/Name``) equal the library's ``pkg/Name`` (``rosreconf.model.type_key``); actions
are read by ``rosreconf.ros.liveactions``. ``Conformance.checked`` says what was judged.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from rosreconf.model import Component, ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.schema import VertexKind, node_vertex
from rosreconf.model.validity import ros_graph
from rosreconf.model.wiring import interface_live_name, node_live_name
from rosreconf.ros.dangling import dangling_findings
from rosreconf.ros.edgechecks import edge_findings
from rosreconf.ros.livegraph import LiveGraph, LiveNode, without_plumbing
from rosreconf.ros.livenames import Finding, library_providers, same_type
from rosreconf.ros.parked import Standby, standbys

if TYPE_CHECKING:  # networkx is imported only when a ROS-graph is built
    from rosreconf.model.schema import RosGraph

__all__ = [
    "Checked",
    "Conformance",
    "Finding",
    "compare",
    "same_type",
]


@dataclass(frozen=True)
class Checked:
    """What a comparison judged, so that "conformant" says what it stands on.

    Attributes:
        nodes: the configuration's live node names that were found answering.
        edges: how many provider -> interface -> consumer edges of the ROS-graph were checked.
        calls: (node, service) of every service call of those nodes (ROS 2 graphs show them).
        subscriptions: (node, topic) of each subscription tied to their requirements.
        actions: (node, action) of each action they send goals to, tied to their requirements.
        states: managed node -> the lifecycle state read (``unknown`` when none answered).
    """

    nodes: tuple[str, ...] = ()
    edges: int = 0
    calls: tuple[tuple[str, str], ...] = ()
    subscriptions: tuple[tuple[str, str], ...] = ()
    actions: tuple[tuple[str, str], ...] = ()
    states: tuple[tuple[str, str], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON shape of ``checked`` in ``inspect --json`` (docs/json.md)."""
        return {
            "nodes": list(self.nodes),
            "edges": self.edges,
            "calls": [{"node": n, "service": s} for n, s in self.calls],
            "subscriptions": [{"node": n, "topic": t} for n, t in self.subscriptions],
            "actions": [{"node": n, "action": a} for n, a in self.actions],
            "lifecycle_states": dict(self.states),
        }


@dataclass(frozen=True)
class Conformance:
    """The outcome of comparing one configuration with a live graph.

    Attributes:
        schema: the schema's name.
        configuration: the configuration expected to run.
        live: the live graph compared (plumbing included, as read).
        expected_nodes: component -> its live node name.
        findings: every difference, in a stable order.
        checked: what was judged (nodes, edges, calls, subscriptions, actions, states).
        standby: the library's managed nodes held out of service (``rosreconf.ros.parked``):
            not in the configuration, and not extra nodes either.
    """

    schema: str
    configuration: Configuration
    live: LiveGraph
    expected_nodes: dict[str, str]
    findings: tuple[Finding, ...]
    checked: Checked = Checked()
    standby: tuple[Standby, ...] = ()

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
            "checked": self.checked.to_dict(),
            "standby": [s.to_dict() for s in self.standby],
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
    comps = {c: library[c] for c in configuration.components}
    names = {c: node_live_name(comp) for c, comp in comps.items()}
    parked = standbys(library, set(names.values()), answering)
    sensors = {v.topic for v in library.context}
    out_of_service = {s.node for s in parked} | {
        name for name, n in answering.items() if sensors & set(n.publishes)
    }
    found = [
        f
        for f in _node_findings(configuration, graph, answering, names)
        if f.code != "extra-node" or f.live_name not in out_of_service
    ]
    found += _lifecycle_findings(live, answering, comps, names)
    expected = ros_graph(configuration, library, schema)
    found += _clash_findings(expected, live, answering, comps, names)
    providers = library_providers(library)
    edges = edge_findings(expected, graph, answering, comps, providers)
    uses = dangling_findings(expected, graph, answering, comps, providers, edges.judged)
    found += edges.findings + uses.findings
    checked = Checked(
        nodes=tuple(n for n in names.values() if n in answering),
        edges=edges.edges,
        calls=tuple(uses.calls),
        subscriptions=tuple(uses.subscriptions),
        actions=tuple(uses.actions),
        states=tuple(
            (name, state)
            for c, name in names.items()
            if (state := _state(comps[c], answering.get(name))) is not None
        ),
    )
    return Conformance(schema.name, configuration, live, names, tuple(found), checked, parked)


def _node_findings(
    configuration: Configuration,
    graph: LiveGraph,
    answering: dict[str, LiveNode],
    names: dict[str, str],
) -> list[Finding]:
    """Report nodes of one name, and missing, dead and extra nodes."""
    found: list[Finding] = []
    owner = {name: c for c, name in names.items()}
    registered = {n.name for n in graph.nodes}
    for name in graph.duplicates:
        count = sum(1 for n in graph.nodes if n.name == name)
        why = (
            f"{count} nodes are named {name} (ROS 2 allows it, but service calls and "
            "parameters reach either one; give each its own name)"
        )
        found.append(Finding("duplicate-node", why, owner.get(name), name))
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
    return found


def _lifecycle_findings(
    live: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    names: dict[str, str],
) -> list[Finding]:
    """Report managed nodes out of the active state, and plain nodes the library calls managed.

    Lifecycle is ROS 2's: a ROS 1 graph has none. A node is managed when it serves
    ``<node>/get_state`` (read from ``live``: the plumbing-free graph has no lifecycle services)
    or when the reader gave it a lifecycle state (a node seen managed stays so while it runs:
    a read that missed its state services says ``unknown`` or hung, never plain).
    """
    if live.ros_version != 2:
        return []
    found: list[Finding] = []
    managed = {
        n.name
        for n in live.nodes
        if f"{n.name}/get_state" in n.serves or n.lifecycle_state is not None
    }
    for c, name in names.items():
        launch, node = comps[c].launch, answering.get(name)
        if launch is None or not launch.lifecycle or node is None:
            continue
        if name not in managed:
            why = (
                f"{c}: {name} is a plain node, but the library says it is managed "
                f"(ros.lifecycle: true): it serves no {name}/get_state, so it cannot be "
                "configured, activated or deactivated (start its managed executable, or "
                "set ros.lifecycle: false)"
            )
            found.append(Finding("not-managed", why, c, name))
        elif node.lifecycle_state not in (None, "active"):
            why = (
                f"{c}: managed node {name} is {node.lifecycle_state}, not active: it does "
                f"nothing until activated (ros2 lifecycle set {name} activate)"
            )
            found.append(Finding("not-active", why, c, name))
    return found


def _clash_findings(
    expected: RosGraph,
    live: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    names: dict[str, str],
) -> list[Finding]:
    """Report a node that has a component's name but none of its endpoints: another node.

    A component's endpoints in a configuration are the live names of its ROS-graph's
    interfaces: what it provides, under its own names, and what it uses, under its providers'
    names. A node of that name that has none of those (actions: none of their ``/_action/``
    services) and none under the interface's own label either (that would be the component
    started unwired: an edge finding), is not that component, whatever its name says; ``watch``
    never takes it for the component. That holds for a node with no endpoints at all (plumbing
    aside): a bare node squatting on the name (``watch`` gives a node just started time to
    show its endpoints, ``clashes``). A managed node that is not active is excused
    (``not-active`` reports it).
    """
    found: list[Finding] = []
    for c, name in names.items():
        node, vertex = answering.get(name), node_vertex(c)
        if node is None or vertex not in expected:
            continue
        labels = {str(expected.nodes[v]["label"]) for v in expected.successors(vertex)}
        wanted = {interface_live_name(comps[c], label) for label in labels}
        for v in expected.predecessors(vertex):
            if v[0] is VertexKind.SERVICE and live.ros_version != 2:
                continue  # a ROS 1 master does not show who calls a service
            labels.add(label := str(expected.nodes[v]["label"]))
            wanted |= {interface_live_name(comps[p[1]], label) for p in expected.predecessors(v)}
        has = {*node.publishes, *node.subscribes, *node.serves, *node.clients}
        bare = not has
        has |= {h.split("/_action/")[0] for h in has if "/_action/" in h}  # ROS 2 actions
        has |= {h.removesuffix("/goal") for h in has if h.endswith("/goal")}  # actionlib
        own = {interface_live_name(comps[c], label) for label in labels} & has
        own |= {h for h in has for label in labels if h.endswith("/" + label.lstrip("/"))}
        if not wanted or wanted & has or own:  # its own label unwired: miswired, not another
            continue
        launch = comps[c].launch
        if launch is not None and launch.lifecycle and node.lifecycle_state != "active":
            continue
        shown = ", ".join(sorted(wanted)[:3]) + (
            f" and {len(wanted) - 3} more" if len(wanted) > 3 else ""
        )
        none = "no endpoints at all" if bare else "none of its endpoints"
        why = (
            f"{name} runs, but it is not {c}: it has {none} ({c}'s: {shown}), so another node "
            "has its name (a name clash). Give one of them another name, or stop it"
        )
        found.append(Finding("name-clash", why, c, name))
    return found


def _state(comp: Component, node: LiveNode | None) -> str | None:
    """Return the lifecycle state read of a managed component's node (None: none read)."""
    launch = comp.launch
    if node is None or launch is None or not launch.lifecycle:
        return None
    return node.lifecycle_state


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
