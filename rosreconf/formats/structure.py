"""Check a YAML document's structure against the shipped JSON Schema, with positions.

``jsonschema`` does the validating (the same JSON Schema files editors use, shipped in
``rosreconf/data``); this module decides which format a document claims to be (its
``format:`` field) and turns each ``ValidationError`` into a ``Problem`` that names the exact
key or value (``file:line:column``), says what is wrong in words, and how to fix it
(``x-hint`` entries in the JSON Schemas, "did you mean" for unknown keys, "quote it" for
names YAML read as numbers).

Valid files are the common case and need no list of errors, so a document is first checked
with ``fastjsonschema`` (the same JSON Schema compiled to Python code, several times faster
on a thousand-role library); only a document it rejects goes through ``jsonschema``, which
reports every error with its path. Tests hold the two to the same verdicts.
"""

from __future__ import annotations

import difflib
import enum
import hashlib
import importlib
import json
import re
from collections.abc import Callable, Iterator, Sequence
from functools import cache
from typing import TYPE_CHECKING, Any

import fastjsonschema

from rosreconf.errors import Problem
from rosreconf.formats import yamlsource as ys
from rosreconf.model import Span
from rosreconf.resources import Bundle, bundled

if TYPE_CHECKING:  # jsonschema is imported only for a document fastjsonschema rejects
    import jsonschema.exceptions


class DocumentKind(enum.StrEnum):
    """The two file formats, named by their ``format:`` field."""

    LIBRARY = "rosreconf/component-library"
    SCHEMA = "rosreconf/interoperability-schema"


JSON_SCHEMA_FILES = {
    DocumentKind.LIBRARY: "component-library.schema.json",
    DocumentKind.SCHEMA: "interoperability-schema.schema.json",
}


@cache
def json_schema(kind: DocumentKind) -> dict[str, Any]:
    """Return the shipped JSON Schema of ``kind`` (the same file editors use)."""
    text = bundled(Bundle.DATA, JSON_SCHEMA_FILES[kind]).read_text(encoding="utf-8")
    schema: dict[str, Any] = json.loads(text)
    return schema


# --- the format field -------------------------------------------------------------------


def kind_of(tree: ys.YNode | None, name: str) -> tuple[DocumentKind | None, list[Problem]]:
    known = ", ".join(k.value for k in DocumentKind)
    if not isinstance(tree, ys.YMapping):
        span = tree.span if tree is not None else Span(name, 1, 1)
        return None, [
            Problem(
                span,
                "expected a mapping with a 'format' key at the top of the file",
                f"start the file with 'format: <kind>' where kind is one of {known}",
                code="not-a-document",
            )
        ]
    fmt = tree.items.get("format")
    if fmt is None:
        return None, [
            Problem(
                tree.span,
                "missing 'format' key",
                f"add 'format: <kind>' where kind is one of {known}",
                code="missing-format",
            )
        ]
    raw = fmt.raw if isinstance(fmt, ys.YScalar) else ""
    for kind in DocumentKind:
        if raw == kind.value:
            return kind, []
    return None, [
        Problem(
            fmt.span,
            f"unknown format '{raw}'",
            f"use one of {known}",
            code="unknown-format",
        )
    ]


def kind_of_plain(plain: ys.Plain) -> DocumentKind | None:
    """Return the kind a document's plain data claims, or None for ``kind_of`` to report.

    The same answer as ``kind_of`` whenever that finds no problem (a text ``format`` is
    its own raw text), without a positioned tree; None asks for the tree, to say where the
    problem is.
    """
    fmt = plain.get("format") if isinstance(plain, dict) else None
    if type(fmt) is str:
        for kind in DocumentKind:
            if fmt == kind.value:
                return kind
    return None


# --- structure: JSON Schema, with friendly positioned messages ---------------------------


@cache
def fast_validator(kind: DocumentKind) -> Callable[[Any], Any]:
    """Return ``kind``'s JSON Schema compiled by fastjsonschema (raises on invalid data).

    Writing and compiling that code costs 0.1 CPU s in every process (more than reading
    and checking the bundled example), so the package ships it as modules written by
    ``scripts/fast_validators.py`` (``FAST_MODULES``); a shipped module whose JSON Schema
    or fastjsonschema version is not the one in use is ignored and the code written here
    instead, so a stale module can cost time but never change a verdict.
    """
    module = importlib.import_module(f"rosreconf.formats.{FAST_MODULES[kind]}")
    if getattr(module, "SOURCE", None) == fast_validator_source(kind):
        shipped: Callable[[Any], Any] = module.VALIDATE
        return shipped
    code = fast_validator_code(kind)
    namespace: dict[str, Any] = {}
    exec(compile(code, f"<fastjsonschema: {kind.value}>", "exec"), namespace)
    validate: Callable[[Any], Any] = namespace[_entry_point(code)]
    return validate


FAST_MODULES = {
    DocumentKind.LIBRARY: "fastschema_library",
    DocumentKind.SCHEMA: "fastschema_schema",
}
"""The modules in ``rosreconf.formats`` holding ``fast_validator_module``'s code."""


def fast_validator_source(kind: DocumentKind) -> str:
    """Return what ``kind``'s validator code is written from: the Schema's text and tools.

    A digest of the JSON Schema as compiled (``without_one_of``'s), fastjsonschema's
    version, this module's trimming patterns and the ``$defs`` it remembers; a shipped
    module records it as ``SOURCE``.
    """
    compiled = json.dumps(without_one_of(json_schema(kind)), sort_keys=True)
    digest = hashlib.sha256(compiled.encode("utf-8"))
    digest.update(fastjsonschema.VERSION.encode("ascii"))
    digest.update(_ITEM_NAME.pattern.encode("utf-8") + _DEFINITION.pattern.encode("utf-8"))
    digest.update(" ".join(REMEMBERED).encode("utf-8"))
    return digest.hexdigest()


def fast_validator_module(kind: DocumentKind) -> str:
    """Return the text of ``kind``'s shipped validator module (see ``fast_validator``)."""
    code = fast_validator_code(kind)
    return (
        f'"""fastjsonschema\'s code for {JSON_SCHEMA_FILES[kind]}: written by\n'
        f"scripts/fast_validators.py, do not edit (see structure.fast_validator).\n"
        f'"""\n\n# ruff: noqa\n# fmt: off\n# mypy: ignore-errors\n'
        f"SOURCE = {fast_validator_source(kind)!r}\n"
        f"{code.rstrip()}\n\n\nVALIDATE = {_entry_point(code)}\n"
    )


def _entry_point(code: str) -> str:
    """Return the name of the validation function fastjsonschema's ``code`` defines first."""
    entry = re.search(r"^def (\w+)\(", code, re.MULTILINE)
    assert entry is not None, "fastjsonschema wrote no validation function"
    return entry.group(1)


def fast_validator_code(kind: DocumentKind) -> str:
    """Return the Python code of ``fast_validator``, trimmed to what a verdict needs.

    The code fastjsonschema writes (``compile_to_code``, its documented way to keep a
    validator as a module) names each list item for its messages before validating it, as
    ``"...[{x}]".format(**locals())``: a dict of every local variable per item, about a third
    of the check on a thousand-role library. Only the verdict of this validator is used
    (jsonschema words the messages), so each item is given its parent's name instead.

    For the same reason every ``raise`` loses its ``definition=`` argument: a literal copy
    of the JSON Schema's part it checks (two thirds of the code), which Python had to compile
    (``detailed_exceptions=False``, made for this, fails on a ``const`` in fastjsonschema
    2.22).

    Last, the ``REMEMBERED`` validators are wrapped to check each distinct valid content
    once (``rosreconf.formats.schemamemo``): the code calls them by their global names.
    """
    code = fastjsonschema.compile_to_code(without_one_of(json_schema(kind)))
    code = _ITEM_NAME.sub('(name_prefix or "data")', code)
    code = _DEFINITION.sub(r"\1None\2", code)
    remembered = [f"validate____defs_{d}" for d in REMEMBERED]
    remembered = [name for name in remembered if f"\ndef {name}(" in code]
    if remembered:
        code += "\n\nfrom rosreconf.formats.schemamemo import remember_valid\n"
        code += "".join(f"{name} = remember_valid({name})\n" for name in remembered)
    return code


REMEMBERED = ("interface", "requirement")
"""The ``$defs`` whose valid contents the fast validator checks once (``schemamemo``): a
large library repeats a few thousand distinct ones tens of thousands of times."""


_ITEM_NAME = re.compile(r'\(name_prefix or "data"\) \+ "[^"\n]*"\.format\(\*\*locals\(\)\)')
"""How fastjsonschema's code names a list item for a message (see ``fast_validator``)."""

_DEFINITION = re.compile(r"(, definition=).*(, rule='\w+'\)$)", re.MULTILINE)
"""The literal JSON Schema part a ``raise`` of fastjsonschema's code carries (its last
arguments on its one line; see ``fast_validator``)."""


EXCLUSIVE_ONE_OF = {
    "/$defs/requirement": "an interface has no 'any_of' key, an any_of object no other key",
    "/$defs/component/properties/ros/properties/parameters/additionalProperties": (
        "a scalar is not an object"
    ),
}
"""The ``oneOf``s whose branches no value can satisfy together, and why: ``anyOf`` says the
same there. fastjsonschema's ``oneOf`` tries every branch and builds an exception with its
message for each failing one (most of the structure check's time on a large library);
``anyOf`` stops at the first branch that holds."""


def without_one_of(schema: dict[str, Any]) -> dict[str, Any]:
    """Return a copy of the JSON Schema with the same verdicts and no ``oneOf`` on hot paths.

    Two kinds are rewritten: those listed in ``EXCLUSIVE_ONE_OF`` become ``anyOf``; and a
    ``oneOf`` of single required keys (``{required: [topic]}``, ``{required: [service]}``:
    exactly one of them) becomes their ``anyOf`` (at least one) with each key forbidding the
    others (``dependencies``: at most one). Only for the fast validator: jsonschema keeps the
    published Schema for its messages. Every other ``oneOf`` stays as it is;
    tests/test_fast_paths.py holds the two validators to the same verdicts.
    """
    fast: dict[str, Any] = json.loads(json.dumps(schema))
    for pointer in EXCLUSIVE_ONE_OF:
        node = _at(fast, pointer)
        if node is not None and "oneOf" in node:
            node["anyOf"] = node.pop("oneOf")
    stack: list[Any] = [fast]
    while stack:
        node = stack.pop()
        if isinstance(node, list):
            stack.extend(node)
            continue
        if not isinstance(node, dict):
            continue
        stack.extend(node.values())
        keys = _single_required_keys(node.get("oneOf"))
        if keys and "dependencies" not in node:
            node["anyOf"] = node.pop("oneOf")
            node["dependencies"] = {
                k: {"properties": {other: False for other in keys if other != k}} for k in keys
            }
    return fast


def _single_required_keys(branches: Any) -> list[str] | None:
    """Return the keys of a ``oneOf`` whose every branch is ``{required: [one key]}``."""
    if not isinstance(branches, list) or len(branches) < 2:
        return None
    keys = []
    for branch in branches:
        if not (isinstance(branch, dict) and list(branch) == ["required"]):
            return None
        required = branch["required"]
        if not (isinstance(required, list) and len(required) == 1):
            return None
        keys.append(str(required[0]))
    return keys if len(set(keys)) == len(keys) else None


def _at(schema: dict[str, Any], pointer: str) -> dict[str, Any] | None:
    """Return the sub-schema at a JSON pointer (``/a/b``), or None when it is not there."""
    node: Any = schema
    for step in pointer.strip("/").split("/"):
        node = node.get(step) if isinstance(node, dict) else None
    return node if isinstance(node, dict) else None


def structure_valid(kind: DocumentKind, plain: ys.Plain) -> bool:
    """Tell whether ``plain`` satisfies ``kind``'s JSON Schema (no tree needed to say yes).

    ``structure_problems`` (which needs the positioned tree, for positions) reports why
    when the answer is no.
    """
    try:
        fast_validator(kind)(plain)
    except fastjsonschema.JsonSchemaException:
        return False
    return True


def structure_problems(
    tree: ys.YNode, kind: DocumentKind, plain: ys.Plain | None = None
) -> Iterator[Problem]:
    """Yield every structural problem of ``tree`` against ``kind``'s JSON Schema.

    ``plain`` is the tree as plain data when the reader already built it (``parse_plain``).
    """
    if plain is None:
        plain = ys.to_plain(tree)
    if structure_valid(kind, plain):
        return
    # Invalid: jsonschema finds every error, with paths. Imported here: valid files (the
    # common case) never pay its import time.
    import jsonschema

    validator = jsonschema.Draft202012Validator(json_schema(kind))
    for error in sorted(validator.iter_errors(plain), key=lambda e: list(map(str, e.path))):
        yield _problem_of(error, tree)


def _problem_of(error: jsonschema.exceptions.ValidationError, tree: ys.YNode) -> Problem:
    if error.validator in ("oneOf", "anyOf") and error.context:
        hint = str(error.schema.get("x-hint", "")) if isinstance(error.schema, dict) else ""
        from jsonschema.exceptions import best_match

        best = best_match(error.context)
        problem = _problem_of(best, tree)
        return Problem(problem.span, problem.message, hint or problem.hint, problem.code)
    path = list(error.absolute_path)
    node = ys.lookup(tree, path)
    span = node.span if node is not None else tree.span
    where = _describe_path(path)
    schema = error.schema if isinstance(error.schema, dict) else {}
    hint = str(schema.get("x-hint", ""))
    validator = error.validator
    if validator == "required":
        missing = str(error.message).split("'")[1] if "'" in error.message else "?"
        return Problem(span, f"{where} is missing required key '{missing}'", code="missing-key")
    if validator == "additionalProperties" and isinstance(error.instance, dict):
        allowed = sorted(schema.get("properties", {}))
        extra = sorted(set(error.instance) - set(allowed))
        name = extra[0] if extra else "?"
        kspan = ys.key_span(tree, [*path, name]) or span
        close = difflib.get_close_matches(name, allowed, n=1)
        fix = f"did you mean '{close[0]}'?" if close else f"allowed keys: {', '.join(allowed)}"
        return Problem(kspan, f"unknown key '{name}' in {where}", fix, code="unknown-key")
    if validator == "type":
        got = _written(node)
        want = error.validator_value
        wanted = " or ".join(want) if isinstance(want, list) else str(want)
        fix = hint
        if "string" in wanted and isinstance(node, ys.YScalar) and node.plain:
            fix = f"quote it ('{node.raw}') if you mean the text"
        return Problem(span, f"{where} must be a {wanted}, not {got}", fix, code="wrong-type")
    if validator == "pattern":
        return Problem(span, f"{where} {_written(node)} is not valid", hint, code="bad-name")
    if validator == "const":
        return Problem(
            span,
            f"{where} must be {json.dumps(error.validator_value)}, not {_written(node)}",
            hint,
            code="wrong-value",
        )
    if validator in ("minimum", "maximum"):
        return Problem(
            span,
            f"{where} is {_written(node)}, which is out of range",
            f"{validator} is {error.validator_value}",
            code="out-of-range",
        )
    if validator == "minItems":
        return Problem(
            span,
            f"{where} needs at least {error.validator_value} item(s)",
            code="too-few",
        )
    if validator == "uniqueItems":
        return Problem(span, f"{where} lists the same item twice", code="duplicate-item")
    if validator == "oneOf":  # with no failing branch to blame: several branches matched
        return Problem(
            span, f"{where} gives more than one of its alternatives", hint, code="one-of"
        )
    return Problem(span, f"{where}: {error.message}", hint, code="invalid")


def _written(node: ys.YNode | None) -> str:
    if isinstance(node, ys.YScalar):
        kind = type(node.value).__name__.replace("NoneType", "null").replace("str", "text")
        kind = {"int": "number", "float": "number", "bool": "boolean"}.get(kind, kind)
        return f"{kind} {node.raw!r}" if node.raw else "empty value"
    if isinstance(node, ys.YMapping):
        return "a mapping"
    if isinstance(node, ys.YSequence):
        return "a list"
    return "nothing"


def _describe_path(path: Sequence[str | int]) -> str:
    if not path:
        return "the document"
    parts = []
    for step in path:
        parts.append(f"[{step}]" if isinstance(step, int) else f".{step}")
    return "'" + "".join(parts).lstrip(".") + "'"
