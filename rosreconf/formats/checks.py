"""Check a loaded library L and configuration library C against the paper's rules.

Structure (keys, types, name syntax) is the JSON Schema's job in ``loader``; this module
checks what needs the whole picture: names that must refer to something, interfaces that
must agree across components, requirements that some component must be able to meet (the
condition of Lemma 4), and roles that some component must be able to fill. Every problem
names the exact value and says how to fix it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator, Sequence

from rosreconf.errors import Problem, Severity
from rosreconf.formats import contextchecks, interfacechecks, qoschecks, simchecks
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Interface,
    InteroperabilitySchema,
    Span,
)


def check(
    libraries: Sequence[ComponentLibrary],
    schemas: Sequence[InteroperabilitySchema],
    *,
    library_complete: bool = True,
) -> list[Problem]:
    """Return every semantic problem of the library files and schema files, sorted.

    When a library file could not be loaded (``library_complete`` false), the schemas'
    checks that need the whole library are skipped: they would only repeat the broken file's
    problem as dozens of false ones. Each check is first decided on ``_Index``; the
    components are walked one by one only to report what it found.
    """
    problems: list[Problem] = []
    components = [c for lib in libraries for c in lib.components]
    index = _Index(components)
    problems.extend(_names(components, index))
    problems.extend(p for c in index.dynamic for p in simchecks.component_problems(c))
    if components:
        problems.extend(_couplings(index))
        problems.extend(interfacechecks.index_problems(components, index.interfaces))
        problems.extend(_launch_args(index.launched))
        problems.extend(contextchecks.context_problems(libraries, components))
    problems.extend(_schema_names(schemas))
    known = index if library_complete else _Index([])
    for schema in schemas:
        problems.extend(_schema(schema, known))
        problems.extend(simchecks.schema_problems(schema))
    if components and schemas and library_complete:
        problems.extend(_usage(components, schemas, index))
        if index.has_qos:  # a library without qos: is not checked
            problems.extend(qoschecks.qos_problems(components, schemas))
    return sorted(problems)


class _Index:
    """What the checks look up in the library, gathered in one walk over its components.

    A thousand-role library has 10,000 components spread over memory: each separate walk
    over them costs more than what it tests, so one walk collects what every check needs,
    and a clean library's checks are decided on these (small) sets.

    Attributes:
        names, known: the components' names, in file order and as a set.
        named_schemas: the schemas some component names (``schemas:``).
        coupled, launched, dynamic: the components with ``needs`` or ``excludes``, with
            ``ros``, with dynamics.
        interfaces: the distinct interfaces they provide and require.
    """

    def __init__(self, components: Sequence[Component]) -> None:
        self.components = components
        self.names: list[str] = []
        self.labels: set[str] = set()
        self.named_schemas: set[str] = set()
        self.coupled: list[Component] = []
        self.launched: list[Component] = []
        self.dynamic: list[Component] = []
        self.has_qos = False
        provided: list[frozenset[Interface]] = []
        options: list[Interface] = []
        for c in components:
            self.names.append(c.name)
            self.labels.add(c.abstraction)
            provided.append(c.provides)
            for r in c.requires:
                options += r.options
            if c.needs or c.excludes:
                self.coupled.append(c)
            if c.launch is not None:
                self.launched.append(c)
            if c.dynamics is not None:
                self.dynamic.append(c)
            if c.schemas:
                self.named_schemas |= c.schemas
            if c.qos:
                self.has_qos = True
        self.known = set(self.names)
        self.interfaces = interfacechecks.InterfaceIndex(provided, options)
        self.provided_labels = {i.label for i in self.interfaces.provided}
        self._by_name: dict[str, Component] | None = None

    @property
    def by_name(self) -> dict[str, Component]:
        """Return the components by name (the last of a repeated name), made when first read."""
        if self._by_name is None:
            self._by_name = dict(zip(self.names, self.components, strict=True))
        return self._by_name


def _names(components: Sequence[Component], index: _Index) -> Iterator[Problem]:
    if _unique_names(index):
        return
    seen: dict[str, Component] = {}
    folded: dict[str, Component] = {}
    for c in components:
        if c.name in seen:
            first = seen[c.name]
            yield Problem(
                c.at("name"),
                f"duplicate component name '{c.name}' (first defined at {first.at('name')})",
                "give every component a unique name",
                code="duplicate-component",
            )
            continue
        other = folded.get(c.name.lower())
        if other is not None:
            yield Problem(
                c.at("name"),
                f"component names '{other.name}' and '{c.name}' differ only in letter case",
                "rename one: PDDL, which rosreconf plans with, does not distinguish case",
                code="case-collision",
            )
        seen[c.name] = c
        folded[c.name.lower()] = c


def _unique_names(index: _Index) -> bool:
    """Tell whether no name is repeated, not even in another letter case (``_names``'s case)."""
    return len(index.known) == len(index.names) == len({n.lower() for n in index.known})


def _couplings(index: _Index) -> Iterator[Problem]:
    for c in index.coupled:  # most components have no needs or excludes
        for key, names in (("needs", c.needs), ("excludes", c.excludes)):
            for name in sorted(names):
                if name == c.name:
                    yield Problem(
                        c.at(f"{key}.{name}"),
                        f"{c.name} {key} itself",
                        f"remove '{name}' from {key}",
                        code="self-coupling",
                    )
                elif name not in index.known:
                    yield Problem(
                        c.at(f"{key}.{name}"),
                        f"{c.name} {key} '{name}', which is not a component of the library",
                        "name a component defined in a library file, or remove it",
                        code="unknown-component",
                    )
        for name in sorted(c.needs & c.excludes):
            yield Problem(
                c.at(f"excludes.{name}"),
                f"{c.name} both needs and excludes '{name}'",
                "keep it in one list only",
                code="contradictory-coupling",
            )


def _launch_args(components: Sequence[Component]) -> Iterator[Problem]:
    """Refuse ``ros.args`` holding a roslaunch substitution (``$(find pkg)``, ``$(env X)``).

    rosreconf writes args into launch files verbatim, where roslaunch would evaluate the
    substitution: a library value must mean what it says, not run a lookup at launch time.
    """
    for c in components:
        if c.launch is None:
            continue
        for i, arg in enumerate(c.launch.args):
            if "$(" in arg:
                yield Problem(
                    c.at(f"ros.args.{i}"),
                    f"ros.args of {c.name} holds the roslaunch substitution {arg!r}",
                    "write the value itself; rosreconf does not evaluate $(...)",
                    code="launch-substitution",
                )


def _schema_names(schemas: Sequence[InteroperabilitySchema]) -> Iterator[Problem]:
    seen: dict[str, InteroperabilitySchema] = {}
    for s in schemas:
        if s.name in seen:
            yield Problem(
                s.at("name"),
                f"duplicate schema name '{s.name}' (first defined at {seen[s.name].at('name')})",
                "give every interoperability schema a unique name",
                code="duplicate-schema",
            )
        seen.setdefault(s.name, s)


def _schema(s: InteroperabilitySchema, index: _Index) -> Iterator[Problem]:
    components = index.components
    labels = index.labels
    roles: dict[str, Span] = {}
    for role in s.graph.roles:
        if role.name in roles:
            yield Problem(
                role.span,
                f"duplicate role '{role.name}' (first at line {roles[role.name].line})",
                "give every role of a schema a unique name",
                code="duplicate-role",
            )
            continue
        roles[role.name] = role.span
        if components and role.abstraction not in labels:
            yield Problem(
                s.at(f"role.{role.name}.abstraction"),
                f"role '{role.name}' needs abstraction '{role.abstraction}', which no "
                "component in the library carries",
                _closest("abstraction labels in the library", role.abstraction, labels),
                code="unknown-abstraction",
            )
    provided = index.provided_labels
    for e in s.graph.edges:
        for end in (e.consumer, e.provider):
            if end not in roles:
                yield Problem(
                    e.span,
                    f"edge names role '{end}', which schema '{s.name}' does not define",
                    _closest("roles", end, set(roles)),
                    code="unknown-role",
                )
        if e.consumer == e.provider:
            yield Problem(
                e.span,
                f"edge from role '{e.consumer}' to itself",
                "a role cannot use what it provides itself; remove the edge",
                code="self-edge",
            )
        for label in sorted(e.interfaces):
            if components and label not in provided:
                yield Problem(
                    e.span,
                    f"edge {e.consumer} -> {e.provider} allows interface '{label}', which no "
                    "component provides",
                    "fix the label, or remove it from interfaces",
                    code="unknown-interface",
                )
    yield from _nominal(s, roles, index)


def _nominal(s: InteroperabilitySchema, roles: dict[str, Span], index: _Index) -> Iterator[Problem]:
    if not s.nominal:
        return
    by_name = index.by_name
    needs: dict[str, str] = {}  # each role's label, as graph.role() (a scan: n^2 here) gives
    for r in s.graph.roles:
        needs.setdefault(r.name, r.abstraction)
    for role, comp in s.nominal.items():
        span = s.at(f"nominal.{role}")
        if role not in roles:
            yield Problem(
                span,
                f"nominal configuration names role '{role}', which the schema does not define",
                _closest("roles", role, set(roles)),
                code="unknown-role",
            )
        elif by_name and comp not in by_name:
            yield Problem(
                span,
                f"nominal configuration puts '{comp}' in role '{role}', but the library has no "
                "such component",
                _closest("components", comp, set(by_name)),
                code="unknown-component",
            )
        elif by_name and by_name[comp].abstraction != needs[role]:
            yield Problem(
                span,
                f"nominal configuration puts {comp} ({by_name[comp].abstraction}) in role "
                f"'{role}', which needs {needs[role]}",
                "choose a component with the role's abstraction label",
                code="wrong-abstraction",
            )
    optional = {r.name for r in s.graph.roles if r.optional}  # these may stay empty
    for role in roles:
        if role not in s.nominal and role not in optional:
            yield Problem(
                s.span,
                f"nominal configuration of '{s.name}' leaves role '{role}' empty",
                "fill every role that is not optional, or remove 'nominal'",
                code="incomplete-nominal",
            )


def _usage(
    components: Sequence[Component], schemas: Sequence[InteroperabilitySchema], index: _Index
) -> Iterator[Problem]:
    names = {s.name for s in schemas}
    used = {r.abstraction for s in schemas for r in s.graph.roles}
    if _all_used(index, names, used):
        return
    for c in components:
        for name in sorted(c.schemas - names):
            yield Problem(
                c.at(f"schemas.{name}"),
                f"{c.name} may serve in schema '{name}', which none of the given files defines",
                _closest("schemas", name, names),
                code="unknown-schema",
                severity=Severity.WARNING,
            )
        if c.abstraction not in used:
            yield Problem(
                c.at("abstraction"),
                f"{c.name} has abstraction '{c.abstraction}', which no role of any schema uses",
                "it can never be chosen; fix the label or add a role",
                code="unused-abstraction",
                severity=Severity.WARNING,
            )


def _all_used(index: _Index, names: set[str], used: set[str]) -> bool:
    """Tell whether every schema a component names exists and every abstraction is used."""
    return index.named_schemas <= names and index.labels <= used


def _closest(what: str, name: str, choices: set[str]) -> str:
    close = difflib.get_close_matches(name, sorted(choices), n=1)
    if close:
        return f"did you mean '{close[0]}'?"
    listed = ", ".join(sorted(choices)[:8]) or "none"
    return f"known {what}: {listed}"
