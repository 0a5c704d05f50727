"""Check a library's context declarations and its components' ``when`` conditions.

What the JSON Schema cannot see: a name declared twice, a condition on a name no library
file declares, ``at_least`` above ``at_most``, a field its message type does not have (for
the types ``messages.KNOWN_FIELDS`` knows), and a condition that compares a variable as
something other than it holds (a bound on a string, ``equals: true`` on a number, or one
variable bounded in one component and compared for equality in another). ``checks.check``
runs these with the other semantic checks.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator, Sequence

from rosreconf.errors import Problem
from rosreconf.formats.messages import KNOWN_FIELDS, FieldKind
from rosreconf.model import Component, ComponentLibrary, type_key
from rosreconf.model.context import Condition, ContextVariable, show


def context_problems(
    libraries: Sequence[ComponentLibrary], components: Sequence[Component]
) -> Iterator[Problem]:
    """Yield every problem of the context declarations and of the conditions on them."""
    declared: dict[str, ContextVariable] = {}
    for v in (v for lib in libraries for v in lib.context):
        first = declared.get(v.name)
        if first is not None:
            yield Problem(
                v.span,
                f"context '{v.name}' is declared twice (first at {first.span})",
                "give every context variable a unique name, in all library files",
                code="duplicate-context",
            )
            continue
        declared[v.name] = v
        yield from _field(v)
    kinds: dict[str, tuple[FieldKind, Component]] = {}
    for c in components:
        for w in c.when:
            var = declared.get(w.name)
            if var is None:
                yield _unknown(c, w, sorted(declared))
                continue
            yield from _condition(c, w, var, kinds)


def _unknown(c: Component, w: Condition, names: list[str]) -> Problem:
    close = difflib.get_close_matches(w.name, names, n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    return Problem(
        w.span if w.span.line else c.at(f"when.{w.name}"),
        f"{c.name} has a condition on '{w.name}', which is not a context of the library",
        f"{hint}declare it under context: ({{name, topic, type, field}}), or fix the name",
        code="unknown-context",
    )


def _field(v: ContextVariable) -> Iterator[Problem]:
    fields = KNOWN_FIELDS.get(type_key(v.type))
    if fields is None or v.field in fields:
        return
    close = difflib.get_close_matches(v.field, list(fields), n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    yield Problem(
        v.field_span,
        f"context '{v.name}': {v.type} has no field '{v.field}'",
        f"{hint}its fields are {', '.join(sorted(fields))}",
        code="unknown-context-field",
    )


def _kind(w: Condition) -> FieldKind:
    if w.numeric:
        return "number"
    return "boolean" if isinstance(w.equals, bool) else "string"


def _condition(
    c: Component,
    w: Condition,
    var: ContextVariable,
    kinds: dict[str, tuple[FieldKind, Component]],
) -> Iterator[Problem]:
    if w.at_least is not None and w.at_most is not None and w.at_least > w.at_most:
        yield Problem(
            c.at(f"when.{w.name}.at_least"),
            f"{c.name}'s condition on {w.name} can never hold: at_least "
            f"{show(w.at_least)} is above at_most {show(w.at_most)}",
            "swap the bounds, or fix one",
            code="empty-condition",
        )
    kind = _kind(w)
    holds = KNOWN_FIELDS.get(type_key(var.type), {}).get(var.field)
    if holds is not None and holds != kind:
        yield Problem(
            c.at(f"when.{w.name}"),
            f"{c.name} compares {w.name} as a {kind}, but {var.type}'s field "
            f"'{var.field}' holds a {holds}",
            "bound a number with at_least/at_most; compare a boolean or string with equals",
            code="context-kind-mismatch",
        )
        return
    first = kinds.setdefault(w.name, (kind, c))
    if first[0] != kind:
        yield Problem(
            c.at(f"when.{w.name}"),
            f"{c.name} compares {w.name} as a {kind}, but {first[1].name} as a {first[0]}",
            "compare one context variable one way in every component",
            code="context-kind-mismatch",
        )
