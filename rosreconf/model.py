"""The paper's model: immutable, free of I/O, named as in Aitken, Veres and Judge (2014).

Every class here is a frozen dataclass of tuples and frozensets, so a loaded library or
schema can be shared between the enumerator, the PDDL renderer and the reports without
anyone changing it under the others' feet. Source positions are kept beside the values
(``Span``) so that semantic checks made long after parsing can still point at a line.

How the paper's names map onto this module::

    paper                                  here
    -------------------------------------  ------------------------------------------
    Omega (interface label)                Interface.label
    Gamma (message class)                  Interface.type
    S+ / T+ (Def. 2, provision)            Component.provides
    S- / T- (Def. 3, requirement)          Component.requires (each a Requirement)
    abstraction N -> Lambda (Def. 5 (1))   Component.abstraction
    component library L                    ComponentLibrary
    system graph (Def. 5 (2))              SystemGraph (roles labelled from Lambda)
    interoperability schema [G, x, e]      InteroperabilitySchema (graph, skill, environment)
    configuration library C (Def. 8)       ConfigurationLibrary
    ROS-graph {N, T, S, E} (Def. 1)        RosGraph (a networkx DiGraph, three vertex kinds)
    configuration                          Configuration (role -> component)
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import NamedTuple

import networkx as nx


class Span(NamedTuple):
    """Where a value was written: file, 1-based line and column.

    A NamedTuple rather than a dataclass: a large library creates one per YAML event
    (hundreds of thousands), and tuples are several times cheaper to build; they are just as
    immutable, ordered and hashable.

    Attributes:
        file: the path as the user gave it (or a bundled resource name).
        line: 1-based line number.
        column: 1-based column number.
    """

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


NOWHERE = Span("<model>", 0, 0)
"""The span of values built in code rather than read from a file."""


class InterfaceKind(enum.StrEnum):
    """The two ways ROS nodes exchange messages (Section 3): topics and services."""

    TOPIC = "topic"
    SERVICE = "service"


@dataclass(frozen=True, order=True)
class Interface:
    """One topic or service: a kind, a label (Omega) and a message class (Gamma).

    Two interfaces match (a provision meets a requirement) exactly when all three are equal,
    which is why this class is hashable and compared by value.

    Attributes:
        kind: topic or service.
        label: the paper's Omega, a ROS graph resource name such as ``camera_image``.
        type: the paper's Gamma, a ROS message or service type such as ``sensor_msgs/Image``.
    """

    kind: InterfaceKind
    label: str
    type: str

    def __str__(self) -> str:
        return f"{self.kind} '{self.label}' ({self.type})"


@dataclass(frozen=True)
class Requirement:
    """One need of a component (Def. 3): any one of ``options`` satisfies it.

    Most requirements have one option; the paper's reasoner NREA has two (it uses whichever
    servo command the chosen arm offers), which is why a requirement is a disjunction.

    Attributes:
        options: the interfaces, any one of which satisfies this requirement (non-empty).
        span: where the requirement was written.
    """

    options: tuple[Interface, ...]
    span: Span = field(default=NOWHERE, compare=False)

    def __str__(self) -> str:
        if len(self.options) == 1:
            return str(self.options[0])
        return "any one of " + ", ".join(str(o) for o in self.options)

    def met_by(self, provided: Iterable[Interface]) -> tuple[Interface, ...]:
        """Return the options of this requirement found in ``provided`` (in option order)."""
        have = frozenset(provided)
        return tuple(o for o in self.options if o in have)


@dataclass(frozen=True)
class RosLaunch:
    """How to start a component as a ROS node.

    Attributes:
        package: the ROS package that holds the executable.
        executable: the executable (ROS 1 ``type``, ROS 2 ``exec``).
        parameters: private parameters, name -> scalar value.
        remappings: interface label -> the real ROS name the executable uses for it.
        namespace: optional namespace to start the node in.
    """

    package: str
    executable: str
    parameters: Mapping[str, str | int | float | bool] = field(
        default_factory=lambda: MappingProxyType({})
    )
    remappings: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    namespace: str | None = None


@dataclass(frozen=True)
class Component:
    """A library node (Def. 2/3): what it provides, what it requires, what it is.

    Attributes:
        name: a valid ROS node base name, unique in the library (and case-insensitively so,
            because PDDL names are case-insensitive).
        abstraction: the Def. 5 label (Lambda) saying which role class it can play.
        provides: services it serves and topics it publishes (S+, T+).
        requires: services it calls and topics it subscribes (S-, T-), each a disjunction.
        failure_probability: probability in [0, 1] that it is unavailable, if known.
        needs: components that must be chosen with it (the paper's "NVP1 needs NCO1 and NCA1").
        excludes: components that must not be chosen with it.
        schemas: names of the schemas it may serve in (Table 1's "In Schema"); empty = any.
        launch: how to start it, if known.
        metrics: named numbers (cost, settling_time, ...) for optimisation.
        description: free text for people.
        span: where the component was written.
        where: positions of individual values for error messages, keyed ``"name"``,
            ``"abstraction"``, ``"needs.<name>"``, ``"excludes.<name>"``, ``"schemas.<name>"``,
            ``"provides.<i>"``, ``"requires.<i>"``.
    """

    name: str
    abstraction: str
    provides: frozenset[Interface] = frozenset()
    requires: tuple[Requirement, ...] = ()
    failure_probability: float | None = None
    needs: frozenset[str] = frozenset()
    excludes: frozenset[str] = frozenset()
    schemas: frozenset[str] = frozenset()
    launch: RosLaunch | None = None
    metrics: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))
    description: str = ""
    span: Span = field(default=NOWHERE, compare=False)
    where: Mapping[str, Span] = field(default_factory=lambda: MappingProxyType({}), compare=False)

    def at(self, key: str) -> Span:
        """Return where the value ``key`` (see ``where``) is written, else the component."""
        return self.where.get(key, self.span)

    def may_serve_in(self, schema_name: str) -> bool:
        """Tell whether Table 1's "In Schema" column lets this component serve ``schema_name``."""
        return not self.schemas or schema_name in self.schemas

    def __hash__(self) -> int:
        return hash(self.name)


@dataclass(frozen=True)
class ComponentLibrary:
    """The component library L: the available nodes (a ROS system provision, Def. 2).

    Attributes:
        name: the library's name.
        components: the components, in file order.
        description: free text.
        source: the file(s) it came from.
    """

    name: str
    components: tuple[Component, ...]
    description: str = ""
    source: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "_by_name", MappingProxyType({c.name: c for c in self.components}))

    @property
    def by_name(self) -> Mapping[str, Component]:
        """Return the components keyed by name."""
        by_name: Mapping[str, Component] = self._by_name  # type: ignore[attr-defined]
        return by_name

    def __getitem__(self, name: str) -> Component:
        return self.by_name[name]

    def __contains__(self, name: object) -> bool:
        return name in self.by_name

    def __iter__(self) -> Iterator[Component]:
        return iter(self.components)

    def __len__(self) -> int:
        return len(self.components)

    def candidates(self, abstraction: str) -> tuple[Component, ...]:
        """Return the components carrying ``abstraction``, in library order (nu^-1(a))."""
        return tuple(c for c in self.components if c.abstraction == abstraction)

    @property
    def abstractions(self) -> frozenset[str]:
        """Return the label set Lambda used by this library."""
        return frozenset(c.abstraction for c in self.components)

    @staticmethod
    def merge(libraries: Iterable[ComponentLibrary]) -> ComponentLibrary:
        """Join several library files into one L (names must already be unique)."""
        libs = tuple(libraries)
        if len(libs) == 1:
            return libs[0]
        return ComponentLibrary(
            name="+".join(lib.name for lib in libs),
            components=tuple(c for lib in libs for c in lib.components),
            description="; ".join(lib.description for lib in libs if lib.description),
            source=tuple(s for lib in libs for s in lib.source),
        )


@dataclass(frozen=True)
class Role:
    """A vertex of a system graph: a place one component fills.

    Attributes:
        name: the role's name, unique within its schema.
        abstraction: the label (from Lambda) a component needs to fill it.
        description: free text.
        span: where it was written.
    """

    name: str
    abstraction: str
    description: str = ""
    span: Span = field(default=NOWHERE, compare=False)


@dataclass(frozen=True)
class Edge:
    """A directed edge of a system graph: ``consumer`` uses what ``provider`` provides.

    Information flows from the provider to the consumer (the provider serves the service or
    publishes the topic; the consumer calls or subscribes). The edge is realised in a
    configuration when some requirement option of the consumer's component is provided by the
    provider's component; ``interfaces`` optionally restricts which labels may realise it.

    Attributes:
        consumer: the role that requires (calls a service, subscribes to a topic).
        provider: the role that provides (serves, publishes).
        interfaces: labels allowed to realise this edge; empty = any matching interface.
        span: where it was written.
    """

    consumer: str
    provider: str
    interfaces: frozenset[str] = frozenset()
    span: Span = field(default=NOWHERE, compare=False)

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
        g = nx.DiGraph()
        for r in self.roles:
            g.add_node(r.name, abstraction=r.abstraction)
        for e in self.edges:
            g.add_edge(e.provider, e.consumer, interfaces=sorted(e.interfaces))
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
    """The configuration library C (Def. 8): the list of interoperability schemas."""

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
    """A filling of every role of one schema by one component.

    Whether it is *valid* is decided by ``rosreconf.validity``; this class only holds it.

    Attributes:
        schema: the schema's name.
        assignment: role -> component name, in the schema's role order.
    """

    schema: str
    assignment: tuple[tuple[str, str], ...]

    @staticmethod
    def of(schema: str, mapping: Mapping[str, str], roles: Iterable[Role]) -> Configuration:
        """Build a configuration from a mapping, ordered by the schema's roles."""
        return Configuration(schema, tuple((r.name, mapping[r.name]) for r in roles))

    @property
    def mapping(self) -> dict[str, str]:
        """Return role -> component as a fresh dict."""
        return dict(self.assignment)

    @property
    def components(self) -> tuple[str, ...]:
        """Return the chosen components in role order (the paper's configuration rows)."""
        return tuple(c for _, c in self.assignment)


class VertexKind(enum.StrEnum):
    """The three vertex kinds of a ROS-graph (Def. 1), never interchangeable."""

    NODE = "node"
    TOPIC = "topic"
    SERVICE = "service"


RosGraph = nx.DiGraph
"""A ROS-graph {N, T, S, E} (Def. 1) as a networkx DiGraph.

Vertex ids are tuples ``(VertexKind, name)`` so that a node and a topic of the same name can
never be confused; every vertex also carries ``kind`` and, for topics and services, ``label``
(Omega) attributes. Edges run in the direction of information flow: provider node ->
topic/service -> consumer node, and carry the message class as ``type`` (Gamma). A service
vertex's name is ``<server node>/<label>``, because in ROS each service has one server; a
topic vertex's name is its label, because topics are many-to-many.
"""


def node_vertex(name: str) -> tuple[VertexKind, str]:
    """Return the ROS-graph vertex id of the node ``name``."""
    return (VertexKind.NODE, name)


def interface_vertex(interface: Interface, provider: str) -> tuple[VertexKind, str]:
    """Return the ROS-graph vertex id carrying ``interface`` as provided by ``provider``."""
    if interface.kind is InterfaceKind.SERVICE:
        return (VertexKind.SERVICE, f"{provider}/{interface.label}")
    return (VertexKind.TOPIC, interface.label)
