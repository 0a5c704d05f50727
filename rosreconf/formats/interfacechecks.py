"""Check that interfaces agree across a library's components and that requirements are met.

A label names one message class and one kind (topic, service or action) in every component
that uses it, and some component must provide every interface a requirement names (the
condition of Lemma 4). A ROS 2 type name's folder must fit its kind (``pkg/msg/X`` for a
topic, ``pkg/srv/X`` for a service, ``pkg/action/X`` for an action; ``pkg/X`` fits all).
``checks.check`` runs these with the other semantic checks.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence

from rosreconf.errors import Problem, Severity
from rosreconf.formats.build import provision_key
from rosreconf.model import Component, Interface, InterfaceKind, Requirement, Span, type_folder
from rosreconf.model.library import TYPE_FOLDERS


def _all_interfaces(c: Component) -> Iterator[tuple[Interface, int, Requirement | None]]:
    """Yield each interface of ``c`` with what ``_where`` needs to say where it is written.

    The position itself is made only for the few that a check keeps or reports: a large
    library has 35,000 interfaces and a handful of distinct ones.
    """
    for i, iface in enumerate(sorted(c.provides)):
        yield iface, i, None
    for i, req in enumerate(c.requires):
        for iface in req.options:
            yield iface, i, req


class InterfaceIndex:
    """The distinct interfaces of a library: what a clean library's checks are decided on.

    The loader shares each distinct interface (``build.Interfaces``): a thousand-role
    library's 45,000 provisions and options are a few thousand objects. Options are kept once
    per object (``id``), skipping the interface's own hash (a Python function) for each
    repeat; correct whether or not interfaces are shared, only slower when they are not.

    Attributes:
        provided: every interface some component provides.
        options: every option of every requirement, each object once.
    """

    def __init__(
        self, provided: Iterable[frozenset[Interface]], options: Sequence[Interface]
    ) -> None:
        self.provided: set[Interface] = set().union(*provided)
        once = dict(zip(map(id, options), options, strict=True))
        self.options: list[Interface] = list(once.values())

    def agree(self) -> bool:
        """Tell whether each (kind, label) has one message class and each label one kind.

        Exactly when ``_conflicts`` has nothing to report, in whatever order it walks.
        """
        types: dict[tuple[InterfaceKind, str], str] = {}
        kinds: dict[str, InterfaceKind] = {}
        for iface in (*self.provided, *self.options):
            if types.setdefault((iface.kind, iface.label), iface.type) != iface.type:
                return False
            if kinds.setdefault(iface.label, iface.kind) is not iface.kind:
                return False
        return True

    def well_spelled(self) -> bool:
        """Tell whether every type's ROS 2 folder (if written) fits its interface's kind."""
        return all(_spelled_right(i) for i in (*self.provided, *self.options))

    def all_met(self) -> bool:
        """Tell whether every option of every requirement is provided (so every one is met)."""
        return self.provided.issuperset(self.options)


def index_problems(components: Sequence[Component], index: InterfaceIndex) -> Iterator[Problem]:
    """Yield type and kind conflicts and unmet requirements, each decided on ``index`` first."""
    if not index.well_spelled():
        yield from _misspelled(components)
    if not index.agree():
        yield from _conflicts(components)
    if not index.all_met():
        yield from _unmet(components, index.provided)


def _where(c: Component, i: int, req: Requirement | None, iface: Interface | None = None) -> Span:
    """Return where ``_all_interfaces`` found an interface (its provision or requirement)."""
    if req is None:
        at = c.where.get(provision_key(iface)) if iface is not None else None
        return at or c.at(f"provides.{i}")
    return req.span if req.span.line else c.at(f"requires.{i}")


def _spelled_right(iface: Interface) -> bool:
    folder = type_folder(iface.written)
    return folder is None or folder == TYPE_FOLDERS[iface.kind]


def _misspelled(components: Sequence[Component]) -> Iterator[Problem]:
    """Yield each type written with the ROS 2 folder of another kind (``pkg/msg/X`` service)."""
    for c in components:
        for iface, i, req in _all_interfaces(c):
            if _spelled_right(iface):
                continue
            right = TYPE_FOLDERS[iface.kind]
            package, folder, name = iface.written.split("/")
            yield Problem(
                _where(c, i, req, iface),
                f"{iface.kind} '{iface.label}' of {c.name} has type {iface.written}: "
                f"'{folder}' is for {_KIND_OF_FOLDER[folder]}'s type, not "
                f"{'an' if iface.kind is InterfaceKind.ACTION else 'a'} {iface.kind}'s",
                f"write {package}/{right}/{name} (or {package}/{name}), or declare it as "
                f"{_KIND_OF_FOLDER[folder]}",
                code="type-kind-mismatch",
            )


_KIND_OF_FOLDER = {"msg": "a topic", "srv": "a service", "action": "an action"}


def _conflicts(components: Sequence[Component]) -> Iterator[Problem]:
    types: dict[
        tuple[InterfaceKind, str], tuple[Interface, str, Component, int, Requirement | None]
    ]
    types = {}
    kinds: dict[str, tuple[InterfaceKind, str]] = {}
    for c in components:
        for iface, i, req in _all_interfaces(c):
            key = (iface.kind, iface.label)
            first = types.get(key)
            if first is None:
                types[key] = (iface, c.name, c, i, req)
            elif first[0].type != iface.type:  # canonical keys: pkg/msg/X equals pkg/X
                same = first[1] == c.name
                yield Problem(
                    _where(c, i, req, iface),
                    f"{iface.kind} '{iface.label}' has type {iface.written} in {c.name} but "
                    f"{first[0].written} in {first[1]} ({_where(*first[2:], first[0])})",
                    "one component cannot use one label with two message classes; rename one"
                    if same
                    else "allowed for alternatives (raw and compressed images): no "
                    "configuration chooses providers of both; rename one if they are one thing",
                    code="type-conflict",
                    severity=Severity.ERROR if same else Severity.WARNING,
                )
            other = kinds.get(iface.label)
            if other is None:
                kinds[iface.label] = (iface.kind, c.name)
            elif other[0] != iface.kind:
                yield Problem(
                    _where(c, i, req, iface),
                    f"'{iface.label}' is a {iface.kind} in {c.name} but a {other[0]} in {other[1]}",
                    "use different labels for topics, services and actions",
                    code="kind-conflict",
                    severity=Severity.WARNING,
                )


def _unmet(components: Sequence[Component], provided: set[Interface]) -> Iterator[Problem]:
    for c in components:
        for i, req in enumerate(c.requires):
            if not provided.isdisjoint(req.options):
                continue
            verb = _VERBS[req.options[0].kind]
            yield Problem(
                _where(c, i, req),
                f"{c.name} {verb} {req}, which no component in the library provides",
                "add a component that provides it, or fix the label or type",
                code="unmet-requirement",
            )


_VERBS = {
    InterfaceKind.TOPIC: "subscribes to",
    InterfaceKind.SERVICE: "calls",
    InterfaceKind.ACTION: "sends goals to",
}
