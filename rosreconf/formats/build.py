"""Build the paper's model objects from well-formed files, with their positions.

The loader calls these only after a file passed its JSON Schema and value checks, so every
key the Schema requires is present and every value has its type. Both formats are built
from their plain data. Where a library's values are written is looked up in its positions
(``positions.Positions``) only when a check asks (``_Where``: a clean library's components
never look); a schema, a small file, has its positions recorded at once (its roles and edges
carry their spans).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from types import MappingProxyType
from typing import Any, TypeAlias

from rosreconf.formats.nodes import NUMBER, Plain
from rosreconf.formats.positions import Place, Positions
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
from rosreconf.model.context import Condition, ContextVariable
from rosreconf.model.dynamics import Dynamics
from rosreconf.model.qos import QosProfile

__all__ = ["Interfaces", "build_library", "build_schema", "provision_key"]

Doc: TypeAlias = dict[str, Any]
"""A mapping of plain data that passed its JSON Schema: its keys and value types are known."""

_NO_NAMES: frozenset[str] = frozenset()
"""One empty set for every component without needs, excludes or schemas: each empty
frozenset is a 216-byte object of its own, 60 MB over a 10,000-role library."""


Interfaces: TypeAlias = dict[tuple[str, str, str], Interface]
"""The interfaces built so far for one library, by (kind, label, type as written): a large
library writes each of its few distinct interfaces many times, and one shared, equal
(frozen) object per distinct interface saves building and hashing a new one each time."""


def _interface(item: Doc, seen: Interfaces, qos: dict[str, QosProfile]) -> Interface:
    """Return the (shared) interface ``item`` describes; record its QoS in ``qos``."""
    kind = _kind(item)
    label = item[kind]
    key = (kind, label, item["type"])
    interface = seen.get(key)
    if interface is None:
        interface = seen[key] = Interface(InterfaceKind(kind), label, key[2])
    if "qos" in item:
        spec = item["qos"].items()
        qos[label] = QosProfile.from_dict({k: v for k, v in spec if type(v) not in _NESTED})
    return interface


_NESTED = (dict, list)


def _kind(keys: Mapping[str, object]) -> str:
    """Return which kind of interface a mapping describes (the JSON Schema allows one)."""
    return "service" if "service" in keys else "action" if "action" in keys else "topic"


def provision_key(iface: Interface) -> str:
    """Return the ``where`` key of a provision's position (``provides.<kind>:<label>:<type>``)."""
    return f"provides.{iface.kind}:{iface.label}:{iface.written}"


def _requirement(item: Doc, seen: Interfaces, qos: dict[str, QosProfile]) -> Requirement:
    """Return a requirement; where it is written is its component's ``requires.<i>``."""
    if "any_of" in item:
        return Requirement(tuple([_interface(o, seen, qos) for o in item["any_of"]]))
    return Requirement((_interface(item, seen, qos),))


def _launch(item: Doc) -> RosLaunch:
    params: dict[str, str | int | float | bool] = {}
    for key, value in item.get("parameters", {}).items():
        marked = type(value) is dict  # {substitution: ...}, marked by the user
        params[key] = Substitution(value["substitution"]) if marked else value
    return RosLaunch(
        package=item["package"],
        executable=item["executable"],
        parameters=MappingProxyType(params),
        remappings=MappingProxyType(dict(item.get("remappings", {}))),
        namespace=item.get("namespace"),
        lifecycle=item.get("lifecycle") is True,
        node=item.get("node"),
        args=tuple(item.get("args", ())),
    )


def _numbers(values: list[Any]) -> tuple[float, ...]:
    return tuple([_float(v, 0.0) for v in values])


def _float(value: Any, default: float) -> float:
    return float(value) if isinstance(value, NUMBER) else default


def _dynamics(item: Doc) -> Dynamics:
    """Build a transfer function or state-space model from its plain data."""
    delay = _float(item.get("delay"), 0.0)
    if "state_space" in item:
        ss = item["state_space"]
        a, b, c, d = (tuple(_numbers(row) for row in ss[part]) for part in "ABCD")
        return StateSpace(a, b, c, d, delay)
    tf = item["transfer_function"]
    return TransferFunction(_numbers(tf["num"]), _numbers(tf["den"]), delay)


def _simulation(item: Doc) -> Simulation:
    """Build a schema's simulation block from its plain data."""
    loops = [
        ControlLoop(
            n["name"],
            tuple(n.get("forward", ())),
            _dynamics(n["plant"]),
            tuple(n.get("feedback", ())),
        )
        for n in item["loops"]
    ]
    return Simulation(
        loops=tuple(loops),
        reference=_float(item.get("reference"), 1.0),
        duration=_float(item.get("duration"), 10.0),
        requirements=PerformanceRequirements(
            **{m: _float(v, 0.0) for m, v in item.get("requirements", {}).items()}
        ),  # keys fixed by the JSON Schema
    )


def _positions(tree: Positions, node: Place, key: str, where: dict[str, Span]) -> None:
    """Record where ``node`` and every value under it are written: ``key``, ``key.<key or i>``..."""
    where[key] = tree.span(node)
    for step, child in [*tree.fields(node).items(), *enumerate(tree.items(node))]:
        _positions(tree, child, f"{key}.{step}" if key else str(step), where)


def _component(item: Doc, seen: Interfaces, where: _Where, keys: _KeySpans) -> Component:
    get = item.get
    qos: dict[str, QosProfile] = {}
    provided = frozenset([_interface(p, seen, qos) for p in get("provides", ())])
    required = tuple([_requirement(r, seen, qos) for r in get("requires", ())])
    fp = get("failure_probability")
    return Component(
        name=item["name"],
        abstraction=item["abstraction"],
        provides=provided,
        requires=required,
        failure_probability=float(fp) if isinstance(fp, NUMBER) else None,
        needs=frozenset(item["needs"]) if get("needs") else _NO_NAMES,
        excludes=frozenset(item["excludes"]) if get("excludes") else _NO_NAMES,
        schemas=frozenset(item["schemas"]) if get("schemas") else _NO_NAMES,
        launch=_launch(item["ros"]) if "ros" in item else None,
        metrics=MappingProxyType({k: float(v) for k, v in get("metrics", {}).items()}),
        qos=MappingProxyType(qos),
        dynamics=_dynamics(item["dynamics"]) if "dynamics" in item else None,
        description=get("description", ""),
        when=_conditions(item["when"], keys.at(where.index)) if "when" in item else (),
        where=where,
    )


def _conditions(when: Doc, names: Callable[[str], Span]) -> tuple[Condition, ...]:
    """Build a component's ``when``; each condition's span is where its name is written."""
    return tuple(
        [
            Condition(
                name,
                at_least=_bound(spec.get("at_least")),
                at_most=_bound(spec.get("at_most")),
                equals=spec.get("equals"),
                span=names(name),
            )
            for name, spec in when.items()
        ]
    )


class _KeySpans:
    """Where a component's ``when`` names are written, from the file's positions read once.

    Only a component with conditions asks; a library without any never reads positions.
    """

    def __init__(self, tree: Callable[[], Positions], table: Positions | None) -> None:
        self._tree, self._places = tree, table

    def at(self, index: int) -> Callable[[str], Span]:
        """Return the finder of component ``index``'s condition names."""

        def name_at(name: str) -> Span:
            if self._places is None:
                self._places = self._tree()
            found = self._places.key_span(["components", index, "when", name])
            return found if found is not None else self._places.span(self._places.root)

        return name_at


def _bound(value: Any) -> float | None:
    return float(value) if isinstance(value, NUMBER) else None


def _context(doc: Doc, places: Positions) -> tuple[ContextVariable, ...]:
    """Build a library's context declarations, each with where it is written."""
    out = []
    for i, v in enumerate(doc.get("context", ())):
        spans = [places.find(["context", i, *key]) for key in ((), ("field",))]
        at, field_at = (places.span(s if s is not None else places.root) for s in spans)
        out.append(ContextVariable(v["name"], v["topic"], v["type"], v["field"], at, field_at))
    return tuple(out)


def component_where(tree: Positions, node: Place) -> dict[str, Span]:
    """Return where a component's values are written (``Component.where``), from its place."""
    where: dict[str, Span] = {}
    _positions(tree, node, "", where)
    items = tree.fields(node)
    for key in ("needs", "excludes", "schemas"):
        where.update((f"{key}.{tree.text(n)}", tree.span(n)) for n in tree.items(items.get(key)))
    provides = tree.items(items.get("provides"))
    for n in provides:  # the first of an interface provided twice
        entry = tree.fields(n)
        kind = _kind(entry)
        written = f"{kind}:{tree.text(entry[kind])}:{tree.text(entry['type'])}"
        where.setdefault(f"provides.{written}", tree.span(n))
    for n in (*provides, *tree.items(items.get("requires"))):  # in build order: last QoS wins
        for iface in tree.items(tree.fields(n).get("any_of")) or [n]:
            entry = tree.fields(iface)
            if "qos" in entry:
                where[f"qos.{tree.text(entry[_kind(entry)])}"] = tree.span(entry["qos"])
    return where


_NAMED = frozenset({"needs", "excludes", "schemas", "provides", "qos"})
"""The ``where`` keys that name a value rather than its path (``component_where``)."""


class _Where(Mapping[str, Span]):
    """A component's ``where``, looked up in its file's positions when first read.

    So positions cost nothing until a problem is reported; ``""`` is the component itself.
    A key that is a path (``abstraction``, ``metrics.cost``) is looked up alone: a warning
    on each of 190,000 components must not keep every position of each.
    ``tree`` gives the file's positions (read again if need be): holding them here would
    keep every file's plain data for the life of the library.
    """

    __slots__ = ("_found", "_index", "_table", "_tree")

    def __init__(self, tree: Callable[[], Positions], table: Positions | None, index: int) -> None:
        self._tree, self._table, self._index = tree, table, index
        self._found: dict[str, Span] | None = None

    @property
    def index(self) -> int:
        """Return the component's index in its file's ``components`` list."""
        return self._index

    def _spans(self) -> dict[str, Span]:
        if self._found is None:
            tree = self._tree()
            self._found = component_where(tree, tree.lookup(["components", self._index]))
        return self._found

    def __getitem__(self, key: str) -> Span:
        if self._found is None and key.partition(".")[0] not in _NAMED:
            steps = [int(s) if s.isdigit() else s for s in key.split(".")] if key else []
            tree = self._table or self._tree()
            found = tree.find(["components", self._index, *steps])
            if found is not None:  # a plain path: no need for every position of the component
                return tree.span(found)
        return self._spans()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._spans())

    def __len__(self) -> int:
        return len(self._spans())


def build_library(
    plain: Plain,
    name: str,
    tree: Callable[[], Positions],
    seen: Interfaces | None = None,
    table: Positions | None = None,
) -> ComponentLibrary:
    """Build a library file's model from its plain data; ``seen`` shares interfaces.

    ``tree`` gives the file's positions with its plain data, called only when a position
    named by a value is asked for (``_Where``): the loader's reads the file again then, so
    that no file's plain data outlives its load. ``table``, the file's positions without
    its plain data (``Positions.without_plain``), places what a path names
    (``abstraction``, ``metrics.cost``) with no second reading. One ``seen`` for all the
    library files of a load makes every use of an interface the same object: a requirement
    and the provision meeting it then match by identity, without a comparison.
    """
    assert isinstance(plain, dict), "a library that passed its JSON Schema is a mapping"
    doc: Doc = plain
    if seen is None:
        seen = {}
    items = doc["components"]
    keys = _KeySpans(tree, table)
    return ComponentLibrary(
        name=doc["name"],
        components=tuple(
            [_component(c, seen, _Where(tree, table, i), keys) for i, c in enumerate(items)]
        ),
        description=doc.get("description", ""),
        source=(name,),
        context=_context(doc, table or tree()) if doc.get("context") else (),
    )


def build_schema(plain: Plain, tree: Positions, name: str) -> InteroperabilitySchema:
    """Build a schema file's model from its plain data, with its positions."""
    assert isinstance(plain, dict), "a schema that passed its JSON Schema is a mapping"
    doc: Doc = plain
    items = tree.fields(tree.root)
    roles_at = tree.items(items["roles"])
    roles = tuple(
        Role(
            r["name"],
            r["abstraction"],
            r.get("description", ""),
            tree.span(n),
            r.get("optional") is True,
        )
        for r, n in zip(doc["roles"], roles_at, strict=True)
    )
    edges = []
    for e, n in zip(doc.get("edges", ()), tree.items(items.get("edges")), strict=True):
        interfaces = frozenset(e.get("interfaces", ()))
        providers = zip(e["providers"], tree.items(tree.fields(n)["providers"]), strict=True)
        for p, at in providers:
            optional = e.get("optional") is True
            edges.append(Edge(e["consumer"], p, interfaces, tree.span(at), optional))
    nominal = items.get("nominal")
    where = {"name": tree.span(items["name"])}
    if nominal is not None:
        where.update({f"nominal.{k}": tree.span(v) for k, v in tree.fields(nominal).items()})
    for r, n in zip(doc["roles"], roles_at, strict=True):
        where[f"role.{r['name']}.abstraction"] = tree.span(tree.fields(n)["abstraction"])
    if "simulation" in items:
        _positions(tree, items["simulation"], "simulation", where)
    return InteroperabilitySchema(
        name=doc["name"],
        title=doc.get("title", ""),
        graph=SystemGraph(roles, tuple(edges)),
        skill=doc["skill"].strip(),
        environment=doc["environment"].strip(),
        nominal=MappingProxyType(dict(doc.get("nominal", {}))),
        simulation=_simulation(doc["simulation"]) if "simulation" in doc else None,
        span=tree.span(tree.root),
        source=name,
        where=MappingProxyType(where),
    )
