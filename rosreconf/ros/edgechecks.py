"""Check each interface of the expected ROS-graph against the live nodes (Lemma 4, live).

``rosreconf.ros.conformance.compare`` checks the nodes; this module checks every topic,
service and action vertex of the configuration's ROS-graph (Def. 1): who serves, publishes,
subscribes and calls it, its type at every endpoint, and QoS along topic edges (ROS 2).

It reads the wiring, never assumes it. Along an edge provider P -> interface (label L) ->
consumer C, P's live name is N = ``interface_live_name(P, L)``, and C must use N on the live
graph (subscribe to it, call it, send goals to it). C's own name for L counts only when it is
N. When C uses another name it may have for L instead (its own, or another library
provider's, as an old launch remapping set it), no call or message can flow along the edge:
that is ``unwired``, naming the name C uses, who serves N, and the ``-r`` rule that wires it.
A ROS 1 master does not list the services a node calls, so service edges are judged there by
their server alone.
"""

from __future__ import annotations

from collections.abc import Set
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from rosreconf.model import Component, Interface, InterfaceKind, VertexKind
from rosreconf.model.qos import incompatibilities
from rosreconf.model.wiring import interface_live_name, node_live_name
from rosreconf.ros.liveactions import LiveAction, live_actions
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.livenames import Finding, Providers, option_names, rules_said, same_type

if TYPE_CHECKING:
    from rosreconf.model import RosGraph

USE = {VertexKind.TOPIC: "subscribes to", VertexKind.SERVICE: "calls", VertexKind.ACTION: "calls"}
"""How a consumer uses each kind of interface, in a finding's words."""
OFFER = {VertexKind.TOPIC: "publishes", VertexKind.SERVICE: "serves", VertexKind.ACTION: "serves"}
"""How a provider offers each kind of interface, in a finding's words."""


@dataclass
class EdgeCheck:
    """What the edge checks found, and what they judged (the dangling checks skip it).

    Attributes:
        findings: every difference, in a stable order.
        judged: (consumer node, kind, live name) of each use an edge explains: the provider's
            name N, and each other name reported ``unwired``.
        edges: how many provider -> interface -> consumer edges were checked.
    """

    findings: list[Finding] = field(default_factory=list)
    judged: set[tuple[str, VertexKind, str]] = field(default_factory=set)
    edges: int = 0


@dataclass(frozen=True)
class _Live:
    """The live graph as the edge checks read it: nodes by name, what is offered, actions."""

    graph: LiveGraph
    answering: dict[str, LiveNode]
    served: frozenset[str]
    published: frozenset[str]
    actions: dict[str, LiveAction]
    providers: Providers

    def offered(self, kind: VertexKind) -> frozenset[str]:
        """Return every live name some node publishes (topics) or serves (services, actions)."""
        if kind is VertexKind.TOPIC:
            return self.published
        if kind is VertexKind.SERVICE:
            return self.served
        return frozenset(a for a, act in self.actions.items() if act.servers)

    def uses(self, node: LiveNode, kind: VertexKind) -> Set[str] | None:
        """Return the names ``node`` subscribes to, calls, or sends goals to (None: unknown)."""
        if kind is VertexKind.TOPIC:
            return set(node.subscribes)
        if kind is VertexKind.ACTION:
            return {a for a, act in self.actions.items() if node.name in act.clients}
        return set(node.clients) if self.graph.ros_version == 2 else None


def edge_findings(
    expected: RosGraph,
    graph: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    providers: Providers,
) -> EdgeCheck:
    """Check every topic, service and action vertex of ``expected`` against the live nodes."""
    live = _Live(
        graph,
        answering,
        frozenset(s for n in answering.values() for s in n.serves),
        frozenset(t for n in answering.values() for t in n.publishes),
        live_actions(graph),
        providers,
    )
    out = EdgeCheck()
    for vertex, data in sorted(expected.nodes(data=True)):
        kind = vertex[0]
        if kind is VertexKind.NODE:
            continue
        label, typ = str(data["label"]), str(data["type"])
        option = Interface(InterfaceKind(str(kind)), label, typ)
        consumers = sorted(c for _, c in expected.successors(vertex))
        # a topic may have several chosen publishers (Nav2's controller_server and
        # behavior_server both publish cmd_vel_nav): each is checked
        for provider in sorted(p for _, p in expected.predecessors(vertex)):
            out.findings += _provider(live, comps[provider], option, typ)
            for consumer in consumers:
                out.edges += 1
                out.findings += _consumer(live, comps, (provider, consumer), option, typ, out)
    out.findings = list(dict.fromkeys(out.findings))  # two publishers under one name: once
    return out


def _provider(live: _Live, comp: Component, option: Interface, typ: str) -> list[Finding]:
    """Check that the provider offers its live name of ``option``, with the library's type."""
    kind, label = VertexKind(str(option.kind)), option.label
    name = interface_live_name(comp, label)
    node = live.answering.get(node_live_name(comp))
    found: list[Finding] = []
    if kind is VertexKind.ACTION:
        act = live.actions.get(name)
        if node is not None and (act is None or node.name not in act.servers):
            msg = f"{comp.name} does not serve action {name} ({label})"
            found.append(Finding("missing-action", msg, comp.name, name))
        if act is not None and act.type is not None and not same_type(act.type, typ):
            msg = f"action {name} ({label}) has type {act.type}, not {typ}"
            found.append(Finding("wrong-type", msg, comp.name, name))
        return found
    what = str(kind)
    if node is not None and name not in (node.publishes if what == "topic" else node.serves):
        msg = f"{comp.name} does not {OFFER[kind][:-1]} {what} {name} ({label})"
        found.append(Finding(f"missing-{what}", msg, comp.name, name))
    using = [
        n.name
        for n in live.graph.nodes
        if name in (*n.publishes, *n.subscribes, *n.serves, *n.clients)
    ]
    return found + _wrong_types(what, name, label, typ, comp.name, live.graph, using)


def _consumer(
    live: _Live,
    comps: dict[str, Component],
    pair: tuple[str, str],
    option: Interface,
    typ: str,
    out: EdgeCheck,
) -> list[Finding]:
    """Check that the consumer uses the provider's live name N of ``option``, and that N lives.

    Records in ``out.judged`` the names of the consumer this edge explains.
    """
    provider, consumer = pair
    kind, label = VertexKind(str(option.kind)), option.label
    comp = comps[consumer]
    name = interface_live_name(comps[provider], label)
    user = live.answering.get(node_live_name(comp))
    if user is None:
        return []  # a missing or dead node: said once, as such
    out.judged.add((user.name, kind, name))
    found: list[Finding] = []
    uses = live.uses(user, kind)
    offered = live.offered(kind)
    if uses is not None and name not in uses:
        wrong = sorted(n for n in option_names(comp, option, live.providers) if n in uses)
        action = kind is VertexKind.ACTION
        for used in wrong:
            out.judged.add((user.name, kind, used))
            nobody = "" if used in offered else f", which nothing live {OFFER[kind]}"
            msg = (
                f"{consumer} {USE[kind]} {used} ({label}){nobody}; {provider} {OFFER[kind]} "
                f"it as {name}: {consumer} is not wired to it (start {consumer} with "
                f"{rules_said(comp, label, name, action, live.graph.ros_version)})"
            )
            found.append(Finding("unwired", msg, consumer, used))
        if not wrong:
            verb = {VertexKind.TOPIC: "subscribe to topic", VertexKind.SERVICE: "call service"}
            what = verb.get(kind, "call action")
            code = {VertexKind.TOPIC: "missing-topic", VertexKind.SERVICE: "missing-client"}
            msg = f"{consumer} does not {what} {name} ({label})"
            found.append(Finding(code.get(kind, "missing-action-client"), msg, consumer, name))
    elif kind is VertexKind.TOPIC:
        node = live.answering.get(node_live_name(comps[provider]))
        if node is not None:
            found += _qos(provider, node, consumer, user, name, label)
    if name not in offered:
        msg = (
            f"{consumer} uses {kind} {name} ({label}, {typ}) of {provider}, "
            f"which nothing live {OFFER[kind]} (Lemma 4)"
        )
        found.append(Finding("unmet-requirement", msg, consumer, name))
    return found


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


def _qos(
    provider: str, node: LiveNode, consumer: str, user: LiveNode, name: str, label: str
) -> list[Finding]:
    """Report a publisher's offered QoS that the consumer's subscription of ``name`` refuses."""
    offered = node.publish_qos.get(name)
    requested = user.subscribe_qos.get(name)
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
