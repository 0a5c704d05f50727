"""Draft a component library from a running system, so a person starts from what really runs.

What the master knows becomes YAML of ``docs/formats.md``; what it cannot know becomes a
placeholder that still validates, marked with a ``# TODO`` comment::

    master                               draft
    -----------------------------------  ----------------------------------------------------
    node /ns/name                        component ``name`` with ``ros.namespace: /ns``
                                         (``ns_name`` if two nodes share a base name, then
                                         with ``ros.node: name``, the name it really runs as)
    anonymous node /rostopic_4711_17...  the same, with a TODO: the name changes on restart
    published topic /t (type T)          provides {topic: /t, type: T}
    served service /s (no type known)    provides {service: /s, type: TODO_srvs/<Name>}
    subscribed topic /t                  requires {topic: /t, type: T} when something live
                                         publishes /t, else a commented-out TODO
    called services                      invisible at the master: TODO comment
    action /a served (ROS 2: its _action/   provides {action: /a, type: pkg/action/T}; its
      services and topics; ROS 1: the five  services and topics are not drafted
      actionlib topics)
    action /a called                     requires {action: /a, type: pkg/action/T} when a
                                         live node serves it, else a commented-out TODO
    -                                    abstraction: TODO_<name>, ros.package: TODO_package,
                                         ros.executable: TODO_executable

Interface labels are the live global names, so ``rosreconf.ros.conformance.interface_live_name``
maps them back to themselves and ``rosreconf inspect`` can compare the draft with the live
system at once. Plumbing (``/rosout``, logger services) is left out.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from rosreconf.model import type_key
from rosreconf.resources import Bundle, bundled
from rosreconf.ros.liveactions import LiveAction, live_actions, without_action_parts
from rosreconf.ros.livegraph import LiveGraph, LiveNode, without_plumbing

ANONYMOUS = re.compile(r"_\d+_\d{10,}$")
"""The suffix ROS 1 gives an anonymous node (``rostopic_4711_1700000000000``): pid, time."""


def header() -> str:
    """Return the editor line pointing at the installed JSON Schema, by absolute URI.

    A draft is written wherever the user asks, not beside a checkout, so a relative path
    would point nowhere.
    """
    path = Path(str(bundled(Bundle.DATA, "component-library.schema.json"))).resolve()
    return f"# yaml-language-server: $schema={path.as_uri()}"


def is_anonymous(node: str) -> bool:
    """Tell whether ``node`` is an anonymous name, which changes every time it starts."""
    return bool(ANONYMOUS.search(node.rsplit("/", 1)[-1]))


UNKNOWN_TOPIC_TYPE = "TODO_msgs/Unknown"
"""The type written for a topic the master has no type for (it always has, in practice)."""


def component_name(node: str, taken: set[str]) -> str:
    """Return a valid component name for node ``node``, unique (any case) in ``taken``.

    The base name is kept (``/arm/NSM3`` -> ``NSM3``); characters a component name cannot
    hold become ``_``; on a clash the namespace is prefixed (``arm_NSM3``), then a number.
    """
    parts = [_clean(p) for p in node.split("/") if p] or ["node"]
    for candidate in (parts[-1], "_".join(parts)):
        if candidate.lower() not in taken:
            taken.add(candidate.lower())
            return candidate
    n = 2
    while f"{'_'.join(parts)}_{n}".lower() in taken:
        n += 1
    taken.add(f"{'_'.join(parts)}_{n}".lower())
    return f"{'_'.join(parts)}_{n}"


def _clean(part: str) -> str:
    """Make one name segment a valid component name (letter first, then letters, digits, _)."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", part)
    return text if text[:1].isalpha() else "N" + text


def _service_type(service: str) -> str:
    """Return the placeholder type of a service (its last segment, CamelCased)."""
    base = "".join(w.capitalize() for w in re.split(r"[^A-Za-z0-9]+", service) if w)
    return f"TODO_srvs/{_clean(base or 'Unknown')}"


def _library_type(live: LiveGraph, service: str) -> str:
    """Return a ROS 2 service's type in the library's ``pkg/Name`` form."""
    return type_key(live.service_types.get(service, _service_type(service)))


def _topic_type(live: LiveGraph, topic: str) -> str:
    """Return a topic's type in the library's ``pkg/Name`` form (ROS 2 says ``pkg/msg/Name``)."""
    return type_key(live.topic_types.get(topic, UNKNOWN_TOPIC_TYPE))


UNKNOWN_ACTION_TYPE = "TODO_msgs/action/Unknown"
"""The type written for an action none of whose parts announced a type."""


def _action_type(action: LiveAction) -> str:
    """Return an action's type as ROS 2 writes it (``pkg/action/T``; ROS 1's ``pkg/T`` too)."""
    if action.type is None:
        return UNKNOWN_ACTION_TYPE
    package, _, name = type_key(action.type).partition("/")
    return f"{package}/action/{name}"


def _q(text: str) -> str:
    """Quote ``text`` as a YAML (JSON) string."""
    return json.dumps(text)


def _where(live: LiveGraph) -> str:
    """Say where the graph was read, for the draft's header."""
    if live.ros_version == 2:
        return f"ROS 2 DDS discovery ({live.master_uri})"
    return f"the ROS master at {live.master_uri}"


def draft_library(graph: LiveGraph, name: str = "imported") -> str:
    """Return the YAML text of a component library with one component per live node."""
    plain = without_plumbing(graph)
    actions = live_actions(plain)
    live = without_action_parts(plain, actions)
    published = {t for n in live.nodes for t in n.publishes}
    lines = [
        header(),
        "#",
        f"# Drafted by 'rosreconf import' from {_where(live)}",
        f"# on {live.taken_at.isoformat()}. Fill in every TODO before using it for planning:",
        "#   abstraction  the role class each component can play (Def. 5), shared by",
        "#                interchangeable components;",
        "#   TODO_srvs/*  service types (the master does not know them);",
        "#   requires     services each node calls (the master does not know them either);",
        "#   ros:         the package and executable that start each node;",
        "#   needs/excludes, schemas, failure_probability, metrics: what only you know.",
        "format: rosreconf/component-library",
        "version: 1",
        f"name: {_q(_clean(name))}",
        f"description: {_q('Drafted from the live system at ' + live.master_uri)}",
        "components:",
    ]
    taken: set[str] = set()
    for node in live.nodes:
        lines += _component(node, component_name(node.name, taken), live, published, actions)
    if not live.nodes:
        lines[-1] = "components: []  # TODO: no node was running (this draft will not load)"
    return "\n".join(lines) + "\n"


def _component(
    node: LiveNode,
    comp: str,
    live: LiveGraph,
    published: set[str],
    actions: dict[str, LiveAction],
) -> list[str]:
    """Return the YAML lines of one component drafted from ``node``."""
    namespace, _, base = node.name.rpartition("/")
    lines = [
        f"  - name: {comp}",
        f"    abstraction: TODO_{comp}  # TODO: the role class {comp} can play",
        f"    description: {_q('Live node ' + node.name)}",
    ]
    if is_anonymous(node.name):
        lines.append(
            f"    # TODO: {node.name} is an anonymous name (pid and start time): it changes on"
            " every restart, so inspect and watch will not find it again; start the node"
            " under a fixed name and put that in ros.node"
        )
    if not node.answered:
        lines.append("    # TODO: this node did not answer (dead?) when the master was read")
    provides = [
        f"      - {{topic: {_q(t)}, type: {_q(_topic_type(live, t))}}}" for t in node.publishes
    ]
    for s in node.serves:
        if s in live.service_types:  # ROS 2 discovery knows service types
            provides.append(f"      - {{service: {_q(s)}, type: {_q(_library_type(live, s))}}}")
        else:
            provides.append(
                f"      - {{service: {_q(s)}, type: {_q(_service_type(s))}}}  # TODO: type"
            )
    for a in actions.values():
        if node.name in a.servers:
            provides.append(f"      - {{action: {_q(a.name)}, type: {_q(_action_type(a))}}}")
    lines += ["    provides:", *provides] if provides else ["    provides: []"]
    requires: list[str] = []
    unmet: list[str] = []
    for t in node.subscribes:
        entry = f"{{topic: {_q(t)}, type: {_q(_topic_type(live, t))}}}"
        (requires if t in published else unmet).append(entry)
    served = {x for n in live.nodes for x in n.serves}
    uncalled: list[str] = []
    for c in node.clients:  # ROS 2 only: a ROS 1 master does not know callers
        entry = f"{{service: {_q(c)}, type: {_q(_library_type(live, c))}}}"
        (requires if c in served else uncalled).append(entry)
    for a in actions.values():
        if node.name in a.clients:
            entry = f"{{action: {_q(a.name)}, type: {_q(_action_type(a))}}}"
            (requires if a.servers else uncalled).append(entry)
    lines += ["    requires:", *(f"      - {r}" for r in requires)] if requires else []
    lines += [f"    # TODO: subscribes {r}, which nothing live publishes" for r in unmet]
    lines += [f"    # TODO: calls {r}, which nothing live serves" for r in uncalled]
    if live.ros_version == 1:
        lines.append("    # TODO: add the services this node calls (invisible at the master)")
    lines += [
        "    ros:  # TODO: package and executable",
        "      package: TODO_package",
        "      executable: TODO_executable",
    ]
    if namespace:
        lines.append(f"      namespace: {_q(namespace)}")
    if base != comp:
        if re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", base):
            lines.append(f"      node: {_q(base)}")
        else:
            lines.append(f"      # TODO: runs as {_q(base)}, which no ros.node can name")
    return lines
