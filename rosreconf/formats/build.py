"""Build the paper's model objects from well-formed positioned trees.

The loader calls these only after a file passed its JSON Schema and value checks, so every
key the Schema requires is present and every value has its type; what is left here is to
turn YAML's shapes into the model (components, requirements, launch data, dynamics, system
graphs) and to record where each value was written (``where``), so that the semantic checks
and the solvers' explanations can point at ``file:line:column``.
"""

from __future__ import annotations

import sys
from types import MappingProxyType
from typing import TypeAlias

from rosreconf.formats import yamlsource as ys
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


def _text(node: ys.YNode | None, default: str = "") -> str:
    """Return a scalar as the text the user wrote (so names are never turned into numbers)."""
    if isinstance(node, ys.YScalar):
        return node.raw
    return default


def _seq(node: ys.YNode | None) -> list[ys.YNode]:
    return node.items if isinstance(node, ys.YSequence) else []


def _map(node: ys.YNode | None) -> dict[str, ys.YNode]:
    return node.items if isinstance(node, ys.YMapping) else {}


def _plain(node: ys.YNode) -> dict[str, object]:
    """Return a (schema-checked) mapping of scalars as plain Python values."""
    return {k: v.value for k, v in _map(node).items() if isinstance(v, ys.YScalar)}


_NO_NAMES: frozenset[str] = frozenset()
"""One empty set for every component without needs, excludes or schemas: each empty
frozenset is a 216-byte object of its own, 60 MB over a 10,000-role library."""


def _names(node: ys.YNode | None) -> frozenset[str]:
    """Return a list of names as a set (the shared empty set when there are none)."""
    items = _seq(node)
    return frozenset(_text(n) for n in items) if items else _NO_NAMES


Interfaces: TypeAlias = dict[tuple[bool, str, str], Interface]
"""The interfaces built so far for one library, by (is a service, label, type): a large
library writes each of its few distinct interfaces many times, and one shared, equal
(frozen) object per distinct interface saves building and hashing a new one each time."""


def _interface(node: ys.YNode, seen: Interfaces, found: _Found) -> Interface:
    """Return the (shared) interface ``node`` describes; record its QoS in ``found``."""
    items = _map(node)
    service = "service" in items
    label = _text(items["service" if service else "topic"])
    key = (service, label, _text(items["type"]))
    interface = seen.get(key)
    if interface is None:
        kind = InterfaceKind.SERVICE if service else InterfaceKind.TOPIC
        interface = seen[key] = Interface(kind, label, key[2])
    spec = items.get("qos")
    if spec is not None:
        found.qos[label] = QosProfile.from_dict(_plain(spec))
        found.where[f"qos.{label}"] = spec.span
    return interface


def _requirement(node: ys.YNode, seen: Interfaces, found: _Found) -> Requirement:
    items = _map(node)
    if "any_of" in items:
        options = tuple([_interface(o, seen, found) for o in _seq(items["any_of"])])
        return Requirement(options, node.span)
    return Requirement((_interface(node, seen, found),), node.span)


class _Found:
    """What building a component's interfaces finds on the way: QoS profiles and positions.

    Interfaces, their QoS and the positions of both are collected in one walk over a
    component's provisions and requirements (a large library has 35,000 of them).
    """

    __slots__ = ("qos", "where")

    def __init__(self, where: dict[str, Span]) -> None:
        self.qos: dict[str, QosProfile] = {}
        self.where = where


def _launch(node: ys.YNode | None) -> RosLaunch | None:
    if node is None:
        return None
    items = _map(node)
    params: dict[str, str | int | float | bool] = {}
    for key, value in _map(items.get("parameters")).items():
        if isinstance(value, ys.YMapping):  # {substitution: ...}, marked by the user
            params[key] = Substitution(_text(value.items["substitution"]))
            continue
        assert isinstance(value, ys.YScalar) and value.value is not None
        params[key] = value.value
    remaps = {k: _text(v) for k, v in _map(items.get("remappings")).items()}
    ns = items.get("namespace")
    lifecycle = items.get("lifecycle")
    node_name = items.get("node")
    return RosLaunch(
        package=_text(items["package"]),
        executable=_text(items["executable"]),
        parameters=MappingProxyType(params),
        remappings=MappingProxyType(remaps),
        namespace=_text(ns) if ns is not None else None,
        lifecycle=isinstance(lifecycle, ys.YScalar) and lifecycle.value is True,
        node=_text(node_name) if node_name is not None else None,
        args=tuple(_text(a) for a in _seq(items.get("args"))),
    )


def _number(node: ys.YNode | None, default: float) -> float:
    if isinstance(node, ys.YScalar) and isinstance(node.value, int | float):
        return float(node.value)
    return default


def _dynamics(node: ys.YNode | None, key: str, where: dict[str, Span]) -> Dynamics | None:
    """Build a transfer function or state-space model; record where its values are."""
    if node is None:
        return None
    items = _map(node)
    where[key] = node.span
    if "delay" in items:
        where[f"{key}.delay"] = items["delay"].span
    delay = _number(items.get("delay"), 0.0)
    if "state_space" in items:
        ss = _map(items["state_space"])
        where[f"{key}.state_space"] = items["state_space"].span
        matrices: dict[str, tuple[tuple[float, ...], ...]] = {}
        for part in ("A", "B", "C", "D"):
            path = f"{key}.state_space.{part}"
            where[path] = ss[part].span
            rows = []
            for i, row in enumerate(_seq(ss[part])):
                where[f"{path}.{i}"] = row.span
                cells = _seq(row)
                for j, n in enumerate(cells):
                    where[f"{path}.{i}.{j}"] = n.span
                rows.append(tuple(_number(n, 0.0) for n in cells))
            matrices[part] = tuple(rows)
        return StateSpace(matrices["A"], matrices["B"], matrices["C"], matrices["D"], delay)
    tf = _map(items["transfer_function"])
    coefficients: dict[str, tuple[float, ...]] = {}
    for part in ("num", "den"):
        where[f"{key}.{part}"] = tf[part].span
        values = _seq(tf[part])
        for i, n in enumerate(values):
            where[f"{key}.{part}.{i}"] = n.span
        coefficients[part] = tuple(_number(n, 0.0) for n in values)
    return TransferFunction(coefficients["num"], coefficients["den"], delay)


def _simulation(node: ys.YNode | None, where: dict[str, Span]) -> Simulation | None:
    """Build a schema's simulation block; positions go under ``simulation.`` in ``where``."""
    if node is None:
        return None
    items = _map(node)
    where["simulation"] = node.span
    loops = []
    for i, n in enumerate(_seq(items["loops"])):
        loop = _map(n)
        key = f"simulation.loops.{i}"
        where[key] = n.span
        where[f"{key}.name"] = loop["name"].span
        paths: dict[str, tuple[str, ...]] = {}
        for path in ("forward", "feedback"):
            roles = _seq(loop.get(path))
            for j, r in enumerate(roles):
                where[f"{key}.{path}.{j}"] = r.span
            paths[path] = tuple(_text(r) for r in roles)
        plant = _dynamics(loop["plant"], f"{key}.plant", where)
        assert plant is not None
        loops.append(ControlLoop(_text(loop["name"]), paths["forward"], plant, paths["feedback"]))
    limits = _map(items.get("requirements"))
    for metric, value in limits.items():
        where[f"simulation.requirements.{metric}"] = value.span
    for key in ("reference", "duration"):
        if key in items:
            where[f"simulation.{key}"] = items[key].span
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


def _component(node: ys.YNode, seen: Interfaces) -> Component:
    items = _map(node)
    get = items.get
    fp = get("failure_probability")
    metrics: dict[str, float] = {}
    for key, value in _map(get("metrics")).items():
        assert isinstance(value, ys.YScalar) and isinstance(value.value, int | float)
        metrics[key] = float(value.value)
    where = {"name": items["name"].span, "abstraction": items["abstraction"].span}
    for key in ("needs", "excludes", "schemas"):
        if key in items:
            for n in _seq(items[key]):
                where[f"{key}.{_text(n)}"] = n.span
    found = _Found(where)
    provides, requires = _seq(get("provides")), _seq(get("requires"))
    names = _LIST_KEYS["provides"]
    for i, n in enumerate(provides):
        where[names[i] if i < len(names) else sys.intern(f"provides.{i}")] = n.span
    provided = frozenset([_interface(n, seen, found) for n in provides])
    names = _LIST_KEYS["requires"]
    for i, n in enumerate(requires):
        where[names[i] if i < len(names) else sys.intern(f"requires.{i}")] = n.span
    required = tuple([_requirement(n, seen, found) for n in requires])
    ros = get("ros")
    if ros is not None:
        for i, n in enumerate(_seq(_map(ros).get("args"))):
            where[f"ros.args.{i}"] = n.span
    dynamics = _dynamics(get("dynamics"), "dynamics", where)
    return Component(
        name=_text(items["name"]),
        abstraction=_text(items["abstraction"]),
        provides=provided,
        requires=required,
        failure_probability=(
            float(fp.value) if isinstance(fp, ys.YScalar) and fp.value is not None else None
        ),
        needs=_names(get("needs")),
        excludes=_names(get("excludes")),
        schemas=_names(get("schemas")),
        launch=_launch(ros),
        metrics=MappingProxyType(metrics),
        qos=MappingProxyType(found.qos),
        dynamics=dynamics,
        description=_text(get("description")),
        span=node.span,
        where=MappingProxyType(where),
    )


def build_library(tree: ys.YMapping, name: str, seen: Interfaces | None = None) -> ComponentLibrary:
    """Build a library file's model; ``seen`` shares interfaces with files built before.

    One ``seen`` for all the library files of a load makes every use of an interface, in
    any file, the same object: a requirement in one file and the provision meeting it in
    another then match by identity in every set and dict, without a comparison.
    """
    items = tree.items
    if seen is None:
        seen = {}
    return ComponentLibrary(
        name=_text(items["name"]),
        components=tuple([_component(n, seen) for n in _seq(items["components"])]),
        description=_text(items.get("description")),
        source=(name,),
    )


def build_schema(tree: ys.YMapping, name: str) -> InteroperabilitySchema:
    items = tree.items
    roles = tuple(
        Role(
            name=_text(_map(n)["name"]),
            abstraction=_text(_map(n)["abstraction"]),
            description=_text(_map(n).get("description")),
            span=n.span,
        )
        for n in _seq(items["roles"])
    )
    edges = []
    for n in _seq(items.get("edges")):
        e = _map(n)
        interfaces = frozenset(_text(i) for i in _seq(e.get("interfaces")))
        opt = e.get("optional")
        optional = isinstance(opt, ys.YScalar) and opt.value is True
        for p in _seq(e["providers"]):
            edges.append(Edge(_text(e["consumer"]), _text(p), interfaces, p.span, optional))
    nominal = {k: _text(v) for k, v in _map(items.get("nominal")).items()}
    where = {"name": items["name"].span}
    where.update({f"nominal.{k}": v.span for k, v in _map(items.get("nominal")).items()})
    for n in _seq(items["roles"]):
        where[f"role.{_text(_map(n)['name'])}.abstraction"] = _map(n)["abstraction"].span
    simulation = _simulation(items.get("simulation"), where)
    return InteroperabilitySchema(
        name=_text(items["name"]),
        title=_text(items.get("title")),
        graph=SystemGraph(roles, tuple(edges)),
        skill=_text(items["skill"]).strip(),
        environment=_text(items["environment"]).strip(),
        nominal=MappingProxyType(nominal),
        simulation=simulation,
        span=tree.span,
        source=name,
        where=MappingProxyType(where),
    )
