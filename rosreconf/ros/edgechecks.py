"""Check each interface of the expected ROS-graph against the live nodes (Lemma 4, live).

``rosreconf.ros.conformance.compare`` checks the nodes; this module checks every topic,
service and action vertex of the configuration's ROS-graph (Def. 1): who serves, publishes,
subscribes and calls it, its type at every endpoint, QoS along topic edges (ROS 2), and the
live calls that no expected service edge explains.
"""

from __future__ import annotations

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    VertexKind,
)
from rosreconf.model.qos import incompatibilities
from rosreconf.model.validity import ros_graph
from rosreconf.ros.liveactions import LiveAction, live_actions
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.livenames import Finding, interface_live_name, node_live_name, same_type

ACTION_SERVICES = ("send_goal", "cancel_goal", "get_result")
"""The services a ROS 2 action ``<a>`` is made of, each ``<a>/_action/<part>``."""


def unserved_findings(
    answering: dict[str, LiveNode], owner: dict[str, str], wired: set[tuple[str, str]]
) -> list[Finding]:
    """Report every live call of a service that no live node serves (a ROS 2 graph only).

    Calls along the configuration's own service edges (``wired``: consumer node, the name it
    calls) are judged there (``unmet-requirement``, with the consumer's own name accepted as
    a launch remapping would set it), not again here. Only the configuration's nodes
    (``owner``) are judged: a node outside it is an ``extra-node`` already, or one held out
    of service on purpose (a parked standby of ``watch``), whose calls are not the
    configuration's.
    """
    served = {s for n in answering.values() for s in n.serves}
    out = []
    for node in answering.values():
        comp = owner.get(node.name)
        if comp is None:
            continue
        for service in node.clients:
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


def edge_findings(
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
    actions = live_actions(graph)
    for vertex, data in sorted(expected.nodes(data=True)):
        kind = vertex[0]
        if kind is VertexKind.NODE:
            continue
        label, typ = str(data["label"]), str(data["type"])
        consumers = sorted(c for _, c in expected.successors(vertex))
        # a topic may have several chosen publishers (Nav2's controller_server and
        # behavior_server both publish cmd_vel_nav): each is checked
        for provider in sorted(p for _, p in expected.predecessors(vertex)):
            if kind is VertexKind.ACTION:
                node = answering.get(node_live_name(comps[provider]))
                name = interface_live_name(comps[provider], label)
                users = {
                    c: (
                        answering.get(node_live_name(comps[c])),
                        interface_live_name(comps[c], label),
                    )
                    for c in consumers
                }
                found += _action(provider, node, users, actions, name, label, typ)
                wired |= {  # its goal, cancel and result calls are the action's findings
                    (user.name, f"{action}/_action/{part}")
                    for user, own in users.values()
                    if user is not None
                    for action in (name, own)
                    for part in ACTION_SERVICES
                }
                continue
            found += _interface(
                graph,
                answering,
                comps,
                (served, published),
                provider,
                consumers,
                (label, typ, kind),
                wired,
            )
    return list(dict.fromkeys(found))  # two publishers under one name: one finding each


def _interface(
    graph: LiveGraph,
    answering: dict[str, LiveNode],
    comps: dict[str, Component],
    live: tuple[set[str], set[str]],
    provider: str,
    consumers: list[str],
    vertex: tuple[str, str, VertexKind],
    wired: set[tuple[str, str]],
) -> list[Finding]:
    """Check one provider's topic or service, and its consumers, against the live nodes.

    ``live`` is what every answering node serves and publishes; ``vertex`` the interface's
    label, type and kind. Adds to ``wired`` each (consumer node, service name) it explains.
    """
    label, typ, kind = vertex
    found: list[Finding] = []
    served, published = live
    name = interface_live_name(comps[provider], label)
    node = answering.get(node_live_name(comps[provider]))
    what = "service" if kind is VertexKind.SERVICE else "topic"
    if node is not None and name not in (node.serves if what == "service" else node.publishes):
        verb = "serve" if what == "service" else "publish"
        msg = f"{provider} does not {verb} {what} {name} ({label})"
        found.append(Finding(f"missing-{what}", msg, provider, name))
    using = [
        n.name for n in graph.nodes if name in (*n.publishes, *n.subscribes, *n.serves, *n.clients)
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


def _action(
    provider: str,
    node: LiveNode | None,
    users: dict[str, tuple[LiveNode | None, str]],
    actions: dict[str, LiveAction],
    name: str,
    label: str,
    typ: str,
) -> list[Finding]:
    """Check one action of the expected ROS-graph: its server, its type, its clients.

    A consumer calls it by the provider's name (remapped) or by its own, as for topics.
    """
    found: list[Finding] = []
    live = actions.get(name)
    servers = live.servers if live is not None else ()
    if node is not None and node.name not in servers:
        msg = f"{provider} does not serve action {name} ({label})"
        found.append(Finding("missing-action", msg, provider, name))
    if live is not None and live.type is not None and not same_type(live.type, typ):
        msg = f"action {name} ({label}) has type {live.type}, not {typ}"
        found.append(Finding("wrong-type", msg, provider, name))
    for consumer, (user, own) in users.items():
        if user is None:
            continue
        clients = {c for a in {name, own} if a in actions for c in actions[a].clients}
        if user.name not in clients:
            msg = f"{consumer} does not call action {name} ({label})"
            found.append(Finding("missing-action-client", msg, consumer, name))
        if not servers:
            msg = (
                f"{consumer} uses action {name} ({label}, {typ}) of {provider}, "
                "which nothing live serves (Lemma 4)"
            )
            found.append(Finding("unmet-requirement", msg, consumer, name))
    return found
