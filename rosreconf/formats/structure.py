"""Check a YAML document's structure against the shipped JSON Schema, with positions.

jsonschema-rs does the validating (the JSON Schema files editors use, in ``rosreconf/data``);
this module turns each error into a ``Problem`` at the exact key or value (its instance path
looked up in the document's positions, ``positions.Positions``), saying what is wrong in
words and how to fix it (``x-hint`` entries in the JSON Schemas, "did you mean", "quote it").
"""

from __future__ import annotations

import difflib
import enum
import json
import math
from collections.abc import Callable
from functools import cache
from typing import Any

from rosreconf.errors import Problem
from rosreconf.formats import nodes
from rosreconf.formats.positions import MAPPING, PLAIN_SCALAR, SEQUENCE, Place, Positions
from rosreconf.model import Span
from rosreconf.resources import Bundle, bundled


class DocumentKind(enum.StrEnum):
    """The two file formats, named by their ``format:`` field."""

    LIBRARY = "rosreconf/component-library"
    SCHEMA = "rosreconf/interoperability-schema"


@cache
def json_schema(kind: DocumentKind) -> dict[str, Any]:
    """Return the shipped JSON Schema of ``kind`` (the same file editors use)."""
    name = kind.value.removeprefix("rosreconf/") + ".schema.json"  # e.g. component-library
    text = bundled(Bundle.DATA, name).read_text(encoding="utf-8")
    schema: dict[str, Any] = json.loads(text)
    return schema


def kind_of(plain: nodes.Plain) -> DocumentKind | None:
    """Return the format a document's plain data names exactly, else None (``format_problem``)."""
    fmt = plain.get("format") if isinstance(plain, dict) else None
    return DocumentKind(fmt) if isinstance(fmt, str) and fmt in _KINDS else None


_KINDS = frozenset(DocumentKind)


def format_problem(tree: Positions | None, plain: nodes.Plain, name: str) -> Problem:
    """Return what is wrong with the format of a document ``kind_of`` found none in."""
    known = ", ".join(k.value for k in DocumentKind)
    if not isinstance(plain, dict):
        return Problem(
            tree.span(tree.root) if tree is not None else Span(name, 1, 1),
            "expected a mapping with a 'format' key at the top of the file",
            f"start the file with 'format: <kind>' where kind is one of {known}",
            code="not-a-document",
        )
    if "format" not in plain:
        return Problem(
            tree.span(tree.root) if tree is not None else Span(name, 1, 1),
            "missing 'format' key",
            f"add 'format: <kind>' where kind is one of {known}",
            code="missing-format",
        )
    assert tree is not None, "a mapping read has its positions"
    fmt = tree.lookup(["format"])
    return Problem(
        tree.span(fmt),
        f"unknown format '{tree.text(fmt)}'",
        f"use one of {known}",
        "unknown-format",
    )


@cache
def validator(kind: DocumentKind) -> Any:
    """Return jsonschema-rs's validator of ``kind``'s JSON Schema (built once per process)."""
    import jsonschema_rs  # imported only by commands that read files

    return jsonschema_rs.Draft202012Validator(json_schema(kind))


def structure_problems(tree: Positions, kind: DocumentKind, plain: nodes.Plain) -> list[Problem]:
    """Return every structural problem of ``plain``, each placed by ``tree``.

    Raises:
        ValueError: a mapping key of ``plain`` is not a string (jsonschema-rs reads none).
    """
    errors = list(validator(kind).iter_errors(plain))
    if not errors:
        return []
    root = json_schema(kind)
    found = [_Error(e, root).as_number(plain) for e in errors]
    ordered = sorted((f for f in found if f is not None), key=_Error.path_key)
    return [_problem_of(f, tree) for f in ordered]


class _Error:
    """One jsonschema-rs error with what the messages need: keyword, subschema, branches.

    The message is jsonschema-rs's own, except for the keywords ``_problem_of`` words itself.
    """

    def __init__(self, error: Any, root: dict[str, Any], branch: int = 0) -> None:
        self.branch = branch  # which branch of the parent's oneOf or anyOf
        self.path: list[str | int] = list(error.instance_path)
        self.instance = error.instance
        self.message: str = error.message
        self.validator: str = str(error.schema_path[-1]) if error.schema_path else ""
        schema: Any = root
        for step in list(error.schema_path)[:-1]:
            schema = schema[step]
        self.schema: dict[str, Any] = schema if isinstance(schema, dict) else {}
        self.validator_value = self.schema.get(self.validator)
        self.many_valid = type(error.kind).__name__ == "OneOfMultipleValid"
        branches: list[Any] = getattr(error.kind, "context", None) or []
        self.context: list[_Error] = []
        if not self.many_valid:
            for index, errors in enumerate(branches):
                self.context += [_Error(e, root, index) for e in errors]

    def path_key(self) -> list[str]:
        """Order errors by where they are (the order problems are reported in)."""
        return list(map(str, self.path))

    def as_number(self, plain: nodes.Plain) -> _Error | None:
        """Return this error as JSON Schema judges a YAML ``.inf`` or ``.nan``: a number.

        JSON has no such numbers (jsonschema-rs reads them as null); rosreconf compares them
        as Python does, and ``values`` and ``simchecks`` say they are not finite. So a type
        error on one becomes the range error it would break, or nothing.
        """
        if self.context:
            branches: dict[int, list[_Error | None]] = {}
            for e in self.context:
                branches.setdefault(e.branch, []).append(e.as_number(plain))
            if any(all(e is None for e in found) for found in branches.values()):
                return None
            return self
        if self.validator != "type" or self.instance is not None:
            return self
        instance: Any = plain
        for step in self.path:  # the value itself: jsonschema-rs gives it as None
            instance = instance[step]
        if not isinstance(instance, float) or math.isfinite(instance):
            return self
        self.instance = instance
        want = self.validator_value
        wanted = want if isinstance(want, list) else [want]
        if "number" not in wanted:
            return self
        for keyword, broken in _RANGES.items():
            limit = self.schema.get(keyword)
            if isinstance(limit, int | float) and broken(instance, limit):
                self.validator, self.validator_value = keyword, limit
                return self
        return None


_RANGES: dict[str, Callable[[float, float], bool]] = {
    "minimum": lambda x, limit: x < limit,
    "maximum": lambda x, limit: x > limit,
    "exclusiveMinimum": lambda x, limit: x <= limit,
    "exclusiveMaximum": lambda x, limit: x >= limit,
}
"""How a number breaks each range keyword (false for NaN, as in every comparison)."""


def _blamed(alternative: _Error) -> tuple[_Error, bool]:
    """Return the error to report for a value that fits none of its alternatives (oneOf, anyOf).

    The alternative blamed is the one the value is closest to in shape: the fewest errors at
    the value itself (a missing or unknown key, a wrong type), then the first written. A
    requirement ``{service: s, type: r?obot/T}`` fits the interface, not ``any_of``: its
    problem is its type's, at the type. The first error of that alternative is reported,
    and True when it lies inside the value (the value's shape fits that alternative).
    """
    by_branch: dict[int, list[_Error]] = {}
    for e in alternative.context:
        by_branch.setdefault(e.branch, []).append(e)

    def at_value(errors: list[_Error]) -> int:
        return sum(len(e.path) == len(alternative.path) for e in errors)

    branch = min(by_branch, key=lambda b: (at_value(by_branch[b]), b))
    errors = sorted(by_branch[branch], key=_Error.path_key)  # at the value itself first
    return errors[0], at_value(by_branch[branch]) == 0


def _problem_of(error: _Error, tree: Positions) -> Problem:
    if error.validator in ("oneOf", "anyOf") and error.context:
        blamed, fits = _blamed(error)
        problem = _problem_of(blamed, tree)
        if fits:  # a value inside the alternative it fits: its own words, as anywhere else
            return problem
        hint = problem.hint or str(error.schema.get("x-hint", ""))  # else: the alternatives
        return Problem(problem.span, problem.message, hint, problem.code)
    path = error.path
    node = tree.lookup(path)
    span = tree.span(node)
    where = f"'{nodes.path_text(path)}'" if path else "the document"
    schema = error.schema
    hint = str(schema.get("x-hint", ""))
    validator = error.validator
    if validator == "required":
        missing = str(error.message).split('"')[1] if '"' in error.message else "?"
        return Problem(span, f"{where} is missing required key '{missing}'", code="missing-key")
    if validator == "additionalProperties" and isinstance(error.instance, dict):
        allowed = sorted(schema.get("properties", {}))
        extra = sorted(set(error.instance) - set(allowed))
        name = extra[0] if extra else "?"
        kspan = tree.key_span([*path, name]) or span
        close = difflib.get_close_matches(name, allowed, n=1)
        fix = f"did you mean '{close[0]}'?" if close else f"allowed keys: {', '.join(allowed)}"
        return Problem(kspan, f"unknown key '{name}' in {where}", fix, code="unknown-key")
    if validator == "type":
        got = _written(tree, node)
        want = error.validator_value
        wanted = " or ".join(want) if isinstance(want, list) else str(want)
        fix = hint
        if "string" in wanted and tree.kind(node) == PLAIN_SCALAR:
            fix = f"quote it ('{tree.text(node)}') if you mean the text"
        return Problem(span, f"{where} must be a {wanted}, not {got}", fix, code="wrong-type")
    if validator == "pattern":
        return Problem(span, f"{where} {_written(tree, node)} is not valid", hint, code="bad-name")
    limit, written = error.validator_value, _written(tree, node)
    if validator == "const":
        return Problem(
            span, f"{where} must be {json.dumps(limit)}, not {written}", hint, "wrong-value"
        )
    if validator in ("minimum", "maximum"):
        message, fix = f"{where} is {written}, which is out of range", f"{validator} is {limit}"
        return Problem(span, message, fix, "out-of-range")
    if validator == "minItems":
        return Problem(span, f"{where} needs at least {limit} item(s)", code="too-few")
    if validator == "uniqueItems":
        return Problem(span, f"{where} lists the same item twice", code="duplicate-item")
    if validator == "oneOf":  # with no failing branch to blame: several branches matched
        return Problem(span, f"{where} gives more than one of its alternatives", hint, "one-of")
    return Problem(span, f"{where}: {error.message}", hint, code="invalid")


def _written(tree: Positions, node: Place) -> str:
    kind = tree.kind(node)
    if kind == MAPPING:
        return "a mapping"
    if kind == SEQUENCE:
        return "a list"
    text = tree.text(node)
    if not text:
        return "empty value"
    what = type(node.value).__name__.replace("NoneType", "null").replace("str", "text")
    what = {"int": "number", "float": "number", "bool": "boolean"}.get(what, what)
    return f"{what} {text!r}"
