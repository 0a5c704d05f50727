"""Name a configuration's nodes and interfaces as ROS does, and say which kept node must restart.

The model names nodes after components and interfaces after labels (Omega); a live system
uses global ROS names, fixed when a process starts (ROS 1 ``name:=`` and ROS 2 ``--ros-args
-r`` remappings are read once). One pair of functions maps model names to live names::

    model                                   live (global ROS name)
    --------------------------------------  ------------------------------------------------
    component C                             <ros.namespace or />/<ros.node or C>  node_live_name
    interface label X of component C        ros.remappings[X] if given, else X;  interface_live_name
                                            a relative name is resolved in C's namespace

A provider is started as it is; each consumer is remapped, along the edges of the ROS-graph
(Def. 1), from the name it uses for a label to the name its provider really uses. So a
consumer's wiring is a function of the providers chosen beside it. The wiring model
(docs/architecture.md, "The wiring model"): **a kept consumer whose wiring changes is
restarted with its new remappings, and that restart counts as one change**, like a role
that changes component. A component's wiring is the union, over the system-graph edges
into its role, of each interface it uses and the name its provider serves it at
(``wiring_of``): exactly what its start command fixes. ``rewiring`` says which kept
components a new configuration restarts, and ``RestartTable`` gives the solvers the same
rule as facts, so that every engine (elimination and clingo, ``rosreconf.solve``; the PDDL
of ``rosreconf.planning``) and the watcher count a restart exactly when it happens.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from rosreconf.model.library import Component, ComponentLibrary, Interface
from rosreconf.model.schema import EMPTY, Edge, InteroperabilitySchema
from rosreconf.model.validity import edge_interfaces


def _join(namespace: str, name: str) -> str:
    """Return the global name of ``name`` in ``namespace`` (``/arm`` + ``x`` -> ``/arm/x``)."""
    parts = [p for p in (*namespace.split("/"), *name.split("/")) if p]
    return "/" + "/".join(parts)


def node_live_name(component: Component) -> str:
    """Return the global name the node of ``component`` has on the live graph.

    The node's own name (``ros.node``) in its namespace, never the library name: ``import``
    names two live ``scan_listener`` nodes ``scan_listener`` and ``robot_scan_listener``, and
    only the second has a namespace to tell them apart.
    """
    return _join(component.namespace or "/", component.node_name)


def interface_live_name(component: Component, label: str) -> str:
    """Return the global ROS name ``component``'s executable uses, unremapped, for ``label``.

    The library's remapping (``ros.remappings``, label -> real name) wins; a relative name is
    resolved in the component's namespace, as ROS resolves it for a node started there.
    """
    launch = component.launch
    target = launch.remappings.get(label, label) if launch else label
    if target.startswith("/"):
        return _join("/", target)
    return _join((launch.namespace if launch else None) or "/", target)


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
