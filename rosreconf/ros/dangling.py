"""Report the calls, subscriptions and goals of the configuration's nodes that reach nobody.

The edge checks (``rosreconf.ros.edgechecks``) judge the names the expected ROS-graph
explains. A node may use others: a kept consumer still calling the provider it was first
wired to, a stand-in or executable started without its remappings. This module judges them:

- every service a configuration node calls (ROS 2 graphs show clients) that no live node
  serves is ``unserved-client``;
- a subscription to a topic no live node publishes is ``unpublished-subscription``, and a
  goal client of an action no live node serves ``unserved-action-client`` (ROS 1 and 2), but
  only for names tied to the node's requirements: its own name for one of its requirement
  options, or a name a library provider uses for such an interface. Real robots subscribe to
  many topics nobody publishes yet (``/initialpose``); those are not the configuration's.

Each finding names who serves or publishes that interface instead, under which name, and the
``-r`` rule that would wire the node to it. One exception, on purpose: a node's own name for
an *unchosen alternative* of an ``any_of`` requirement (an option on none of its ROS-graph
edges, another option of that requirement being on one) is not a finding. A node that can use
either arm keeps a client of both; the edge judges the requirement.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from rosreconf.model import Component, Interface, InterfaceKind, Requirement, VertexKind
from rosreconf.model.schema import node_vertex
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.liveactions import LiveAction, live_actions
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.livenames import Finding, Providers, option_names, rules_said

if TYPE_CHECKING:
    from rosreconf.model import RosGraph

ACTION_PART = "/_action/"
"""What every ROS 2 action's services and topics have in their names (judged as the action)."""


@dataclass(frozen=True)
class _Tie:
    """One requirement option a live name may stand for, and whose name it is."""

    requirement: Requirement
    option: Interface
    owner: str


@dataclass
class Uses:
    """What the dangling checks judged: (node, live name) of each call, subscription, goal."""

    calls: list[tuple[str, str]] = field(default_factory=list)
    subscriptions: list[tuple[str, str]] = field(default_factory=list)
    actions: list[tuple[str, str]] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)


def _ties(comp: Component, providers: Providers) -> dict[tuple[VertexKind, str], list[_Tie]]:
    """Return each (kind, live name) tied to a requirement of ``comp``, and what it stands for."""
    ties: dict[tuple[VertexKind, str], list[_Tie]] = {}
    for req in comp.requires:
        for option in req.options:
            for name, owner in option_names(comp, option, providers).items():
                ties.setdefault((VertexKind(str(option.kind)), name), []).append(
                    _Tie(req, option, owner)
                )
    return ties


def _on_edges(expected: RosGraph, comp: str) -> set[Interface]:
    """Return the interfaces ``comp`` uses along its edges of the expected ROS-graph."""
    return {
        Interface(InterfaceKind(str(v[0])), str(expected.nodes[v]["label"]), str(d["type"]))
        for v, _, d in expected.in_edges(node_vertex(comp), data=True)
    }


def _excused(comp: Component, ties: list[_Tie], chosen: set[Interface]) -> bool:
    """Tell whether the name is ``comp``'s own for an unchosen alternative of a met requirement."""
    return bool(ties) and all(
        t.owner == comp.name
        and t.option not in chosen
        and any(o in chosen for o in t.requirement.options)
        for t in ties
    )


def dangling_findings(
    expected: RosGraph,
    graph: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    providers: Providers,
    judged: set[tuple[str, VertexKind, str]],
) -> Uses:
    """Judge every call, and each requirement's subscription and goal client, of the nodes.

    ``judged`` holds the (node, kind, name) uses the edge checks explained already.
    """
    offers = _Offers(answering, live_actions(graph), graph.ros_version)
    out = Uses()
    for c, comp in comps.items():
        node = answering.get(node_live_name(comp))
        if node is None:
            continue
        ties, chosen = _ties(comp, providers), _on_edges(expected, c)
        goals = sorted(a for a, act in offers.actions.items() if node.name in act.clients)
        for kind, names, into in (
            (VertexKind.SERVICE, _calls(node, graph), out.calls),
            (VertexKind.TOPIC, node.subscribes, out.subscriptions),
            (VertexKind.ACTION, goals, out.actions),
        ):
            for name in names:
                tie = ties.get((kind, name), [])
                edge = (node.name, kind, name) in judged
                if kind is not VertexKind.SERVICE and not tie and not edge:
                    continue  # not the configuration's business (module docstring)
                into.append((node.name, name))
                if edge or offers.anyone(kind, name) or _excused(comp, tie, chosen):
                    continue
                out.findings.append(_finding(comp, kind, name, tie, offers, providers))
    return out


@dataclass
class _Offers:
    """Who offers what on the live graph: the answering nodes, the actions they carry, and
    the graph's ROS version (1 or 2: how a rule moving an action is written).
    """

    answering: dict[str, LiveNode]
    actions: dict[str, LiveAction]
    ros_version: int

    def by(self, node: str, kind: VertexKind, name: str) -> bool:
        """Tell whether live node ``node`` publishes or serves ``name``."""
        n = self.answering.get(node)
        if n is None:
            return False
        if kind is VertexKind.ACTION:
            return name in self.actions and node in self.actions[name].servers
        return name in (n.publishes if kind is VertexKind.TOPIC else n.serves)

    def anyone(self, kind: VertexKind, name: str) -> bool:
        """Tell whether some live node publishes or serves ``name``."""
        if kind is VertexKind.ACTION:
            return name in self.actions and bool(self.actions[name].servers)
        return name in (self.published if kind is VertexKind.TOPIC else self.served)

    @functools.cached_property
    def published(self) -> frozenset[str]:
        """Return every topic an answering node publishes."""
        return frozenset(t for n in self.answering.values() for t in n.publishes)

    @functools.cached_property
    def served(self) -> frozenset[str]:
        """Return every service an answering node serves."""
        return frozenset(s for n in self.answering.values() for s in n.serves)


def _calls(node: LiveNode, graph: LiveGraph) -> Iterator[str]:
    """Return the services ``node`` calls, but an action's own (its goal client judges them)."""
    if graph.ros_version != 2:
        return iter(())  # a ROS 1 master does not know who calls a service
    return (s for s in node.clients if ACTION_PART not in s)


def _finding(
    comp: Component,
    kind: VertexKind,
    name: str,
    ties: list[_Tie],
    offers: _Offers,
    providers: Providers,
) -> Finding:
    """Say that ``comp`` uses ``name``, which nothing live offers, and who offers it instead."""
    c = comp.name
    if kind is VertexKind.SERVICE:
        code, said, nobody = "unserved-client", f"calls service {name}", "serves"
    elif kind is VertexKind.TOPIC:
        code, said, nobody = "unpublished-subscription", f"subscribes to {name}", "publishes"
    else:
        code, said, nobody = "unserved-action-client", f"calls action {name}", "serves"
    if not ties:
        return Finding(code, f"{c} {said}, which no live node {nobody}", c, name)
    option = ties[0].option
    whose = ", ".join(sorted({t.owner for t in ties if t.owner != c}))
    label = f" ({option.label}" + (f", {whose}'s name for it)" if whose else ")")
    msg = f"{c} {said}{label}, which no live node {nobody}"
    instead = [
        (who, live) for who, node, live in providers.get(option, ()) if offers.by(node, kind, live)
    ]
    if instead:
        listed = ", ".join(f"{who} {nobody} it as {live}" for who, live in instead)
        action = kind is VertexKind.ACTION
        rule = rules_said(comp, option.label, instead[0][1], action, offers.ros_version)
        msg += f"; {listed}: {c} is not wired to it (start {c} with {rule})"
    else:
        msg += f"; no live node {nobody} {option.label} under any name"
    return Finding(code, msg, c, name)
