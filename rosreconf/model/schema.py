"""The paper's system graphs, interoperability schemas and configurations (Def. 1, 5, 7, 8).

Frozen like the component library (``rosreconf.model.library``); a configuration is only held
here, its validity is decided by ``rosreconf.model.validity``.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from rosreconf.model.dynamics import Simulation
from rosreconf.model.library import NOWHERE, Interface, InterfaceKind, Span

if TYPE_CHECKING:  # networkx costs 0.2 s to import: only the commands that build graphs pay it
    import networkx as nx


EMPTY = ""
"""The component of an optional role a configuration leaves empty (``Configuration``).

Never a component's name (names start with a letter). Reports print it as ``(empty)`` and
JSON as ``null``."""


def shown(mapping: Mapping[str, str]) -> dict[str, str | None]:
    """Return role -> component with ``None`` for an empty role: the JSON documents' form."""
    return {r: (c if c != EMPTY else None) for r, c in mapping.items()}


def shown_text(component: str) -> str:
    """Return a component as reports print it (``(empty)`` for an empty optional role)."""
    return component if component != EMPTY else "(empty)"


@dataclass(frozen=True)
class Role:
    """A vertex of a system graph: a place one component fills.

    Attributes:
        name: the role's name, unique within its schema.
        abstraction: the label (from Lambda) a component needs to fill it.
        description: free text.
        span: where it was written.
        optional: True when a configuration may leave the role empty (an extension of
            Def. 5: an add-on EKF, a map server not needed under SLAM). Edges touching an empty
            role impose nothing; every requirement of every chosen component must still be
            met along the remaining edges (Lemma 4), so a consumer only the role can serve
            forces it to be filled (docs/formats.md, "Optional roles").
    """

    name: str
    abstraction: str
    description: str = ""
    span: Span = field(default=NOWHERE, compare=False)
    optional: bool = False


@dataclass(frozen=True)
class Edge:
    """A directed edge of a system graph: ``consumer`` uses what ``provider`` provides.

    Information flows from the provider to the consumer (the provider serves the service or
    publishes the topic; the consumer calls or subscribes). The edge is realised in a
    configuration when some requirement option of the consumer's component is provided by the
    provider's component; ``interfaces`` optionally restricts which labels may realise it.

    An edge is *required* by default (Def. 5: every edge of the system graph must be realised
    by the chosen pair). An *optional* edge only says the consumer may use what the provider
    provides: requirements may be met across it, but a pair that shares nothing is still
    valid (a TEB local planner does not read the laser that a DWB planner reads).

    Attributes:
        consumer: the role that requires (calls a service, subscribes to a topic).
        provider: the role that provides (serves, publishes).
        interfaces: labels allowed to realise this edge; empty = any matching interface.
        span: where it was written.
        optional: True when the chosen pair need not realise the edge.
    """

    consumer: str
    provider: str
    interfaces: frozenset[str] = frozenset()
    span: Span = field(default=NOWHERE, compare=False)
    optional: bool = False

    def allows(self, interface: Interface) -> bool:
        """Tell whether ``interface`` may realise this edge."""
        return not self.interfaces or interface.label in self.interfaces


@dataclass(frozen=True)
class SystemGraph:
    """A system graph (Def. 5 (2)): roles labelled from Lambda and directed edges.

    Attributes:
        roles: the roles in the order reports list them (the paper's configuration rows).
        edges: consumer -> provider edges, in file order.
    """

    roles: tuple[Role, ...]
    edges: tuple[Edge, ...]

    def role(self, name: str) -> Role:
        """Return the role called ``name``."""
        for r in self.roles:
            if r.name == name:
                return r
        raise KeyError(name)

    def providers_of(self, consumer: str) -> tuple[Edge, ...]:
        """Return the edges whose consumer is ``consumer``."""
        return tuple(e for e in self.edges if e.consumer == consumer)

    def to_networkx(self) -> nx.DiGraph:
        """Return the graph with edges drawn provider -> consumer (the information flow)."""
        import networkx as nx

        g = nx.DiGraph()
        for r in self.roles:
            g.add_node(r.name, abstraction=r.abstraction, optional=r.optional)
        for e in self.edges:
            g.add_edge(e.provider, e.consumer, interfaces=sorted(e.interfaces), optional=e.optional)
        return g


@dataclass(frozen=True)
class InteroperabilitySchema:
    """An interoperability schema S = [G, x, e] (Def. 7).

    Attributes:
        name: identifier used by components' ``schemas`` lists and on the command line.
        title: a human title ("Object Repositioning").
        graph: the system graph G.
        skill: x, the skill the graph implements.
        environment: e, the environment the skill can operate in.
        nominal: the declared running configuration, role -> component (may be empty).
        simulation: the control loops to simulate and the performance required of them
            (the M-solution), if given.
        span: where the schema was written.
        source: the file it came from.
        where: positions of values for error messages: ``"name"``, ``"nominal.<role>"``,
            ``"role.<role>.abstraction"``.
    """

    name: str
    graph: SystemGraph
    skill: str
    environment: str
    title: str = ""
    nominal: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    simulation: Simulation | None = None
    span: Span = field(default=NOWHERE, compare=False)
    source: str = ""
    where: Mapping[str, Span] = field(default_factory=lambda: MappingProxyType({}), compare=False)

    def at(self, key: str) -> Span:
        """Return where the value ``key`` (see ``where``) is written, else the schema."""
        return self.where.get(key, self.span)

    @property
    def display_name(self) -> str:
        """Return the title when there is one, else the name."""
        return self.title or self.name


@dataclass(frozen=True)
class ConfigurationLibrary:
    """The configuration library C: the list of interoperability schemas Def. 8 names.

    Only the list: what Def. 8 defines about it, orthogonality of C to L, is decided per schema
    by ``rosreconf.analysis.library.analyse`` (docs/architecture.md).
    """

    schemas: tuple[InteroperabilitySchema, ...]

    def __iter__(self) -> Iterator[InteroperabilitySchema]:
        return iter(self.schemas)

    def __len__(self) -> int:
        return len(self.schemas)

    def get(self, name: str) -> InteroperabilitySchema:
        """Return the schema called ``name``."""
        for s in self.schemas:
            if s.name == name:
                return s
        raise KeyError(name)


@dataclass(frozen=True)
class Configuration:
    """A filling of every role of one schema by one component (optional roles may be empty).

    Whether it is *valid* is decided by ``rosreconf.model.validity``; this class only holds it.

    Attributes:
        schema: the schema's name.
        assignment: role -> component name, in the schema's role order; an optional role
            left empty holds ``EMPTY``.
    """

    schema: str
    assignment: tuple[tuple[str, str], ...]

    @staticmethod
    def of(schema: str, mapping: Mapping[str, str], roles: Iterable[Role]) -> Configuration:
        """Build a configuration from a mapping, ordered by the schema's roles.

        An optional role the mapping leaves out (or maps to ``EMPTY``) is empty; a required
        one it leaves out is a ``KeyError``.
        """
        return Configuration(
            schema,
            tuple(
                (r.name, mapping.get(r.name, EMPTY) if r.optional else mapping[r.name])
                for r in roles
            ),
        )

    @property
    def mapping(self) -> dict[str, str]:
        """Return role -> component as a fresh dict (``EMPTY`` for an empty role)."""
        return dict(self.assignment)

    @property
    def shown(self) -> dict[str, str | None]:
        """Return role -> component with ``None`` for an empty role (JSON documents)."""
        return shown(self.mapping)

    @property
    def filled(self) -> dict[str, str]:
        """Return role -> component of the filled roles only, as a fresh dict."""
        return {r: c for r, c in self.assignment if c != EMPTY}

    @property
    def components(self) -> tuple[str, ...]:
        """Return the chosen components in role order (the paper's configuration rows)."""
        return tuple(c for _, c in self.assignment if c != EMPTY)


class VertexKind(enum.StrEnum):
    """The vertex kinds of a ROS-graph (Def. 1, and ROS 2's actions), never interchangeable."""

    NODE = "node"
    TOPIC = "topic"
    SERVICE = "service"
    ACTION = "action"


# RosGraph: a ROS-graph {N, T, S, E} (Def. 1) as a networkx DiGraph.
#
# Vertex ids are tuples ``(VertexKind, name)`` so that a node and a topic of the same name can
# never be confused; every vertex also carries ``kind`` and, for topics and services, ``label``
# (Omega) attributes. Edges run in the direction of information flow: provider node ->
# topic/service -> consumer node, and carry the message class as ``type`` (Gamma). A service
# vertex's name is ``<server node>/<label>``, because in ROS each service has one server (an
# action vertex likewise: one action server); a topic vertex's name is its label, because
# topics are many-to-many.
#
# networkx takes about 0.2 s to import, so it is imported when ``RosGraph`` is first looked up
# (module ``__getattr__``): ``rosreconf --help`` and ``validate`` never need it.
if TYPE_CHECKING:
    RosGraph = nx.DiGraph
else:

    def __getattr__(name: str) -> Any:
        """Return ``RosGraph`` (networkx's DiGraph), importing networkx on first use."""
        if name == "RosGraph":
            import networkx as nx

            return nx.DiGraph
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def node_vertex(name: str) -> tuple[VertexKind, str]:
    """Return the ROS-graph vertex id of the node ``name``."""
    return (VertexKind.NODE, name)


def interface_vertex(interface: Interface, provider: str) -> tuple[VertexKind, str]:
    """Return the ROS-graph vertex id carrying ``interface`` as provided by ``provider``."""
    if interface.kind is InterfaceKind.SERVICE:
        return (VertexKind.SERVICE, f"{provider}/{interface.label}")
    if interface.kind is InterfaceKind.ACTION:
        return (VertexKind.ACTION, f"{provider}/{interface.label}")
    return (VertexKind.TOPIC, interface.label)
