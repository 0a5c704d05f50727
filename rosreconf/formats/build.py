"""Build the paper's model objects from well-formed files, with their positions.

The loader calls these only after a file passed its JSON Schema and value checks, so every
key the Schema requires is present and every value has its type; what is left here is to
turn YAML's shapes into the model (components, requirements, launch data, dynamics, system
graphs) and to record where each value was written (``span``, ``where``), so that the
semantic checks can point at ``file:line:column``. It reads the positioned tree
(``yamlsource.read``) through ``nodes``: names as the text written, numbers resolved with
YAML 1.2.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from types import MappingProxyType
from typing import TypeAlias

from rosreconf.formats.nodes import (
    NUMBER,
    SCALAR,
    MappingNode,
    field_text,
    scalars_of,
    seq_of,
    text_of,
)
from rosreconf.formats.nodes import Node as YNode
from rosreconf.formats.nodes import fields as map_of
from rosreconf.formats.nodes import span as span_of
from rosreconf.formats.nodes import value as value_of
from rosreconf.model import (
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

__all__ = ["Interfaces", "Node", "build_library", "build_schema", "provision_key"]

Node: TypeAlias = "YNode | None"
"""What the builder reads: a node of the positioned tree, or None for an absent key."""

_NO_NAMES: frozenset[str] = frozenset()
"""One empty set for every component without needs, excludes or schemas: each empty
frozenset is a 216-byte object of its own, 60 MB over a 10,000-role library."""


def _names(node: Node) -> frozenset[str]:
    """Return a list of names as a set (the shared empty set when there are none)."""
    items = seq_of(node)
    return frozenset(text_of(n) for n in items) if items else _NO_NAMES


Interfaces: TypeAlias = dict[tuple[str, str, str], Interface]
"""The interfaces built so far for one library, by (kind, label, type as written): a large
library writes each of its few distinct interfaces many times, and one shared, equal
(frozen) object per distinct interface saves building and hashing a new one each time."""


def _interface(node: Node, seen: Interfaces, found: _Found) -> Interface:
    """Return the (shared) interface ``node`` describes; record its QoS in ``found``."""
    items = map_of(node)
    kind = "service" if "service" in items else "action" if "action" in items else "topic"
    label = text_of(items[kind])
    key = (kind, label, text_of(items["type"]))
    interface = seen.get(key)
    if interface is None:
        interface = seen[key] = Interface(InterfaceKind(kind), label, key[2])
    if "qos" in items:
        spec = items["qos"]
        found.qos[label] = QosProfile.from_dict(scalars_of(spec))
        found.where[f"qos.{label}"] = span_of(spec)
    return interface


def provision_key(iface: Interface) -> str:
    """Return the ``where`` key of a provision's position (``provides.<kind>:<label>:<type>``)."""
    return f"provides.{iface.kind}:{iface.label}:{iface.written}"


def _requirement(node: Node, seen: Interfaces, found: _Found) -> Requirement:
    items = map_of(node)
    if "any_of" in items:
        options = tuple([_interface(o, seen, found) for o in seq_of(items["any_of"])])
        return Requirement(options, span_of(node))
    return Requirement((_interface(node, seen, found),), span_of(node))


class _Found:
    """What building a component's interfaces finds on the way: QoS profiles and positions.

    Interfaces, their QoS and the positions of both are collected in one walk over a
    component's provisions and requirements (a large library has 35,000 of them).
    """

    __slots__ = ("qos", "where")

    def __init__(self, where: dict[str, Span]) -> None:
        self.qos: dict[str, QosProfile] = {}
        self.where = where


def _launch(node: Node) -> RosLaunch | None:
    items = map_of(node)
    params: dict[str, str | int | float | bool] = {}
    for key, value in map_of(items.get("parameters")).items():
        if type(value) is MappingNode:  # {substitution: ...}, marked by the user
            params[key] = Substitution(text_of(map_of(value)["substitution"]))
            continue
        scalar = value_of(value)
        assert isinstance(scalar, SCALAR)
        params[key] = scalar
    remaps = {k: text_of(v) for k, v in map_of(items.get("remappings")).items()}
    return RosLaunch(
        package=text_of(items["package"]),
        executable=text_of(items["executable"]),
        parameters=MappingProxyType(params),
        remappings=MappingProxyType(remaps),
        namespace=text_of(items["namespace"]) if "namespace" in items else None,
        lifecycle=value_of(items.get("lifecycle")) is True,
        node=text_of(items["node"]) if "node" in items else None,
        args=tuple(text_of(a) for a in seq_of(items.get("args"))),
    )


def _number(node: Node, default: float) -> float:
    value = value_of(node)
    return float(value) if isinstance(value, NUMBER) else default


def _dynamics(node: Node, key: str, where: dict[str, Span]) -> Dynamics:
    """Build a transfer function or state-space model; record where its values are."""
    items = map_of(node)
    where[key] = span_of(node)
    if "delay" in items:
        where[f"{key}.delay"] = span_of(items["delay"])
    delay = _number(items.get("delay"), 0.0)
    if "state_space" in items:
        ss = map_of(items["state_space"])
        where[f"{key}.state_space"] = span_of(items["state_space"])
        matrices: dict[str, tuple[tuple[float, ...], ...]] = {}
        for part in ("A", "B", "C", "D"):
            path = f"{key}.state_space.{part}"
            where[path] = span_of(ss[part])
            rows = []
            for i, row in enumerate(seq_of(ss[part])):
                where[f"{path}.{i}"] = span_of(row)
                cells = seq_of(row)
                for j, n in enumerate(cells):
                    where[f"{path}.{i}.{j}"] = span_of(n)
                rows.append(tuple(_number(n, 0.0) for n in cells))
            matrices[part] = tuple(rows)
        return StateSpace(matrices["A"], matrices["B"], matrices["C"], matrices["D"], delay)
    tf = map_of(items["transfer_function"])
    coefficients: dict[str, tuple[float, ...]] = {}
    for part in ("num", "den"):
        where[f"{key}.{part}"] = span_of(tf[part])
        values = seq_of(tf[part])
        for i, n in enumerate(values):
            where[f"{key}.{part}.{i}"] = span_of(n)
        coefficients[part] = tuple(_number(n, 0.0) for n in values)
    return TransferFunction(coefficients["num"], coefficients["den"], delay)


def _simulation(node: Node, where: dict[str, Span]) -> Simulation:
    """Build a schema's simulation block; positions go under ``simulation.`` in ``where``."""
    items = map_of(node)
    where["simulation"] = span_of(node)
    loops = []
    for i, n in enumerate(seq_of(items["loops"])):
        loop = map_of(n)
        key = f"simulation.loops.{i}"
        where[key] = span_of(n)
        where[f"{key}.name"] = span_of(loop["name"])
        paths: dict[str, tuple[str, ...]] = {}
        for path in ("forward", "feedback"):
            roles = seq_of(loop.get(path))
            for j, r in enumerate(roles):
                where[f"{key}.{path}.{j}"] = span_of(r)
            paths[path] = tuple(text_of(r) for r in roles)
        plant = _dynamics(loop["plant"], f"{key}.plant", where)
        loops.append(ControlLoop(text_of(loop["name"]), paths["forward"], plant, paths["feedback"]))
    limits = map_of(items.get("requirements"))
    for metric, value in limits.items():
        where[f"simulation.requirements.{metric}"] = span_of(value)
    for key in ("reference", "duration"):
        if key in items:
            where[f"simulation.{key}"] = span_of(items[key])
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


def _where_listed(where: dict[str, Span], kind: str, listed: Sequence[YNode]) -> None:
    """Record where each provision or requirement is (``provides.<i>``, ``requires.<i>``)."""
    names = _LIST_KEYS[kind]
    for i, n in enumerate(listed):
        where[names[i] if i < len(names) else sys.intern(f"{kind}.{i}")] = span_of(n)


def _component(node: Node, seen: Interfaces) -> Component:
    items = map_of(node)
    get = items.get
    metrics: dict[str, float] = {}
    for key, value in map_of(get("metrics")).items():
        metric = value_of(value)
        assert isinstance(metric, NUMBER)
        metrics[key] = float(metric)
    provides, requires = seq_of(get("provides")), seq_of(get("requires"))
    where = {"name": span_of(items["name"]), "abstraction": span_of(items["abstraction"])}
    for key in ("needs", "excludes", "schemas"):
        for n in seq_of(get(key)):
            where[f"{key}.{text_of(n)}"] = span_of(n)
    found = _Found(where)
    _where_listed(where, "provides", provides)
    listed = [_interface(n, seen, found) for n in provides]
    provided = frozenset(listed)
    for n, iface in zip(provides, listed, strict=True):  # the set keeps no file order
        where.setdefault(provision_key(iface), span_of(n))
    _where_listed(where, "requires", requires)
    required = tuple([_requirement(n, seen, found) for n in requires])
    for i, n in enumerate(seq_of(map_of(get("ros")).get("args"))):
        where[f"ros.args.{i}"] = span_of(n)
    fp = value_of(get("failure_probability"))
    return Component(
        name=text_of(items["name"]),
        abstraction=text_of(items["abstraction"]),
        provides=provided,
        requires=required,
        failure_probability=float(fp) if isinstance(fp, NUMBER) else None,
        needs=_names(get("needs")) if "needs" in items else _NO_NAMES,
        excludes=_names(get("excludes")) if "excludes" in items else _NO_NAMES,
        schemas=_names(get("schemas")) if "schemas" in items else _NO_NAMES,
        launch=_launch(items["ros"]) if "ros" in items else None,
        metrics=MappingProxyType(metrics),
        qos=MappingProxyType(found.qos),
        dynamics=_dynamics(items["dynamics"], "dynamics", where) if "dynamics" in items else None,
        description=field_text(items, "description"),
        span=span_of(node),
        where=MappingProxyType(where),
    )


def build_library(tree: Node, name: str, seen: Interfaces | None = None) -> ComponentLibrary:
    """Build a library file's model; ``seen`` shares interfaces with files built before.

    ``tree`` is the file's positioned tree (see the module doc). One ``seen`` for all the
    library files of a load makes every use of an interface, in any file, the same object:
    a requirement in one file and the provision meeting it in another then match by
    identity in every set and dict, without a comparison.
    """
    items = map_of(tree)
    if seen is None:
        seen = {}
    return ComponentLibrary(
        name=text_of(items["name"]),
        components=tuple([_component(n, seen) for n in seq_of(items["components"])]),
        description=field_text(items, "description"),
        source=(name,),
    )


def build_schema(tree: Node, name: str) -> InteroperabilitySchema:
    """Build a schema file's model from its positioned tree."""
    items = map_of(tree)
    roles = tuple(
        Role(
            name=text_of(map_of(n)["name"]),
            abstraction=text_of(map_of(n)["abstraction"]),
            description=field_text(map_of(n), "description"),
            span=span_of(n),
            optional=value_of(map_of(n).get("optional")) is True,
        )
        for n in seq_of(items["roles"])
    )
    edges = []
    for n in seq_of(items.get("edges")):
        e = map_of(n)
        interfaces = frozenset(text_of(i) for i in seq_of(e.get("interfaces")))
        optional = value_of(e.get("optional")) is True
        for p in seq_of(e["providers"]):
            edges.append(Edge(text_of(e["consumer"]), text_of(p), interfaces, span_of(p), optional))
    nominal = {k: text_of(v) for k, v in map_of(items.get("nominal")).items()}
    where = {"name": span_of(items["name"])}
    where.update({f"nominal.{k}": span_of(v) for k, v in map_of(items.get("nominal")).items()})
    for n in seq_of(items["roles"]):
        where[f"role.{text_of(map_of(n)['name'])}.abstraction"] = span_of(map_of(n)["abstraction"])
    simulation = _simulation(items["simulation"], where) if "simulation" in items else None
    return InteroperabilitySchema(
        name=text_of(items["name"]),
        title=field_text(items, "title"),
        graph=SystemGraph(roles, tuple(edges)),
        skill=text_of(items["skill"]).strip(),
        environment=text_of(items["environment"]).strip(),
        nominal=MappingProxyType(nominal),
        simulation=simulation,
        span=span_of(tree),
        source=name,
        where=MappingProxyType(where),
    )
