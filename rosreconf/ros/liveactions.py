"""Find the ROS actions of a live graph in the services and topics that carry them.

Neither a ROS 1 master nor ROS 2 discovery knows actions: an action is a bundle of
services and topics under its name, and this module is the one place that reads them back::

    ROS 2 (rcl_action)                              server         client
    ----------------------------------------------  -------------  ---------------
    service <a>/_action/send_goal    pkg/action/T_SendGoal      serves         calls
    service <a>/_action/cancel_goal  action_msgs/srv/CancelGoal serves         calls
    service <a>/_action/get_result   pkg/action/T_GetResult     serves         calls
    topic   <a>/_action/feedback     pkg/action/T_FeedbackMessage  publishes   subscribes
    topic   <a>/_action/status       action_msgs/msg/GoalStatusArray publishes subscribes

    ROS 1 (actionlib)                               server         client
    ----------------------------------------------  -------------  ---------------
    topic   <a>/goal      pkg/TActionGoal           subscribes     publishes
    topic   <a>/cancel    actionlib_msgs/GoalID     subscribes     publishes
    topic   <a>/status    actionlib_msgs/GoalStatusArray  publishes  subscribes
    topic   <a>/feedback  pkg/TActionFeedback       publishes      subscribes
    topic   <a>/result    pkg/TActionResult         publishes      subscribes

The action's type is ``pkg/action/T`` (ROS 2) or ``pkg/T`` (ROS 1), read from its goal's
type; ``rosreconf.model.type_key`` makes the two equal. ``rosreconf inspect`` compares these
with a configuration's action vertices, and ``rosreconf import`` drafts ``action:`` entries
from them instead of their parts.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from rosreconf.ros.livegraph import LiveGraph

ROS2_SERVICES = ("send_goal", "cancel_goal", "get_result")
"""The services an action server serves under ``<action>/_action/`` (ROS 2)."""
ROS2_TOPICS = ("feedback", "status")
"""The topics an action server publishes under ``<action>/_action/`` (ROS 2)."""
ROS1_SERVER_SUBSCRIBES = ("goal", "cancel")
"""The topics an actionlib server subscribes to under ``<action>/`` (a client publishes)."""
ROS1_SERVER_PUBLISHES = ("status", "feedback", "result")
"""The topics an actionlib server publishes under ``<action>/`` (a client subscribes)."""


@dataclass(frozen=True)
class LiveAction:
    """One action a live graph carries, with its servers and clients.

    Attributes:
        name: its global name (``/navigate_to_pose``).
        type: ``pkg/action/T`` (ROS 2) or ``pkg/T`` (ROS 1, from ``pkg/TActionGoal``), None
            when no part of it announced a type.
        servers: the nodes serving it, sorted.
        clients: the nodes calling it, sorted.
        parts: the global names of its services and topics.
    """

    name: str
    type: str | None
    servers: tuple[str, ...]
    clients: tuple[str, ...]
    parts: frozenset[str]


def _strip(typ: str | None, suffix: str) -> str | None:
    """Return ``typ`` without ``suffix`` (``pkg/action/T_SendGoal`` -> ``pkg/action/T``)."""
    if typ is None or not typ.endswith(suffix) or len(typ) == len(suffix):
        return None
    return typ[: -len(suffix)]


def live_actions(graph: LiveGraph) -> dict[str, LiveAction]:
    """Return the actions of ``graph`` by global name (ROS 2 or ROS 1, as the graph is)."""
    return _ros2(graph) if graph.ros_version == 2 else _ros1(graph)


def _ros2(graph: LiveGraph) -> dict[str, LiveAction]:
    marker = "/_action/send_goal"
    names = {
        s[: -len(marker)]
        for n in graph.nodes
        for s in (*n.serves, *n.clients)
        if s.endswith(marker) and len(s) > len(marker)
    }
    found = {}
    for a in sorted(names):
        services = {f"{a}/_action/{s}" for s in ROS2_SERVICES}
        topics = {f"{a}/_action/{t}" for t in ROS2_TOPICS}
        typ = _strip(graph.service_types.get(f"{a}{marker}"), "_SendGoal") or _strip(
            graph.topic_types.get(f"{a}/_action/feedback"), "_FeedbackMessage"
        )
        found[a] = LiveAction(
            a,
            typ,
            tuple(n.name for n in graph.nodes if f"{a}{marker}" in n.serves),
            tuple(n.name for n in graph.nodes if f"{a}{marker}" in n.clients),
            frozenset(services | topics),
        )
    return found


def _ros1(graph: LiveGraph) -> dict[str, LiveAction]:
    found = {}
    for goal, typ in sorted(graph.topic_types.items()):
        a = goal.removesuffix("/goal")
        if a == goal or not a or not typ.endswith("ActionGoal"):
            continue
        parts = {f"{a}/{t}" for t in (*ROS1_SERVER_SUBSCRIBES, *ROS1_SERVER_PUBLISHES)}
        if not parts <= set(graph.topic_types):
            continue  # a topic called goal, not an actionlib action
        found[a] = LiveAction(
            a,
            _strip(typ, "ActionGoal"),
            tuple(n.name for n in graph.nodes if goal in n.subscribes),
            tuple(n.name for n in graph.nodes if goal in n.publishes),
            frozenset(parts),
        )
    return found


def without_action_parts(graph: LiveGraph, actions: dict[str, LiveAction]) -> LiveGraph:
    """Return ``graph`` without the services and topics that carry ``actions``.

    What is left is what the nodes exchange besides their actions: ``rosreconf import``
    drafts these as topics and services and the actions as ``action:`` entries.
    """
    parts = frozenset().union(*(a.parts for a in actions.values()))
    nodes = tuple(
        replace(
            n,
            publishes=tuple(t for t in n.publishes if t not in parts),
            subscribes=tuple(t for t in n.subscribes if t not in parts),
            serves=tuple(s for s in n.serves if s not in parts),
            clients=tuple(s for s in n.clients if s not in parts),
            publish_qos={t: q for t, q in n.publish_qos.items() if t not in parts},
            subscribe_qos={t: q for t, q in n.subscribe_qos.items() if t not in parts},
        )
        for n in graph.nodes
    )
    return replace(
        graph,
        nodes=nodes,
        topic_types={t: ty for t, ty in graph.topic_types.items() if t not in parts},
        service_types={s: ty for s, ty in graph.service_types.items() if s not in parts},
    )
