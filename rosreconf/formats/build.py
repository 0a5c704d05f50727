"""Build the paper's model objects from well-formed files, with or without positions.

The loader calls these only after a file passed its JSON Schema and value checks, so every
key the Schema requires is present and every value has its type; what is left here is to
turn YAML's shapes into the model (components, requirements, launch data, dynamics, system
graphs) and to record where each value was written (``span``, ``where``), so that the
semantic checks can point at ``file:line:column``.

A document reaches this one builder in either of two forms (``Node``): the positioned tree
(``yamlsource.parse_plain``), or its plain data alone (``yamlsource.parse_plain_only``, the
loader's first try, several times cheaper to read). Positions are read only to report
problems, so from plain data every span is ``NOWHERE`` and every ``where`` is empty; the
loader reads a file again with positions whenever there is anything to report, and every
compared field of the model is the same from either form (tests/test_lazy_positions.py).
One thing plain data cannot give is the text as written of a scalar that is not a string
(``1.0`` written as a name is "1.0"; its plain value is the float 1.0): there the builder
does not guess but raises ``NeedsPositions`` (the JSON Schema makes every such field a
string, so a checked file never gets there).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import TypeAlias

from rosreconf.formats import yamlsource as ys
from rosreconf.model import (
    NOWHERE,
    Component,
    ComponentLibrary,
    ControlLoop,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    PerformanceRequirements,
    Requirement,
    Role,
    RosLaunch,
    Simulation,
    Span,
    StateSpace,
    Substitution,
    SystemGraph,
    TransferFunction,
)
from rosreconf.model.dynamics import Dynamics
from rosreconf.model.qos import QosProfile

Node: TypeAlias = "ys.YNode | ys.Plain"
"""What the builder reads: a node of the positioned tree, or a value of the plain data."""


class NeedsPositions(Exception):
    """Plain data cannot give what the positioned tree would: build from the tree instead."""


def _text(node: Node) -> str:
    """Return a scalar as the text the user wrote (so names are never turned into numbers).

    A string's plain value is its text as written (quoted or not: ``resolve_plain`` returns
    the text itself for every string); any other plain value is not, so the builder asks
    for the tree rather than guess whether ``1.0`` was written ``1.0`` or ``1.00``.
    """
    if type(node) is str:
        return node
    if isinstance(node, ys.YScalar):
        return node.raw
    if isinstance(node, ys.YNode):
        return ""
    raise NeedsPositions(f"the text of {node!r} as written")


def _field(items: Mapping[str, Node], key: str, default: str = "") -> str:
    """Return the text of ``items[key]`` as written, or ``default`` when the key is absent."""
    return _text(items[key]) if key in items else default


def _span(node: Node) -> Span:
    """Return where ``node`` was written: ``NOWHERE`` for plain data."""
    return node.span if isinstance(node, ys.YNode) else NOWHERE


def _value(node: Node) -> ys.Plain:
    """Return a scalar's resolved value."""
    return node.value if isinstance(node, ys.YScalar) else node  # type: ignore[return-value]


def _seq(node: Node) -> Sequence[Node]:
    if type(node) is list:
        return node
    return node.items if isinstance(node, ys.YSequence) else []


def _map(node: Node) -> Mapping[str, Node]:
    if type(node) is dict:
        return node
    return node.items if isinstance(node, ys.YMapping) else {}


def _plain(node: Node) -> dict[str, object]:
    """Return a (schema-checked) mapping of scalars as plain Python values."""
    collections = (dict, list, ys.YMapping, ys.YSequence)
    return {k: _value(v) for k, v in _map(node).items() if not isinstance(v, collections)}


_NO_NAMES: frozenset[str] = frozenset()
"""One empty set for every component without needs, excludes or schemas: each empty
frozenset is a 216-byte object of its own, 60 MB over a 10,000-role library."""


def _names(node: Node) -> frozenset[str]:
    """Return a list of names as a set (the shared empty set when there are none)."""
    items = _seq(node)
    return frozenset(_text(n) for n in items) if items else _NO_NAMES


Interfaces: TypeAlias = dict[tuple[bool, str, str], Interface]
"""The interfaces built so far for one library, by (is a service, label, type): a large
library writes each of its few distinct interfaces many times, and one shared, equal
(frozen) object per distinct interface saves building and hashing a new one each time."""


def _interface(node: Node, seen: Interfaces, found: _Found) -> Interface:
    """Return the (shared) interface ``node`` describes; record its QoS in ``found``."""
    items = _map(node)
    service = "service" in items
    label = _text(items["service" if service else "topic"])
    key = (service, label, _text(items["type"]))
    interface = seen.get(key)
    if interface is None:
        kind = InterfaceKind.SERVICE if service else InterfaceKind.TOPIC
        interface = seen[key] = Interface(kind, label, key[2])
    if "qos" in items:
        spec = items["qos"]
        found.qos[label] = QosProfile.from_dict(_plain(spec))
        if found.where is not None:
            found.where[f"qos.{label}"] = _span(spec)
    return interface


def _requirement(node: Node, seen: Interfaces, found: _Found) -> Requirement:
    items = _map(node)
    if "any_of" in items:
        options = tuple([_interface(o, seen, found) for o in _seq(items["any_of"])])
        return Requirement(options, _span(node))
    return Requirement((_interface(node, seen, found),), _span(node))


class _Found:
    """What building a component's interfaces finds on the way: QoS profiles and positions.

    Interfaces, their QoS and the positions of both are collected in one walk over a
    component's provisions and requirements (a large library has 35,000 of them); ``where``
    is None when building without positions.
    """

    __slots__ = ("qos", "where")

    def __init__(self, where: dict[str, Span] | None) -> None:
        self.qos: dict[str, QosProfile] = {}
        self.where = where


def _launch(node: Node) -> RosLaunch | None:
    items = _map(node)
    params: dict[str, str | int | float | bool] = {}
    for key, value in _map(items.get("parameters")).items():
        if isinstance(value, dict | ys.YMapping):  # {substitution: ...}, marked by the user
            params[key] = Substitution(_text(_map(value)["substitution"]))
            continue
        scalar = _value(value)
        assert isinstance(scalar, str | int | float | bool)
        params[key] = scalar
    remaps = {k: _text(v) for k, v in _map(items.get("remappings")).items()}
    return RosLaunch(
        package=_text(items["package"]),
        executable=_text(items["executable"]),
        parameters=MappingProxyType(params),
        remappings=MappingProxyType(remaps),
        namespace=_text(items["namespace"]) if "namespace" in items else None,
        lifecycle=_value(items.get("lifecycle")) is True,
        node=_text(items["node"]) if "node" in items else None,
        args=tuple(_text(a) for a in _seq(items.get("args"))),
    )


def _number(node: Node, default: float) -> float:
    value = _value(node)
    return float(value) if isinstance(value, int | float) else default


def _dynamics(node: Node, key: str, where: dict[str, Span] | None) -> Dynamics:
    """Build a transfer function or state-space model; record where its values are."""
    items = _map(node)
    if where is None:
        where = {}  # without positions: every span is NOWHERE, and these are dropped
    where[key] = _span(node)
    if "delay" in items:
        where[f"{key}.delay"] = _span(items["delay"])
    delay = _number(items.get("delay"), 0.0)
    if "state_space" in items:
        ss = _map(items["state_space"])
        where[f"{key}.state_space"] = _span(items["state_space"])
        matrices: dict[str, tuple[tuple[float, ...], ...]] = {}
        for part in ("A", "B", "C", "D"):
            path = f"{key}.state_space.{part}"
            where[path] = _span(ss[part])
            rows = []
            for i, row in enumerate(_seq(ss[part])):
                where[f"{path}.{i}"] = _span(row)
                cells = _seq(row)
                for j, n in enumerate(cells):
                    where[f"{path}.{i}.{j}"] = _span(n)
                rows.append(tuple(_number(n, 0.0) for n in cells))
            matrices[part] = tuple(rows)
        return StateSpace(matrices["A"], matrices["B"], matrices["C"], matrices["D"], delay)
    tf = _map(items["transfer_function"])
    coefficients: dict[str, tuple[float, ...]] = {}
    for part in ("num", "den"):
        where[f"{key}.{part}"] = _span(tf[part])
        values = _seq(tf[part])
        for i, n in enumerate(values):
            where[f"{key}.{part}.{i}"] = _span(n)
        coefficients[part] = tuple(_number(n, 0.0) for n in values)
    return TransferFunction(coefficients["num"], coefficients["den"], delay)


def _simulation(node: Node, where: dict[str, Span] | None) -> Simulation:
    """Build a schema's simulation block; positions go under ``simulation.`` in ``where``."""
    items = _map(node)
    if where is None:
        where = {}  # without positions: every span is NOWHERE, and these are dropped
    where["simulation"] = _span(node)
    loops = []
    for i, n in enumerate(_seq(items["loops"])):
        loop = _map(n)
        key = f"simulation.loops.{i}"
        where[key] = _span(n)
        where[f"{key}.name"] = _span(loop["name"])
        paths: dict[str, tuple[str, ...]] = {}
        for path in ("forward", "feedback"):
            roles = _seq(loop.get(path))
            for j, r in enumerate(roles):
                where[f"{key}.{path}.{j}"] = _span(r)
            paths[path] = tuple(_text(r) for r in roles)
        plant = _dynamics(loop["plant"], f"{key}.plant", where)
        loops.append(ControlLoop(_text(loop["name"]), paths["forward"], plant, paths["feedback"]))
    limits = _map(items.get("requirements"))
    for metric, value in limits.items():
        where[f"simulation.requirements.{metric}"] = _span(value)
    for key in ("reference", "duration"):
        if key in items:
            where[f"simulation.{key}"] = _span(items[key])
    return Simulation(
        loops=tuple(loops),
        reference=_number(items.get("reference"), 1.0),
        duration=_number(items.get("duration"), 10.0),
        requirements=PerformanceRequirements(
            **{m: _number(v, 0.0) for m, v in limits.items()}  # keys fixed by the JSON Schema
        ),
    )


_LIST_KEYS = {
    key: [sys.intern(f"{key}.{i}") for i in range(64)] for key in ("provides", "requires")
}
"""The ``where`` keys of a component's first provisions and requirements: one string per key
for the whole library, not one per component."""

_NOWHERE_ELSE: Mapping[str, Span] = MappingProxyType({})
"""The ``where`` of every component and schema built without positions."""


def _where_listed(where: dict[str, Span] | None, kind: str, listed: Sequence[Node]) -> None:
    """Record where each provision or requirement is (``provides.<i>``, ``requires.<i>``)."""
    if where is None:
        return
    names = _LIST_KEYS[kind]
    for i, n in enumerate(listed):
        where[names[i] if i < len(names) else sys.intern(f"{kind}.{i}")] = _span(n)


def _component(node: Node, seen: Interfaces) -> Component:
    items = _map(node)
    get = items.get
    metrics: dict[str, float] = {}
    for key, value in _map(get("metrics")).items():
        metric = _value(value)
        assert isinstance(metric, int | float)
        metrics[key] = float(metric)
    provides, requires = _seq(get("provides")), _seq(get("requires"))
    where: dict[str, Span] | None = None
    if isinstance(node, ys.YNode):  # positions: where each value of the component is
        where = {"name": _span(items["name"]), "abstraction": _span(items["abstraction"])}
        for key in ("needs", "excludes", "schemas"):
            for n in _seq(get(key)):
                where[f"{key}.{_text(n)}"] = _span(n)
    found = _Found(where)
    _where_listed(where, "provides", provides)
    provided = frozenset([_interface(n, seen, found) for n in provides])
    _where_listed(where, "requires", requires)
    required = tuple([_requirement(n, seen, found) for n in requires])
    if where is not None:
        for i, n in enumerate(_seq(_map(get("ros")).get("args"))):
            where[f"ros.args.{i}"] = _span(n)
    fp = _value(get("failure_probability"))
    return Component(
        name=_text(items["name"]),
        abstraction=_text(items["abstraction"]),
        provides=provided,
        requires=required,
        failure_probability=float(fp) if isinstance(fp, int | float) else None,
        needs=_names(get("needs")),
        excludes=_names(get("excludes")),
        schemas=_names(get("schemas")),
        launch=_launch(items["ros"]) if "ros" in items else None,
        metrics=MappingProxyType(metrics),
        qos=MappingProxyType(found.qos),
        dynamics=_dynamics(items["dynamics"], "dynamics", where) if "dynamics" in items else None,
        description=_field(items, "description"),
        span=_span(node),
        where=_NOWHERE_ELSE if where is None else MappingProxyType(where),
    )


def build_library(tree: Node, name: str, seen: Interfaces | None = None) -> ComponentLibrary:
    """Build a library file's model; ``seen`` shares interfaces with files built before.

    ``tree`` is the file's positioned tree or its plain data (see the module doc). One
    ``seen`` for all the library files of a load makes every use of an interface, in any
    file, the same object: a requirement in one file and the provision meeting it in
    another then match by identity in every set and dict, without a comparison.

    Raises:
        NeedsPositions: plain data where only the tree can give the text as written.
    """
    items = _map(tree)
    if seen is None:
        seen = {}
    return ComponentLibrary(
        name=_text(items["name"]),
        components=tuple([_component(n, seen) for n in _seq(items["components"])]),
        description=_field(items, "description"),
        source=(name,),
    )


def build_schema(tree: Node, name: str) -> InteroperabilitySchema:
    """Build a schema file's model from its positioned tree or its plain data.

    Raises:
        NeedsPositions: plain data where only the tree can give the text as written.
    """
    items = _map(tree)
    roles = tuple(
        Role(
            name=_text(_map(n)["name"]),
            abstraction=_text(_map(n)["abstraction"]),
            description=_field(_map(n), "description"),
            span=_span(n),
        )
        for n in _seq(items["roles"])
    )
    edges = []
    for n in _seq(items.get("edges")):
        e = _map(n)
        interfaces = frozenset(_text(i) for i in _seq(e.get("interfaces")))
        optional = _value(e.get("optional")) is True
        for p in _seq(e["providers"]):
            edges.append(Edge(_text(e["consumer"]), _text(p), interfaces, _span(p), optional))
    nominal = {k: _text(v) for k, v in _map(items.get("nominal")).items()}
    where: dict[str, Span] | None = None
    if isinstance(tree, ys.YNode):  # positions: where each value of the schema is
        where = {"name": _span(items["name"])}
        where.update({f"nominal.{k}": _span(v) for k, v in _map(items.get("nominal")).items()})
        for n in _seq(items["roles"]):
            where[f"role.{_text(_map(n)['name'])}.abstraction"] = _span(_map(n)["abstraction"])
    simulation = _simulation(items["simulation"], where) if "simulation" in items else None
    return InteroperabilitySchema(
        name=_text(items["name"]),
        title=_field(items, "title"),
        graph=SystemGraph(roles, tuple(edges)),
        skill=_text(items["skill"]).strip(),
        environment=_text(items["environment"]).strip(),
        nominal=MappingProxyType(nominal),
        simulation=simulation,
        span=_span(tree),
        source=name,
        where=_NOWHERE_ELSE if where is None else MappingProxyType(where),
    )
