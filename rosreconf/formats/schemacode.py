"""Write a JSON Schema as Python code that gives only a verdict: valid or not.

A valid file is the common case and needs no error list, only a yes; ``jsonschema`` (which
words every message, with paths) runs only on a document this code rejects
(``structure.structure_problems``). General validator compilers (fastjsonschema) raise and
catch an exception per failing ``oneOf`` branch and copy every dict's keys into a set to
find the unknown ones; at 1000 roles x 10 candidates that was 0.16 CPU s of every load. The
code written here is plain ``if ...: return False`` statements over the data: one set
comparison for a mapping's keys, one compiled pattern per name, a ``$ref`` or a list's items
checked inline (any failure fails the document), and a function only for a ``oneOf`` or
``anyOf`` branch, whose failure is local.

Only the keywords the shipped JSON Schemas use are known; any other keyword, or a form of
one this module does not handle, raises ``Unsupported`` when the code is written (by
``scripts/fast_validators.py`` and the tests), never a wrong verdict when it runs. Every
check is as strict as jsonschema's or stricter (exact types: ``type(x) is str``), so a
disagreement can only send a valid document to jsonschema, costing time, never a verdict:
tests/test_fast_paths.py holds the two to the same verdicts.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

GENERATOR_VERSION = "1"
"""Part of a written module's digest (``structure.fast_validator_source``): bump it when the
code written here changes, so that a module written by an older generator is not used."""

REMEMBERED = 100_000
"""Most texts remembered per pattern as matching it (a long-lived ``watch`` process reads
its files again and again, and must not grow without bound)."""

ANNOTATIONS = frozenset({"$schema", "$id", "title", "description", "x-hint", "$comment"})
"""Keywords that only describe, and never change a verdict."""

EXACT = {
    "string": "type({v}) is str",
    "object": "type({v}) is dict",
    "array": "type({v}) is list",
    "boolean": "type({v}) is bool",
    "null": "{v} is None",
    "number": "type({v}) in _NUMBER",
    "integer": "(type({v}) is int or (type({v}) is float and {v}.is_integer()))",
}
"""A JSON type as an exact Python type test (as strict as jsonschema's, or stricter)."""

BROAD = {
    "string": "isinstance({v}, str)",
    "object": "isinstance({v}, dict)",
    "array": "isinstance({v}, list)",
}
"""jsonschema's own test of a type, for a keyword applying to it when the type is unknown:
as broad as jsonschema's, so that the keyword is never skipped where jsonschema applies it."""


class Unsupported(ValueError):
    """Raised when a JSON Schema uses a keyword or form this module cannot write as code."""


@dataclass
class _Writer:
    """The module being written: constants, branch functions, and fresh local names."""

    defs: dict[str, Any]
    constants: dict[str, str] = field(default_factory=dict)  # code -> name
    functions: list[list[str]] = field(default_factory=list)
    branch_names: dict[str, str] = field(default_factory=dict)  # json of schema -> name
    counter: int = 0
    expanding: list[str] = field(default_factory=list)

    def local(self) -> str:
        self.counter += 1
        return f"v{self.counter}"

    def constant(self, code: str) -> str:
        if code not in self.constants:
            self.constants[code] = f"_C{len(self.constants)}"
        return self.constants[code]


def verdict_code(schema: dict[str, Any], entry: str = "validate") -> str:
    """Return Python code defining ``entry(data) -> bool``: does ``data`` satisfy ``schema``?

    Raises:
        Unsupported: the schema uses a keyword or form not written here.
    """
    writer = _Writer(defs=dict(schema.get("$defs", {})))
    body = _check(writer, schema, "data", None)
    main = [f"def {entry}(data):", *_indent(body), "    return True"]
    lines = ["import re", "", "_NUMBER = (int, float)", "_MISSING = object()"]
    lines += [f"{name} = {code}" for code, name in writer.constants.items()]
    for function in writer.functions:
        lines += ["", "", *function]
    lines += ["", "", *main]
    return "\n".join(lines) + "\n"


def _frozen(keys: Any) -> str:
    """Return a frozenset's code with its members sorted (the same text in every process)."""
    return "frozenset({" + ", ".join(repr(k) for k in sorted(keys)) + "})"


def _indent(lines: list[str]) -> list[str]:
    return ["    " + line for line in lines]


def _check(w: _Writer, schema: Any, v: str, known: str | None) -> list[str]:
    """Return statements that ``return False`` when the value named ``v`` fails ``schema``.

    ``known`` is ``v``'s exact JSON type when an enclosing check already asserted it.
    """
    if schema is True or schema == {}:
        return []
    if schema is False:
        return ["return False"]
    if not isinstance(schema, dict):
        raise Unsupported(f"a schema must be an object or a boolean, not {schema!r}")
    unknown = set(schema) - ANNOTATIONS - KEYWORDS
    if unknown:
        raise Unsupported(f"keyword(s) not written as code: {', '.join(sorted(unknown))}")
    out: list[str] = []
    types = schema.get("type")
    if types is not None:
        names = [types] if isinstance(types, str) else list(types)
        if not names or any(t not in EXACT for t in names):
            raise Unsupported(f"type {types!r}")
        test = " or ".join(EXACT[t].format(v=v) for t in names)
        out.append(f"if not ({test}):" if len(names) > 1 else f"if not {test}:")
        out.append("    return False")
        if len(names) == 1:
            known = names[0]
    typeset = None if types is None else ({types} if isinstance(types, str) else set(types))
    for keywords, write in GROUPS:
        if any(k in schema for k in keywords):
            out += write(w, schema, v, known, typeset)
    return out


def _applies(v: str, json_type: str, known: str | None, typeset: set[str] | None) -> str | None:
    """Return the test for "``v`` is a ``json_type``" ("" when certain, None when never)."""
    if known is not None:
        return "" if known == json_type or (known == "integer" and json_type == "number") else None
    if typeset is not None:
        if json_type not in typeset and not (json_type == "number" and "integer" in typeset):
            return None
        return EXACT[json_type].format(v=v)  # v is exactly one of typeset's types
    if json_type not in BROAD:
        raise Unsupported(f"a {json_type} keyword on a value of unknown type")
    return BROAD[json_type].format(v=v)


def _guarded(test: str | None, failing: str) -> list[str]:
    """Return ``if <test> and <failing>: return False`` (nothing when the test never holds)."""
    if test is None:
        return []
    return [f"if {test + ' and ' if test else ''}{failing}:", "    return False"]


def _ref(w: _Writer, schema: dict[str, Any], v: str, known: str | None, _: Any) -> list[str]:
    ref = schema["$ref"]
    if not (isinstance(ref, str) and ref.startswith("#/$defs/")) or ref[8:] not in w.defs:
        raise Unsupported(f"$ref {ref!r} (only #/$defs/<name> of this schema)")
    name = ref[8:]
    if name in w.expanding:
        raise Unsupported(f"$ref {ref!r} refers to itself")
    w.expanding.append(name)
    try:
        return _check(w, w.defs[name], v, known)  # inline: a failure fails this schema too
    finally:
        w.expanding.pop()


def _literal(value: Any) -> tuple[str, str]:
    """Return (exact type test template, Python literal) of a ``const``/``enum`` value."""
    if isinstance(value, str):
        return "type({v}) is str", repr(value)
    if isinstance(value, int) and not isinstance(value, bool):
        return "type({v}) in _NUMBER", repr(value)  # jsonschema: 1.0 equals 1, True does not
    raise Unsupported(f"const or enum value {value!r} (only strings and integers)")


def _const(w: _Writer, schema: dict[str, Any], v: str, *_: Any) -> list[str]:
    test, literal = _literal(schema["const"])
    return [f"if not ({test.format(v=v)} and {v} == {literal}):", "    return False"]


def _enum(w: _Writer, schema: dict[str, Any], v: str, *_: Any) -> list[str]:
    values = schema["enum"]
    if not isinstance(values, list) or not values:
        raise Unsupported(f"enum {values!r}")
    tests = {_literal(x)[0] for x in values}
    if len(tests) != 1:
        raise Unsupported("an enum mixing strings and numbers")
    choices = w.constant(_frozen(values))
    return [f"if not ({tests.pop().format(v=v)} and {v} in {choices}):", "    return False"]


def _pattern(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
    # jsonschema: re.search(pattern, instance), Python's regular expressions, as here.
    search = w.constant(f"re.compile({schema['pattern']!r}).search")
    if known != "string":
        return _guarded(_applies(v, "string", known, typeset), f"{search}({v}) is None")
    # An exact str: remember the texts that matched (a library repeats its labels, types and
    # abstractions thousands of times; a set lookup is a fifth of a search).
    matched = w.constant(f"set()  # texts {search} matched")
    return [
        f"if {v} not in {matched}:",
        f"    if {search}({v}) is None:",
        "        return False",
        f"    if len({matched}) < {REMEMBERED}:",
        f"        {matched}.add({v})",
    ]


def _min_length(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
    return _guarded(_applies(v, "string", known, typeset), f"len({v}) < {int(schema['minLength'])}")


def _bound(keyword: str, operator: str) -> Any:
    def write(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
        limit = schema[keyword]
        if isinstance(limit, bool) or not isinstance(limit, int | float):
            raise Unsupported(f"{keyword} {limit!r}")
        # jsonschema's own comparison (``instance < minimum`` fails): NaN passes both ways.
        return _guarded(_applies(v, "number", known, typeset), f"{v} {operator} {limit!r}")

    return write


def _required(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
    keys = schema["required"]
    if not isinstance(keys, list) or not all(isinstance(k, str) for k in keys):
        raise Unsupported(f"required {keys!r}")
    test = _applies(v, "object", known, typeset)
    if test == "":  # an object for sure: ``_properties`` reads each key it has a schema for
        keys = [k for k in keys if k not in schema.get("properties", {})]
    if not keys:
        return []
    if len(keys) == 1:
        failing = f"{keys[0]!r} not in {v}"
    else:
        failing = f"not {v}.keys() >= {w.constant(_frozen(keys))}"
    return _guarded(test, failing)


def _properties(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
    """Write ``properties``, ``additionalProperties`` and ``propertyNames`` together."""
    test = _applies(v, "object", known, typeset)
    if test is None:
        return []
    properties = schema.get("properties", {})
    extra = schema.get("additionalProperties", True)
    names = schema.get("propertyNames", True)
    required = set(schema.get("required", []))
    body: list[str] = []
    if extra is False:
        allowed = w.constant(_frozen(properties))
        body += [f"if not {v}.keys() <= {allowed}:", "    return False"]
    for key, sub in properties.items():
        x = w.local()
        inner = _check(w, sub, x, None)
        if key in required and test == "":  # one lookup tells presence and gives the value
            body += [f"{x} = {v}.get({key!r}, _MISSING)", f"if {x} is _MISSING:"]
            body += ["    return False", *inner]
        elif not inner:
            continue
        else:
            body += [f"{x} = {v}.get({key!r}, _MISSING)", f"if {x} is not _MISSING:"]
            body += _indent(inner)
    if extra not in (True, False, {}):
        k, x = w.local(), w.local()
        inner = _check(w, extra, x, None)
        if properties:
            listed = w.constant(_frozen(properties))
            body += [f"for {k}, {x} in {v}.items():", f"    if {k} not in {listed}:"]
            body += _indent(_indent(inner))
        elif inner:
            body += [f"for {x} in {v}.values():", *_indent(inner)]
    if names not in (True, {}):
        k = w.local()
        inner = _check(w, names, k, None)
        if inner:
            body += [f"for {k} in {v}:", *_indent(inner)]
    if test == "" or not body:
        return body
    return [f"if {test}:", *_indent(body)]


def _items(w: _Writer, schema: dict[str, Any], v: str, known: Any, typeset: Any) -> list[str]:
    """Write ``items``, ``minItems`` and ``uniqueItems`` together."""
    test = _applies(v, "array", known, typeset)
    if test is None:
        return []
    body: list[str] = []
    if "minItems" in schema:
        body += [f"if len({v}) < {int(schema['minItems'])}:", "    return False"]
    items = schema.get("items", True)
    if isinstance(items, list):
        raise Unsupported("items as a list (prefixItems)")
    x = w.local()
    inner = _check(w, items, x, None)
    if inner:
        body += [f"for {x} in {v}:", *_indent(inner)]
    if schema.get("uniqueItems") is True:
        if not _asserts_string(w, items):
            raise Unsupported("uniqueItems on items that may not be strings")
        body += [f"if len(set({v})) != len({v}):", "    return False"]  # strings: == is JSON's
    if test == "" or not body:
        return body
    return [f"if {test}:", *_indent(body)]


def _asserts_string(w: _Writer, schema: Any) -> bool:
    """Tell whether ``schema`` holds only for exact ``str`` values."""
    while isinstance(schema, dict) and "$ref" in schema and "type" not in schema:
        schema = w.defs.get(str(schema["$ref"])[8:])
    return isinstance(schema, dict) and schema.get("type") == "string"


def _branches(keyword: str) -> Any:
    def write(w: _Writer, schema: dict[str, Any], v: str, known: Any, _: Any) -> list[str]:
        branches = schema[keyword]
        if not isinstance(branches, list) or not branches:
            raise Unsupported(f"{keyword} {branches!r}")
        calls = [_inline(w, b, v, known) or _branch(w, b, known) + f"({v})" for b in branches]
        if keyword == "anyOf":
            return [f"if not ({' or '.join(calls)}):", "    return False"]
        return [f"if ({' + '.join(calls)}) != 1:", "    return False"]  # bools add as 0 and 1

    return write


def _inline(w: _Writer, schema: Any, v: str, known: str | None) -> str | None:
    """Return ``schema``'s test of ``v`` as one expression, if its code is only ``if``s.

    A ``oneOf`` of ``{required: [topic]}`` and ``{required: [service]}`` becomes
    ``('topic' in v) + ('service' in v) != 1``, with no call per interface.
    """
    lines = _check(w, schema, v, known)
    if not lines or len(lines) % 2 or lines[1::2] != ["    return False"] * (len(lines) // 2):
        return None
    if not all(line.startswith("if ") and line.endswith(":") for line in lines[::2]):
        return None
    failing = " or ".join(f"({line[3:-1]})" for line in lines[::2])
    return f"(not {failing})" if len(lines) == 2 else f"(not ({failing}))"


def _branch(w: _Writer, schema: Any, known: str | None) -> str:
    """Return the name of a function telling whether its argument satisfies ``schema``."""
    key = repr((schema, known))
    if key not in w.branch_names:
        name = f"_branch{len(w.branch_names)}"
        w.branch_names[key] = name
        body = _check(w, schema, "data", known)
        w.functions.append([f"def {name}(data):", *_indent(body), "    return True"])
    return w.branch_names[key]


GROUPS: tuple[tuple[tuple[str, ...], Any], ...] = (
    (("const",), _const),
    (("enum",), _enum),
    (("pattern",), _pattern),
    (("minLength",), _min_length),
    (("minimum",), _bound("minimum", "<")),
    (("maximum",), _bound("maximum", ">")),
    (("exclusiveMinimum",), _bound("exclusiveMinimum", "<=")),
    (("exclusiveMaximum",), _bound("exclusiveMaximum", ">=")),
    (("required",), _required),
    (("oneOf",), _branches("oneOf")),
    (("anyOf",), _branches("anyOf")),
    (("properties", "additionalProperties", "propertyNames"), _properties),
    (("items", "minItems", "uniqueItems"), _items),
    (("$ref",), _ref),
)
"""Every keyword written as code (after ``type``, written first), grouped where one writer
writes several, in the order written: cheap tests of the value itself first, then
``required`` (of an object's keys without a schema: ``properties`` tests the others as it
reads them), the branches, and last the walks into mappings and lists."""

KEYWORDS = frozenset({"type", "$defs"}.union(*(keys for keys, _ in GROUPS)))
"""Every keyword this module knows (besides ``ANNOTATIONS``)."""
