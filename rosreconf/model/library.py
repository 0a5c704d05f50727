"""The paper's component library L: interfaces, provisions, requirements, components.

Every class here is a frozen dataclass of tuples and frozensets, so a loaded library can be
shared between the enumerator, the PDDL renderer and the reports without anyone changing it
under the others' feet. Source positions are kept beside the values (``Span``) so that
semantic checks made long after parsing can still point at a line. The name table of the
whole model is in ``rosreconf.model``'s docstring.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from rosreconf.model.context import Condition, ContextVariable
from rosreconf.model.dynamics import Dynamics
from rosreconf.model.qos import QosProfile
from rosreconf.model.span import NOWHERE, Span

__all__ = [  # Span and NOWHERE live in model.span (model.context needs them too)
    "NOWHERE",
    "TYPE_FOLDERS",
    "Component",
    "ComponentLibrary",
    "Interface",
    "InterfaceKind",
    "Requirement",
    "RosLaunch",
    "Span",
    "Substitution",
    "type_folder",
    "type_key",
]


class InterfaceKind(enum.StrEnum):
    """The ways ROS nodes exchange messages (Section 3): topics, services, and ROS actions.

    Actions are not in the paper (2014, ROS 1 actionlib was a library over five topics); ROS
    2 made them a kind of interface of their own, and Nav2's servers talk through them, so a
    library declares them like services: a server provides one, a client requires it.
    """

    TOPIC = "topic"
    SERVICE = "service"
    ACTION = "action"


TYPE_FOLDERS: Mapping[InterfaceKind, str] = MappingProxyType(
    {InterfaceKind.TOPIC: "msg", InterfaceKind.SERVICE: "srv", InterfaceKind.ACTION: "action"}
)
"""The folder ROS 2 writes in a type name of each kind (``sensor_msgs/msg/LaserScan``)."""


def type_key(written: str) -> str:
    """Return the canonical form of a ROS type name: ``pkg/msg/Name`` -> ``pkg/Name``.

    ROS 1 writes ``sensor_msgs/LaserScan``, ROS 2 ``sensor_msgs/msg/LaserScan`` (``srv``,
    ``action`` likewise); both name one message class (Gamma), so every comparison of types
    in rosreconf compares this key: the library's interfaces (``Interface.type``) and a live
    graph's types (``rosreconf.ros.conformance``). Other names are returned unchanged.
    """
    if written.count("/") != 2:
        return written
    package, folder, name = written.split("/")
    return f"{package}/{name}" if folder in _FOLDERS else written


_FOLDERS = frozenset(TYPE_FOLDERS.values())


def type_folder(written: str) -> str | None:
    """Return the ROS 2 folder (``msg``, ``srv``, ``action``) a type name is written with."""
    parts = written.split("/")
    return parts[1] if len(parts) == 3 and parts[1] in _FOLDERS else None


@dataclass(frozen=True, order=True)
class Interface:
    """One topic, service or action: a kind, a label (Omega) and a message class (Gamma).

    Two interfaces match (a provision meets a requirement) exactly when kind, label and type
    are equal, which is why this class is hashable and compared by value. The type compared
    is the canonical key (``type_key``: ``sensor_msgs/msg/LaserScan`` and
    ``sensor_msgs/LaserScan`` are one type); what the user wrote is kept in ``written`` for
    messages, pictures and JSON, and does not take part in comparisons.

    Attributes:
        kind: topic, service or action.
        label: the paper's Omega, a ROS graph resource name such as ``camera_image``.
        type: the paper's Gamma as its canonical key, such as ``sensor_msgs/Image`` (given
            ``sensor_msgs/msg/Image``, it is stored as ``sensor_msgs/Image``).
        written: the type as written in the library (defaults to ``type`` as given).
    """

    kind: InterfaceKind
    label: str
    type: str
    written: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        if not self.written:
            object.__setattr__(self, "written", self.type)
        key = type_key(self.type)
        if key is not self.type:
            object.__setattr__(self, "type", key)

    def __str__(self) -> str:
        return f"{self.kind} '{self.label}' ({self.written})"


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


class Substitution(str):
    """A launch parameter value the user marked as a roslaunch substitution (``$(find ...)``).

    Launch files evaluate ``$(...)`` in every value; only values of this type may carry one,
    so that a library cannot run code on the robot by accident (``rosreconf.formats.values``).
    """

    __slots__ = ()


@dataclass(frozen=True)
class RosLaunch:
    """How to start a component as a ROS node.

    Attributes:
        package: the ROS package that holds the executable.
        executable: the executable (ROS 1 ``type``, ROS 2 ``exec``).
        parameters: private parameters, name -> scalar value.
        remappings: interface label -> the real ROS name the executable uses for it.
        namespace: optional namespace to start the node in.
        lifecycle: ROS 2: the node is a managed (lifecycle) node, taken in and out of service
            by lifecycle transitions rather than by starting and killing its process.
        node: the ROS node base name when it differs from the component's library name
            (two live nodes ``/robot/scan_listener`` and ``/scan_listener`` are two
            components but both run as ``scan_listener``); None = the component's name.
        args: command-line arguments given to the executable, in order
            (``rostopic pub -r 1 ...`` cannot be described without them).
    """

    package: str
    executable: str
    parameters: Mapping[str, str | int | float | bool] = field(
        default_factory=lambda: MappingProxyType({})
    )
    remappings: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    namespace: str | None = None
    lifecycle: bool = False
    node: str | None = None
    args: tuple[str, ...] = ()


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
        qos: ROS 2: topic label -> the QoS of this component's publisher (a provision) or
            subscription (a requirement) on it; labels not listed use the rmw default
            profile (``rosreconf.model.qos``).
        dynamics: its dynamical model for the M-solution (``rosreconf simulate``), if known;
            a role whose component has none is simulated as unity gain.
        description: free text for people.
        when: the conditions on context (``rosreconf.model.context``) that must all hold for
            it to be usable; none = always usable.
        span: where the component was written.
        where: positions of individual values for error messages, keyed ``"name"``,
            ``"abstraction"``, ``"needs.<name>"``, ``"excludes.<name>"``, ``"schemas.<name>"``,
            ``"provides.<i>"``, ``"requires.<i>"``, ``"ros.args.<i>"``, ``"qos.<label>"``,
            ``"when.<name>"``, ``"when.<name>.at_least"``;
            ``""`` is the component itself, when the loader looks positions up only when asked
            (then ``span`` is not given). Positions never take part in comparisons.
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
    qos: Mapping[str, QosProfile] = field(default_factory=lambda: MappingProxyType({}))
    dynamics: Dynamics | None = None
    description: str = ""
    when: tuple[Condition, ...] = ()
    span: Span = field(default=NOWHERE, compare=False)
    where: Mapping[str, Span] = field(default_factory=lambda: MappingProxyType({}), compare=False)

    def at(self, key: str) -> Span:
        """Return where the value ``key`` (see ``where``) is written, else the component."""
        found = self.where.get(key)
        return found if found is not None else self.where.get("", self.span)

    @property
    def node_name(self) -> str:
        """Return the ROS node base name this component runs as (``ros.node``, else its name).

        Library names must be unique and node names need not be (nodes in different
        namespaces), so live checks, launch files and imports use this, never ``name``.
        """
        if self.launch is not None and self.launch.node:
            return self.launch.node
        return self.name

    @property
    def namespace(self) -> str | None:
        """Return the namespace this component's node is started in, if any."""
        return self.launch.namespace if self.launch is not None else None

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
        context: what the robot measures, that components' ``when`` conditions are on.
    """

    name: str
    components: tuple[Component, ...]
    description: str = ""
    source: tuple[str, ...] = ()
    context: tuple[ContextVariable, ...] = ()

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

    @property
    def metrics(self) -> frozenset[str]:
        """Return the metric names some component carries: all an objective can weigh."""
        return frozenset(m for c in self.components for m in c.metrics)

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
            context=tuple(v for lib in libs for v in lib.context),
        )
