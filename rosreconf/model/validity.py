"""Decide whether a configuration is valid, build its ROS-graph, and say why not.

This is the one definition of "valid" in rosreconf (docs/formats.md, "What a configuration
is"). The solver, the planner cross-check and the live checks all defer to it, so a plan or
a solver answer is only trusted after ``violations`` comes back empty.

The definition is also *encoded* four more times, for speed: as a clingo program, as the
counting tables, as the elimination tables and as a PDDL task. ``RULES``
(``rosreconf.model.rules``) lists every rule of validity once, with the places each encoding
implements it, so that a rule added to one is found in all (tests/test_rules.py demands that
all five agree rule by rule).
"""

from __future__ import annotations

from collections.abc import Collection, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Configuration,
    Edge,
    Interface,
    InteroperabilitySchema,
    Requirement,
    VertexKind,
    interface_vertex,
    node_vertex,
)
from rosreconf.model.rules import RULES, Encoding, Rule

__all__ = [
    "RULES",
    "Encoding",
    "Rule",
    "Violation",
    "edge_interfaces",
    "graph_dict",
    "is_valid",
    "requirement_met",
    "ros_graph",
    "type_clash",
    "violations",
]

if TYPE_CHECKING:
    from rosreconf.model import RosGraph


@dataclass(frozen=True)
class Violation:
    """One reason a configuration is not valid.

    Attributes:
        code: stable identifier (``failed``, ``wrong-abstraction``, ``not-in-schema``,
            ``reused``, ``edge-unrealised``, ``requirement-unmet``, ``needs``, ``excludes``,
            ``unknown-component``, ``missing-role``, ``type-clash``).
        message: the reason in plain words.
        components: the components involved (for reports and pictures).
    """

    code: str
    message: str
    components: tuple[str, ...] = ()

    def __str__(self) -> str:
        return self.message


def type_clash(a: Component, b: Component) -> tuple[Interface, Interface] | None:
    """Return a provision of ``a`` and one of ``b`` with one label but two types, if any.

    A ROS name carries one message type, so two such components cannot run together even
    when the library allows both (rule ``one-type-per-label``).
    """
    # Every provision of b with the label, not one: a component may itself provide one label
    # with two types, and keeping one of them per label (a dict) missed the other depending on
    # set iteration order, which the string hash seed changes from run to run.
    theirs = sorted(b.provides)
    for mine in sorted(a.provides):
        for other in theirs:
            if (other.kind, other.label) == (mine.kind, mine.label) and other.type != mine.type:
                # ``type`` is the canonical key: pkg/msg/X and pkg/X do not clash
                return mine, other
    return None


def edge_interfaces(consumer: Component, provider: Component, edge: Edge) -> tuple[Interface, ...]:
    """Return the interfaces that can realise ``edge`` between the two components.

    An interface realises the edge when it is an option of one of the consumer's
    requirements, the provider provides it, and the edge allows its label.
    """
    found: list[Interface] = []
    for req in consumer.requires:
        for option in req.options:
            if option in provider.provides and edge.allows(option) and option not in found:
                found.append(option)
    return tuple(found)


def requirement_met(
    req: Requirement,
    consumer_role: str,
    schema: InteroperabilitySchema,
    chosen: dict[str, Component],
) -> bool:
    """Tell whether some provider along ``consumer_role``'s edges meets ``req`` (Lemma 4).

    Lemma 4 says that within a ROS-graph every service and topic a node requires (S-, T-)
    is provided (S+, T+); an action a client requires is met the same way, by an action
    server of the same label and type along an edge, like a service. Checking it here, one
    requirement at a time along the schema's edges, is what makes every valid configuration
    a ROS-graph in the lemma's sense.
    """
    for edge in schema.graph.providers_of(consumer_role):
        provider = chosen.get(edge.provider)
        if provider is None:
            continue
        if any(o in provider.provides and edge.allows(o) for o in req.options):
            return True
    return False


def violations(
    configuration: Configuration,
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str] = (),
) -> list[Violation]:
    """Return every reason ``configuration`` is not a valid configuration of ``schema``."""
    return list(_violations(configuration, library, schema, frozenset(failed)))


def is_valid(
    configuration: Configuration,
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str] = (),
) -> bool:
    """Tell whether ``configuration`` is valid (no violations)."""
    return not any(True for _ in _violations(configuration, library, schema, frozenset(failed)))


def _violations(
    configuration: Configuration,
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: frozenset[str],
) -> Iterator[Violation]:
    mapping = configuration.mapping
    chosen: dict[str, Component] = {}
    for role in schema.graph.roles:
        name = mapping.get(role.name)
        if name is None or name == EMPTY:
            if not role.optional:  # rule optional-role: only an optional role may be empty
                yield Violation("missing-role", f"role '{role.name}' is not filled")
            continue
        if name not in library:
            yield Violation("unknown-component", f"'{name}' is not in the library", (name,))
            continue
        comp = library[name]
        chosen[role.name] = comp
        if name in failed:
            yield Violation("failed", f"{name} ({role.name}) has failed", (name,))
        if comp.abstraction != role.abstraction:
            yield Violation(
                "wrong-abstraction",
                f"{name} is a {comp.abstraction}; role '{role.name}' needs a {role.abstraction}",
                (name,),
            )
        if not comp.may_serve_in(schema.name):
            yield Violation(
                "not-in-schema",
                f"{name} may only serve in {', '.join(sorted(comp.schemas))}, "
                f"not in {schema.display_name}",
                (name,),
            )
    extra = set(mapping) - {r.name for r in schema.graph.roles}
    for role_name in sorted(extra):
        yield Violation("missing-role", f"'{role_name}' is not a role of {schema.display_name}")
    seen: dict[str, str] = {}
    for role_name, comp in chosen.items():
        if comp.name in seen:
            yield Violation(
                "reused",
                f"{comp.name} fills both '{seen[comp.name]}' and '{role_name}'",
                (comp.name,),
            )
        seen[comp.name] = role_name
    for edge in schema.graph.edges:
        consumer, provider = chosen.get(edge.consumer), chosen.get(edge.provider)
        if consumer is None or provider is None or edge.optional:
            continue
        if not edge_interfaces(consumer, provider, edge):
            yield Violation(
                "edge-unrealised",
                f"{consumer.name} ({edge.consumer}) uses nothing {provider.name} "
                f"({edge.provider}) provides: {consumer.name} requires "
                f"{_requires_text(consumer)}; {provider.name} provides {_provides_text(provider)}",
                (consumer.name, provider.name),
            )
    for role_name, comp in chosen.items():
        for req in comp.requires:
            if not requirement_met(req, role_name, schema, chosen):
                yield Violation(
                    "requirement-unmet",
                    f"{comp.name} ({role_name}) requires {req}, which no provider along its "
                    "edges offers",
                    (comp.name,),
                )
    distinct = sorted({c.name: c for c in chosen.values()}.values(), key=lambda c: c.name)
    for i, a in enumerate(distinct):
        for b in distinct[i + 1 :]:
            clash = type_clash(a, b)
            if clash is not None:
                yield Violation(
                    "type-clash",
                    f"{a.name} provides {clash[0]} and {b.name} provides {clash[1]}: one ROS "
                    "name cannot carry two types",
                    (a.name, b.name),
                )
    names = {c.name for c in chosen.values()}
    for comp in chosen.values():
        for need in sorted(comp.needs - names):
            yield Violation(
                "needs", f"{comp.name} needs {need}, which is not chosen", (comp.name, need)
            )
        for ex in sorted(comp.excludes & names):
            yield Violation(
                "excludes", f"{comp.name} excludes {ex}, which is chosen", (comp.name, ex)
            )


def _requires_text(c: Component) -> str:
    return ", ".join(_short(r.options) for r in c.requires) or "nothing"


def _provides_text(c: Component) -> str:
    return _short(tuple(sorted(c.provides))) if c.provides else "nothing"


def _short(options: tuple[Interface, ...]) -> str:
    return " or ".join(o.label for o in options)


def ros_graph(
    configuration: Configuration, library: ComponentLibrary, schema: InteroperabilitySchema
) -> RosGraph:
    """Build the concrete ROS-graph (Def. 1) of a valid configuration.

    Nodes are the chosen components (an empty optional role has none); along every
    system-graph edge between two filled roles (optional edges too, where the pair shares
    something), each interface that realises it becomes a topic, service or action vertex with
    edges provider -> vertex -> consumer, carrying the type as written.
    Provisions nobody uses stay dormant (Section 3) and are not drawn.
    """
    import networkx as nx  # here, not at the top: validating files never builds a ROS-graph

    g: RosGraph = nx.DiGraph()
    mapping = configuration.filled  # an empty optional role has no node and no edges
    for role in schema.graph.roles:
        if role.name not in mapping:
            continue
        comp = library[mapping[role.name]]
        g.add_node(node_vertex(comp.name), kind=VertexKind.NODE, role=role.name, label=comp.name)
    for edge in schema.graph.edges:
        if edge.consumer not in mapping or edge.provider not in mapping:
            continue
        consumer = library[mapping[edge.consumer]]
        provider = library[mapping[edge.provider]]
        for iface in edge_interfaces(consumer, provider, edge):
            v = interface_vertex(iface, provider.name)
            # the type as its provider writes it (pkg/msg/X or pkg/X: one key, two spellings)
            written = next(p.written for p in provider.provides if p == iface)
            g.add_node(v, kind=v[0], label=iface.label, type=written)
            g.add_edge(node_vertex(provider.name), v, type=written)
            g.add_edge(v, node_vertex(consumer.name), type=iface.written)
    return g


def graph_dict(g: RosGraph) -> dict[str, list[dict[str, str]]]:
    """Return a ROS-graph as the JSON shape of docs/json.md (nodes, topics, services, actions,
    edges).
    """
    out: dict[str, list[dict[str, str]]] = {
        "nodes": [],
        "topics": [],
        "services": [],
        "actions": [],
        "edges": [],
    }
    lists = {
        VertexKind.TOPIC: "topics",
        VertexKind.SERVICE: "services",
        VertexKind.ACTION: "actions",
    }
    for (kind, name), data in sorted(g.nodes(data=True)):
        entry = {"id": name}
        if kind is VertexKind.NODE:
            entry["role"] = str(data.get("role", ""))
            out["nodes"].append(entry)
        else:
            entry.update(label=str(data["label"]), type=str(data["type"]))
            out[lists[kind]].append(entry)
    for (k1, n1), (k2, n2), data in sorted(g.edges(data=True)):
        out["edges"].append(
            {"from": n1, "from_kind": k1.value, "to": n2, "to_kind": k2.value, "type": data["type"]}
        )
    return out
