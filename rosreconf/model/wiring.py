"""Name a configuration's nodes and interfaces as ROS does, and say which kept node must restart.

The model names nodes after components and interfaces after labels (Omega); a live system
uses global ROS names, fixed when a process starts (ROS 1 ``name:=`` and ROS 2 ``--ros-args
-r`` remappings are read once). One resolver (``resolve_name``, ROS's own rules) and the
functions built on it map model names to live names, for wiring, conformance, launch files
and stand-ins alike::

    model                                   live (global ROS name)
    --------------------------------------  ------------------------------------------------
    component C                             <ros.namespace or />/<ros.node or C>  node_live_name
    interface label X of component C        the name C's executable asks for       spelled_name
                                            (ros.remappings[X] if given, else X),
                                            resolved for C's node:            interface_live_name
                                            /x absolute; x in C's namespace;
                                            ~/x or ~x under C's node name

A provider is started as it is; each consumer is remapped, along the edges of the ROS-graph
(Def. 1), from the name it uses for a label to the name its provider really uses, when the
two resolved names differ. So a consumer's wiring is a function of the providers chosen
beside it. The wiring model (docs/architecture.md, "The wiring model"): **a kept consumer
whose wiring changes is restarted with its new remappings, and that restart counts as one
change**, like a role that changes component. A component's wiring is the union, over the
system-graph edges into its role, of each interface it uses and the resolved name its
provider serves it at (``wiring_of``): exactly what its start command fixes. ``rewiring``
says which kept components a new configuration restarts, and ``RestartTable`` gives the
solvers the same rule as facts, so that every engine (elimination and clingo,
``rosreconf.solve``; the PDDL of ``rosreconf.planning``) and the watcher count a restart
exactly when it happens.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from rosreconf.model.library import Component, ComponentLibrary, Interface
from rosreconf.model.schema import EMPTY, Edge, InteroperabilitySchema
from rosreconf.model.validity import edge_interfaces

_SUBSTITUTION = re.compile(r"\{([^{}]*)\}")


def _join(namespace: str, name: str) -> str:
    """Return the global name of ``name`` in ``namespace`` (``/arm`` + ``x`` -> ``/arm/x``)."""
    parts = [p for p in (*namespace.split("/"), *name.split("/")) if p]
    return "/" + "/".join(parts)


def expand_name(name: str, node: str, namespace: str | None = None) -> str:
    """Return the fully qualified name node ``node`` in ``namespace`` has for ``name``.

    The rules of ``rcl_expand_topic_name`` (ros2/rcl, ``rcl/src/rcl/expand_topic_name.c``),
    in its order, which ROS 1 (``rosgraph.names.resolve_name``, roscpp's ``names::resolve``)
    shares for the names it allows:

    - ``~`` starts a private name: ``~/x`` (ROS 2) and ``~x`` (ROS 1) are
      ``<namespace>/<node>/x``, ``~`` alone is the node's own name;
    - ``{node}`` is the node's name, ``{ns}`` and ``{namespace}`` its namespace (ROS 2);
    - a name that is still not absolute is relative: ``<namespace>/x``; ``/x`` is itself.

    A namespace is absolute: none is ``/``, and a relative one (``sensors``) is taken from
    the root, as ``rcl_node_init`` and a top-level roslaunch ``ns`` take it.

    Raises:
        ValueError: a substitution other than those three (rcl refuses it too).
    """
    ns = _join("/", namespace or "/")
    if name.startswith("~"):
        name = f"{_join(ns, node)}/{name[1:]}"

    def substitute(found: re.Match[str]) -> str:
        key = found.group(1)
        if key == "node":
            return node
        if key in ("ns", "namespace"):
            return ns
        raise ValueError(f"unknown substitution {{{key}}} in the ROS name {name!r}")

    name = _SUBSTITUTION.sub(substitute, name)
    return _join("/", name) if name.startswith("/") else _join(ns, name)


def resolve_name(
    name: str,
    node: str,
    namespace: str | None = None,
    rules: Iterable[tuple[str, str]] = (),
) -> str:
    """Return the name node ``node`` in ``namespace``, started with ``rules``, uses for ``name``.

    ``rules`` are its remappings (``-r from:=to``, ``<remap from= to=>``), in order. As
    ``rcl_remap_name`` (``rcl/src/rcl/remap.c``) applies them: ``name`` is expanded first
    (``expand_name``); the first rule whose ``from``, expanded for this node too, equals it
    replaces it by its ``to``, expanded for this node; only one rule ever applies. So a rule
    ``scan:=/sensors/scan`` matches ``/nav/scan`` in ``/nav`` and ``/scan`` in ``/``. ROS 1
    resolves both sides of each mapping in the node's namespace likewise and looks the
    resolved name up (``rospy.names.initialize_mappings``, roscpp's ``names::init``).
    """
    expanded = expand_name(name, node, namespace)
    for match, replacement in rules:
        if expand_name(match, node, namespace) == expanded:
            return expand_name(replacement, node, namespace)
    return expanded


def node_namespace(component: Component) -> str | None:
    """Return the absolute namespace ``component``'s node is started in, if it has one.

    A library may write ``sensors``; rcl refuses ``-r __ns:=sensors`` (a namespace rule
    must be absolute) and resolves every name of the node in ``/sensors``, so that is what
    launch files, ``--ros-args`` and stand-ins are given.
    """
    return _join("/", component.namespace) if component.namespace else None


def node_live_name(component: Component) -> str:
    """Return the global name the node of ``component`` has on the live graph.

    The node's own name (``ros.node``) in its namespace, never the library name: ``import``
    names two live ``scan_listener`` nodes ``scan_listener`` and ``robot_scan_listener``, and
    only the second has a namespace to tell them apart.
    """
    return _join(component.namespace or "/", component.node_name)


def spelled_name(component: Component, label: str) -> str:
    """Return the name ``component``'s executable asks ROS for, for ``label``, as written.

    The library's remapping (``ros.remappings``, label -> the real name) wins, else the
    label: what the node's code spells, relative, private or absolute. A remap rule for the
    node rewrites this name (``rule_spelling`` writes it for rcl).
    """
    launch = component.launch
    return launch.remappings.get(label, label) if launch is not None else label


def interface_live_name(
    component: Component, label: str, rules: Iterable[tuple[str, str]] = ()
) -> str:
    """Return the global ROS name ``component``'s node uses for ``label``, started with ``rules``.

    Its spelled name (``spelled_name``) resolved for its node, in its namespace, as ROS
    resolves it (``resolve_name``); with no ``rules``, the name its executable uses unwired.
    """
    return resolve_name(
        spelled_name(component, label), component.node_name, component.namespace, rules
    )


def rule_spelling(name: str) -> str:
    """Return ``name`` as a remap rule may spell it for both ROS 1 and ROS 2: ``~x`` as ``~/x``.

    rcl refuses ``~x`` (a tilde must be followed by ``/``, ``validate_topic_name.c``); ROS 1
    resolves the two alike in a remapping (``rosgraph.names.resolve_name``), so a ROS 1
    file may keep the executable's own spelling.
    """
    if name.startswith("~") and len(name) > 1 and name[1] != "/":
        return "~/" + name[1:]
    return name


ACTIONLIB_TOPICS = ("goal", "cancel", "status", "feedback", "result")
"""The topics ROS 1 actionlib puts under an action's name (``<action>/goal`` ...)."""
ROS2_ACTION_NAMES = (
    "_action/send_goal",
    "_action/cancel_goal",
    "_action/get_result",
    "_action/feedback",
    "_action/status",
)
"""The services and topics rcl_action puts under a ROS 2 action's name."""


def remap_rules(source: str, target: str, action: bool, ros_version: int) -> list[tuple[str, str]]:
    """Return the remap rules (from, to) that point a node's ``source`` name at ``target``.

    A topic or service takes one rule. An action takes one per name under it, because a
    rule for the action's own name moves none of them: ROS 1 actionlib's five topics, and
    ROS 2's three services and two topics. rcl_action of Jazzy (rcl 9) builds those names
    from the action's name without remapping it; Kilted's (rcl 10, ros2/rcl#1170) remaps the
    name first, and still applies a rule to each name under it. Measured on both with rclpy:
    ``-r relocalize:=/relocalize`` moved the client of ``/nav/relocalize`` on Kilted only;
    the five rules moved it on both. A ROS 2 rule spells a private name ``~/x``
    (``rule_spelling``).
    """
    if ros_version == 2:
        source = rule_spelling(source)
    if not action:
        return [(source, target)]
    parts = ROS2_ACTION_NAMES if ros_version == 2 else ACTIONLIB_TOPICS
    return [(f"{source}/{part}", f"{target}/{part}") for part in parts]


Wire = tuple[Interface, str]
"""One thing a consumer is wired to: an interface it uses and the name its provider serves."""


def edge_wiring(consumer: Component, provider: Component | None, edge: Edge) -> frozenset[Wire]:
    """Return the interfaces ``consumer`` uses along ``edge`` and the names they are served at.

    An empty (optional) provider role wires nothing.
    """
    if provider is None:
        return frozenset()
    return frozenset(
        (iface, interface_live_name(provider, iface.label))
        for iface in edge_interfaces(consumer, provider, edge)
    )


def wiring_of(
    library: ComponentLibrary, schema: InteroperabilitySchema, mapping: Mapping[str, str]
) -> dict[str, frozenset[Wire]]:
    """Return role -> what its component is wired to: the union over its edges (Def. 1).

    This is what its start command fixes (the remappings, and the options a stand-in acts
    out); an empty role has none.
    """
    filled = {r: c for r, c in mapping.items() if c != EMPTY}
    known = library.by_name
    out: dict[str, set[Wire]] = {r: set() for r in filled}
    for edge in schema.graph.edges:
        consumer, provider = filled.get(edge.consumer), filled.get(edge.provider)
        if consumer is not None and provider is not None:
            out[edge.consumer] |= edge_wiring(known[consumer], known[provider], edge)
    return {r: frozenset(w) for r, w in out.items()}


@dataclass(frozen=True)
class RestartTable:
    """What the running components are wired to, and what each choice would wire them to.

    The solvers' restart facts: a kept component of role ``u`` restarts exactly when the
    union, over the system-graph edges into ``u``, of ``offers[(u, v)][choice of v]`` differs
    from ``wired[u]``. Choices missing from ``offers[(u, v)]`` wire nothing along that edge.

    Attributes:
        wired: consumer role -> what its running component is wired to now.
        offers: (consumer role, provider role) -> provider choice (a component name,
            ``EMPTY`` for an empty optional role) -> what it would wire the kept consumer to.
    """

    wired: Mapping[str, frozenset[Wire]] = field(default_factory=dict)
    offers: Mapping[tuple[str, str], Mapping[str, frozenset[Wire]]] = field(default_factory=dict)

    def restarted(self, current: Mapping[str, str], mapping: Mapping[str, str]) -> set[str]:
        """Return the roles whose running component ``mapping`` keeps and must restart."""
        now: dict[str, set[Wire]] = {}
        for (u, v), offer in self.offers.items():
            if mapping.get(u) == current.get(u):
                now.setdefault(u, set()).update(offer.get(mapping.get(v, EMPTY), ()))
        return {
            u
            for u, was in self.wired.items()
            if mapping.get(u) == current.get(u) and now.get(u, set()) != was
        }


def restart_table(
    library: ComponentLibrary, schema: InteroperabilitySchema, current: Mapping[str, str]
) -> RestartTable:
    """Return the restart facts of a reconfiguration away from ``current`` (``RestartTable``).

    Only running components that require something can be rewired; every candidate of each
    provider role along an edge into theirs is offered.
    """
    known = library.by_name
    roles = {r.name: r for r in schema.graph.roles}
    by_abstraction: dict[str, list[str]] = {}
    for c in library.components:
        by_abstraction.setdefault(c.abstraction, []).append(c.name)
    now = wiring_of(library, schema, current)
    wired: dict[str, frozenset[Wire]] = {}
    offers: dict[tuple[str, str], dict[str, frozenset[Wire]]] = {}
    for edge in schema.graph.edges:
        kept = known.get(current.get(edge.consumer, EMPTY))
        if kept is None or not kept.requires or edge.consumer == edge.provider:
            continue
        wired[edge.consumer] = now.get(edge.consumer, frozenset())
        role = roles[edge.provider]
        for name in by_abstraction.get(role.abstraction, []):
            offer = edge_wiring(kept, known[name], edge)
            if offer:
                offers.setdefault((edge.consumer, edge.provider), {})[name] = offer
    return RestartTable(wired, offers)


def rewiring(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    old: Mapping[str, str],
    new: Mapping[str, str],
) -> dict[str, str]:
    """Return role -> why, for each kept component ``new`` must restart to rewire it.

    A component is kept when it holds the same role in both configurations; it is rewired
    when the interfaces it uses, or the names its providers serve them at, differ (the
    module docstring: the wiring model).
    """
    before, after = wiring_of(library, schema, old), wiring_of(library, schema, new)
    out = {}
    for role, was in before.items():
        kept = new.get(role)
        if kept is None or kept != old.get(role) or after.get(role, frozenset()) == was:
            continue
        now = after.get(role, frozenset())
        came, gone = _some(now - was), _some(was - now)
        if not came:
            how = f"it no longer uses {gone}"
        elif not gone:
            how = f"it now also uses {came}"
        else:
            how = f"it now uses {came}, instead of {gone}"
        out[role] = (
            f"{kept} ({role}) restarts to be rewired, since ROS names are fixed when a node "
            f"starts: {how}"
        )
    return out


def _some(wires: frozenset[Wire]) -> str:
    """Say a few wires ("label at /name"), and how many more there are ("" for none)."""
    said = sorted(f"{i.label} at {n}" for i, n in wires)
    more = f" and {len(said) - 2} more" if len(said) > 2 else ""
    return ", ".join(said[:2]) + more


def used_interfaces(
    library: ComponentLibrary, schema: InteroperabilitySchema, mapping: Mapping[str, str]
) -> dict[str, frozenset[Interface]]:
    """Return component -> the requirement options it uses along its ROS-graph edges.

    A node started for a configuration acts out only these (a stand-in calls, subscribes and
    sends goals to no alternative it is not wired to), so its live graph is the ROS-graph.
    """
    filled = {r: c for r, c in mapping.items() if c != EMPTY}
    known = library.by_name
    out: dict[str, set[Interface]] = {c: set() for c in filled.values()}
    for edge in schema.graph.edges:
        consumer, provider = filled.get(edge.consumer), filled.get(edge.provider)
        if consumer is None or provider is None:
            continue
        out[consumer] |= {i for i, _ in edge_wiring(known[consumer], known[provider], edge)}
    return {c: frozenset(v) for c, v in out.items()}
