"""Decide whether a configuration is valid, build its ROS-graph, and say why not.

This is the one definition of "valid" in rosreconf (docs/formats.md, "What a configuration
is"). The solver, the planner cross-check and the live checks all defer to it, so a plan or
a solver answer is only trusted after ``violations`` comes back empty.

The definition is also *encoded* four more times, for speed: as a clingo program, as the
counting tables, as the elimination tables and as a PDDL task. ``RULES`` lists every rule of
validity once, with the places each encoding implements it, so that a rule added to one is
found in all (tests/test_rules.py demands that all five agree rule by rule).
"""

from __future__ import annotations

import enum
from collections.abc import Collection, Iterator, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    Requirement,
    VertexKind,
    interface_vertex,
    node_vertex,
)

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


class Encoding(enum.StrEnum):
    """The five encodings of validity that must agree."""

    DEFINITION = "definition"
    """``violations`` here: the brute-force reference."""
    CLINGO = "clingo"
    """The ASP program and facts of ``rosreconf.solve.solver`` (enumeration, clingo optimum)."""
    COUNTING = "counting"
    """The 0/1 tables of ``rosreconf.solve.factors`` summed out by ``rosreconf.solve.counting``."""
    ELIMINATION = "elimination"
    """The same tables minimised out by ``rosreconf.solve.optimum`` (the optimum)."""
    PDDL = "pddl"
    """The pre-grounded STRIPS task of ``rosreconf.planning.pddl`` (Fast Downward)."""


@dataclass(frozen=True)
class Rule:
    """One rule of validity, where the paper states it, and where each encoding implements it.

    Attributes:
        name: stable identifier (tests are named after it).
        paper: where the paper defines it (or "extension" with the reason).
        meaning: the rule in one sentence.
        codes: the ``Violation.code`` values the definition reports when it is broken (empty
            for a rule that only relaxes another, such as optional edges).
        places: per encoding, the ``module:function`` places that implement the rule. The
            compiled tables of ``rosreconf.solve.instance`` are shared by clingo, counting,
            elimination and PDDL, so a rule decided there is listed for each of them.
    """

    name: str
    paper: str
    meaning: str
    codes: tuple[str, ...]
    places: Mapping[Encoding, tuple[str, ...]]


_V = "rosreconf.model.validity:"
_I = "rosreconf.solve.instance:"
_S = "rosreconf.solve.solver:"
_F = "rosreconf.solve.factors:"
_P = "rosreconf.planning.pddl:"
_CANDIDATES = {  # who may fill a role is decided once, by the candidate domains
    Encoding.CLINGO: (_I + "compile_instance", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _I + "prune"),
    Encoding.ELIMINATION: (_I + "compile_instance", _I + "prune"),
    Encoding.PDDL: (_I + "compile_instance", _P + "_choose_actions"),
}
_EDGES = {  # realised edges: the edge_ok tables of the required edges
    Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _F + "constraint_factors"),
    Encoding.ELIMINATION: (_I + "compile_instance", _F + "constraint_factors"),
    Encoding.PDDL: (_I + "compile_instance", _P + "_choose_actions"),
}
_REQUIREMENTS = {  # requirements met: the meets tables along every edge of the consumer
    Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _F + "_requirement_factors"),
    Encoding.ELIMINATION: (_I + "compile_instance", _F + "_requirement_factors"),
    Encoding.PDDL: (
        _I + "compile_instance",
        _P + "_connect_actions",
        _P + "_finish_actions",
    ),
}

RULES: tuple[Rule, ...] = (
    Rule(
        "complete",
        "Def. 8",
        "every role of the schema is filled, by a component of the library, and nothing else is",
        ("missing-role", "unknown-component"),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM",),
            Encoding.COUNTING: (_F + "eliminate",),
            Encoding.ELIMINATION: (_F + "eliminate",),
            Encoding.PDDL: (_P + "_finish_actions",),
        },
    ),
    Rule(
        "available",
        "Section 6 (reconfiguration after a failure)",
        "a failed component fills no role",
        ("failed",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "abstraction",
        "Def. 5 (the labelling nu)",
        "a role is filled by a component carrying the role's abstraction",
        ("wrong-abstraction",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "in-schema",
        'Table 1 ("In Schema")',
        "a component whose schemas list is not empty serves only in the schemas it names",
        ("not-in-schema",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "one-role-each",
        "Def. 8 (one node per role)",
        "no component fills two roles",
        ("reused",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM",),
            Encoding.COUNTING: (_F + "constraint_factors",),
            Encoding.ELIMINATION: (_F + "constraint_factors",),
            Encoding.PDDL: (_P + "_Tables.earlier", _P + "_choose_actions"),
        },
    ),
    Rule(
        "edge-realised",
        "Def. 5 and 7 (the system graph's edges)",
        "along every required edge, some requirement option of the consumer's component is "
        "provided by the provider's component",
        ("edge-unrealised",),
        {Encoding.DEFINITION: (_V + "_violations", _V + "edge_interfaces"), **_EDGES},
    ),
    Rule(
        "edge-interfaces",
        "extension (an edge's interfaces list)",
        "an edge that lists interfaces is realised, and meets requirements, only by those labels",
        ("edge-unrealised", "requirement-unmet"),
        {
            Encoding.DEFINITION: (_V + "edge_interfaces", _V + "requirement_met"),
            Encoding.CLINGO: (_I + "compile_instance", _I + "_allows"),
            Encoding.COUNTING: (_I + "compile_instance", _I + "_allows"),
            Encoding.ELIMINATION: (_I + "compile_instance", _I + "_allows"),
            Encoding.PDDL: (_I + "compile_instance", _I + "_allows"),
        },
    ),
    Rule(
        "requirement-met",
        "Def. 3 and Lemma 4",
        "every requirement of every chosen component is provided by the component of a role "
        "the consumer's role has an edge to",
        ("requirement-unmet",),
        {Encoding.DEFINITION: (_V + "_violations", _V + "requirement_met"), **_REQUIREMENTS},
    ),
    Rule(
        "any-of",
        "Def. 3 (NREA uses whichever servo command the arm offers)",
        "a requirement with several options is met by any one of them",
        ("requirement-unmet",),
        {Encoding.DEFINITION: (_V + "requirement_met",), **_REQUIREMENTS},
    ),
    Rule(
        "needs",
        'Section 5 ("NVP1 needs NCO1 and NCA1")',
        "a chosen component's needs are chosen too",
        ("needs",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_F + "constraint_factors", _F + "_needs_met"),
            Encoding.ELIMINATION: (_F + "constraint_factors", _F + "_needs_met"),
            Encoding.PDDL: (_P + "_choose_actions", _P + "_finish_actions"),
        },
    ),
    Rule(
        "excludes",
        "Section 5 (components that cannot run together)",
        "a chosen component's excludes are not chosen (either way round)",
        ("excludes",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_F + "constraint_factors",),
            Encoding.ELIMINATION: (_F + "constraint_factors",),
            Encoding.PDDL: (_P + "_Tables", _P + "_choose_actions"),
        },
    ),
    Rule(
        "one-type-per-label",
        "Def. 1 (a topic or service vertex carries one message class, Gamma)",
        "no two chosen components provide one topic or service label with different types "
        "(raw and compressed images under one name are alternatives, never chosen together)",
        ("type-clash",),
        {
            Encoding.DEFINITION: (_V + "_violations", _V + "type_clash"),
            Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_I + "compile_instance", _F + "constraint_factors"),
            Encoding.ELIMINATION: (_I + "compile_instance", _F + "constraint_factors"),
            Encoding.PDDL: (_I + "compile_instance", _P + "_Tables", _P + "_choose_actions"),
        },
    ),
    Rule(
        "optional-edge",
        "extension (edges only some candidates use; issue 10)",
        "an optional edge need not be realised, but requirements may still be met across it",
        (),
        {
            Encoding.DEFINITION: (_V + "_violations", _V + "requirement_met"),
            Encoding.CLINGO: (_I + "compile_instance",),
            Encoding.COUNTING: (_I + "compile_instance",),
            Encoding.ELIMINATION: (_I + "compile_instance",),
            Encoding.PDDL: (_I + "compile_instance",),
        },
    ),
)
"""Every rule of validity, once. Adding a rule: see docs/formats.md, "Adding a rule"."""


def type_clash(a: Component, b: Component) -> tuple[Interface, Interface] | None:
    """Return a provision of ``a`` and one of ``b`` with one label but two types, if any.

    A ROS name carries one message type, so two such components cannot run together even
    when the library allows both (rule ``one-type-per-label``).
    """
    theirs = {(i.kind, i.label): i for i in b.provides}
    for mine in sorted(a.provides):
        other = theirs.get((mine.kind, mine.label))
        if other is not None and other.type != mine.type:
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
    """Tell whether some provider along ``consumer_role``'s edges meets ``req``."""
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
        if name is None:
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

    Nodes are the chosen components; along every system-graph edge (optional ones too, where
    the pair shares something), each interface that realises it becomes a topic or service
    vertex with edges provider -> vertex -> consumer.
    Provisions nobody uses stay dormant (Section 3) and are not drawn.
    """
    import networkx as nx  # here, not at the top: validating files never builds a ROS-graph

    g: RosGraph = nx.DiGraph()
    mapping = configuration.mapping
    for role in schema.graph.roles:
        comp = library[mapping[role.name]]
        g.add_node(node_vertex(comp.name), kind=VertexKind.NODE, role=role.name, label=comp.name)
    for edge in schema.graph.edges:
        consumer = library[mapping[edge.consumer]]
        provider = library[mapping[edge.provider]]
        for iface in edge_interfaces(consumer, provider, edge):
            v = interface_vertex(iface, provider.name)
            kind = VertexKind.SERVICE if iface.kind is InterfaceKind.SERVICE else VertexKind.TOPIC
            g.add_node(v, kind=kind, label=iface.label, type=iface.type)
            g.add_edge(node_vertex(provider.name), v, type=iface.type)
            g.add_edge(v, node_vertex(consumer.name), type=iface.type)
    return g


def graph_dict(g: RosGraph) -> dict[str, list[dict[str, str]]]:
    """Return a ROS-graph as the JSON shape of docs/json.md (nodes, topics, services, edges)."""
    out: dict[str, list[dict[str, str]]] = {"nodes": [], "topics": [], "services": [], "edges": []}
    for (kind, name), data in sorted(g.nodes(data=True)):
        entry = {"id": name}
        if kind is VertexKind.NODE:
            entry["role"] = str(data.get("role", ""))
            out["nodes"].append(entry)
        else:
            entry.update(label=str(data["label"]), type=str(data["type"]))
            out["topics" if kind is VertexKind.TOPIC else "services"].append(entry)
    for (k1, n1), (k2, n2), data in sorted(g.edges(data=True)):
        out["edges"].append(
            {"from": n1, "from_kind": k1.value, "to": n2, "to_kind": k2.value, "type": data["type"]}
        )
    return out
