"""Read YAML into PyYAML's positioned node tree and plain data, applying rosreconf's rules.

The reader of record is PyYAML's composer over libyaml (``yaml.CSafeLoader``): it builds the
node tree in C, and every node keeps its start mark, so ``file:line:column`` comes from the
library. Where PyYAML was installed without libyaml, the same code runs over its pure-Python
parser (``yaml.SafeLoader``), slower. Nothing is constructed: the tree's scalars keep the text
as written, and rosreconf adds the rules it promises:

* safe by construction: no tags other than the standard string ones;
* duplicate keys are errors naming both lines;
* anchors and aliases are rejected (they hide structure and allow "billion laughs");
* input over ``MAX_BYTES`` and nesting deeper than ``MAX_DEPTH`` are errors, not crashes;
* plain scalars are resolved with YAML 1.2's core schema: only ``true``/``false`` are
  booleans, so ``no``, ``on`` and ``yes`` stay strings, and the written text is kept.

``read`` composes the tree once and walks it once into the plain data the JSON Schema check
reads. Problems that show in the event stream alone (a tag, an anchor or alias, a second
document, too deep a nesting, a syntax error) are found by one pass over libyaml's events
(``_event_problems``), run only when the text holds ``!``, ``&`` or ``*`` or when composing
failed, so a clean file is read once.
"""

from __future__ import annotations

import io
import math
import re
from collections.abc import Sequence
from typing import Any, TypeAlias

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.model import Span

__all__ = [
    "MAX_BYTES",
    "MAX_DEPTH",
    "MappingNode",
    "Node",
    "Plain",
    "Scalar",
    "ScalarNode",
    "SequenceNode",
    "fields",
    "is_plain",
    "key_span",
    "lookup",
    "read",
    "resolve_plain",
    "span",
    "too_large",
    "value",
]

MAX_BYTES = 64 * 1024 * 1024
"""Largest YAML file rosreconf reads: room for a 10,000-role, 10-candidate library (27 MB as
``rosreconf generate`` writes it); the loader reads no more than this of any file."""

MAX_DEPTH = 32
"""Deepest nesting accepted; rosreconf's formats need 6 levels."""

Scalar: TypeAlias = str | int | float | bool | None
Plain: TypeAlias = "Scalar | dict[str, Plain] | list[Plain]"

PLAIN = ""
"""The tag ``read`` gives an untagged plain scalar (resolved with YAML 1.2) and an untagged
collection: PyYAML's own resolver (YAML 1.1, ``no`` -> False) is never asked."""
TEXT = "tag:yaml.org,2002:str"
"""The tag of a quoted or block scalar, and of ``!!str``: a string as written."""
STR_TAGS = frozenset({TEXT, "!"})
"""The explicit tags a scalar may carry: both mean a string."""

BASE_LOADER: type[Any] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
"""libyaml's composer when PyYAML was built with it (the wheels are), else the pure one."""

SYNTAX_HINT = "check the indentation, and quote values that contain ': ' or start with a symbol"
ALIAS_HINT = "write the value out in full; rosreconf rejects anchors and aliases"


class _TooDeep(Exception):
    """Raised by ``_plain`` at a collection nested deeper than ``MAX_DEPTH``."""


class _Loader(BASE_LOADER):  # type: ignore[misc]
    """The composer with rosreconf's resolver: no YAML 1.1 tags.

    The composer calls ``resolve`` for every untagged node; this one only tells plain
    scalars (``PLAIN``, resolved later with YAML 1.2) from the others. Its nesting is
    bounded by libyaml itself (measured: over 1000 levels, "exceeded maximum nesting depth")
    or, for the pure parser, by Python's recursion limit; ``_plain`` applies ``MAX_DEPTH``.
    """

    def resolve(self, kind: type[Node], value: Any, implicit: Any) -> str:
        """Tag a plain scalar and a collection ``PLAIN``, another untagged scalar ``TEXT``."""
        if kind is ScalarNode:
            return PLAIN if implicit[0] else TEXT
        return PLAIN if implicit else "!"


def too_large(file: str, size: int) -> Problem:
    """Return the problem of a file over ``MAX_BYTES`` (checked before reading it whole)."""
    return Problem(
        Span(file, 1, 1),
        f"file is {size} bytes, over the limit of {MAX_BYTES} bytes",
        "split the library into several files",
        code="too-large",
    )


def read(data: bytes, file: str) -> tuple[Node | None, Plain]:
    """Return the positioned tree of one YAML document and its plain data; None for no document.

    Raises:
        InvalidInputError: with every problem found (a syntax error stops reading at the
            first one, because nothing after it can be trusted).
    """
    if len(data) > MAX_BYTES:
        raise InvalidInputError([too_large(file, len(data))])
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InvalidInputError(
            [
                Problem(
                    _offset_span(file, data, exc.start),
                    "file is not valid UTF-8 text",
                    "save it as UTF-8",
                    code="encoding",
                )
            ]
        ) from None
    if b"!" in data or b"&" in data or b"*" in data:  # a tag, anchor or alias may be there
        shown = _event_problems(data, file)
        if shown:
            raise InvalidInputError(shown)
    stream = io.BytesIO(data)
    stream.name = file  # the marks' file name
    loader = _Loader(stream)
    problems: list[Problem] = []
    try:
        root: Node | None = loader.get_single_node()
        plain = _plain(root, problems, {}, 1) if root is not None else None
    except (yaml.YAMLError, RecursionError, _TooDeep):
        raise InvalidInputError(_event_problems(data, file)) from None
    finally:
        loader.dispose()
    if problems:
        raise InvalidInputError(problems)
    return root, plain


def _plain(node: Node, problems: list[Problem], resolved: dict[str, Scalar], depth: int) -> Plain:
    """Return ``node`` (a collection at ``depth``) as plain data; add key problems to ``problems``.

    Duplicate and complex keys are reported here; each mapping node also keeps its values
    by key (``fields``). A plain scalar is resolved once per distinct text (a library
    repeats its names and numbers); scalars are handled inline, collections recursively.

    Raises:
        _TooDeep: a collection is nested deeper than ``MAX_DEPTH``.
    """
    if depth > MAX_DEPTH:
        raise _TooDeep
    deeper = depth + 1
    if type(node) is SequenceNode:
        items: list[Plain] = []
        for item in node.value:
            if type(item) is ScalarNode:
                text = item.value
                if item.tag:
                    items.append(text)
                    continue
                found = resolved.get(text, resolved)
                if found is resolved:
                    found = resolved[text] = resolve_plain(text)
                items.append(found)  # type: ignore[arg-type]
            else:
                items.append(_plain(item, problems, resolved, deeper))
        return items
    if type(node) is ScalarNode:  # the document is a scalar
        return node.value if node.tag else resolve_plain(node.value)
    out: dict[str, Plain] = {}
    nodes: dict[str, Node] = {}
    for key, item in node.value:
        if type(key) is not ScalarNode:
            problems.append(
                Problem(
                    span(key),
                    "a mapping key must be a plain value, not a list or mapping",
                    code="complex-key",
                )
            )
            continue
        name = key.value
        if name in out:
            first = next(k for k, _ in node.value if type(k) is ScalarNode and k.value == name)
            problems.append(
                Problem(
                    span(key),
                    f"duplicate key '{name}' (first written at line {first.start_mark.line + 1})",
                    "remove or rename one of the two",
                    code="duplicate-key",
                )
            )
            continue
        nodes[name] = item
        if type(item) is ScalarNode:
            text = item.value
            if item.tag:
                out[name] = text
                continue
            found = resolved.get(text, resolved)
            if found is resolved:
                found = resolved[text] = resolve_plain(text)
            out[name] = found  # type: ignore[assignment]
        else:
            out[name] = _plain(item, problems, resolved, deeper)
    node.fields = nodes  # type: ignore[attr-defined]
    return out


def _event_problems(data: bytes, file: str) -> list[Problem]:
    """Return what libyaml's event stream shows wrong: tags, anchors, aliases, documents, depth.

    Reading stops at a syntax error (reported with libyaml's words) or past ``MAX_DEPTH``.
    """
    problems: list[Problem] = []
    depth = documents = 0
    stream = io.BytesIO(data)
    stream.name = file
    try:
        for event in yaml.parse(stream, Loader=BASE_LOADER):
            where = _mark_span(file, event.start_mark)
            if isinstance(event, yaml.DocumentStartEvent):
                documents += 1
                if documents > 1:
                    problems.append(
                        Problem(
                            where,
                            "file holds more than one YAML document",
                            "keep one library or one schema per file",
                            code="multi-document",
                        )
                    )
            elif isinstance(event, yaml.AliasEvent):
                problems.append(
                    Problem(where, f"alias '*{event.anchor}' is not allowed", ALIAS_HINT, "alias")
                )
            elif isinstance(event, yaml.NodeEvent):
                if event.anchor is not None:
                    problems.append(
                        Problem(
                            where, f"anchor '&{event.anchor}' is not allowed", ALIAS_HINT, "alias"
                        )
                    )
                collection = isinstance(event, yaml.CollectionStartEvent)
                tag = getattr(event, "tag", None)  # AliasEvent is the NodeEvent without one
                if tag is not None and (collection or tag not in STR_TAGS):
                    problems.append(
                        Problem(
                            where,
                            f"YAML tag '{tag}' is not allowed",
                            "remove the tag; quote the value if you mean a string",
                            code="tag",
                        )
                    )
                if collection:
                    if depth >= MAX_DEPTH:
                        problems.append(
                            Problem(
                                where,
                                f"nesting is deeper than {MAX_DEPTH} levels",
                                "rosreconf's formats need far fewer; check the indentation",
                                code="too-deep",
                            )
                        )
                        break  # nothing deeper is read
                    depth += 1
            elif isinstance(event, yaml.CollectionEndEvent):
                depth -= 1
    except yaml.reader.ReaderError as exc:
        character = exc.character if isinstance(exc.character, int) else ord(exc.character)
        problems.append(
            Problem(
                _offset_span(file, data, exc.position),
                f"character U+{character:04X} is not allowed in YAML",
                "remove control characters; rosreconf reads text files only",
                code="syntax",
            )
        )
    except yaml.MarkedYAMLError as exc:
        what = " ".join(p for p in (exc.context, exc.problem) if p)
        problems.append(
            Problem(
                _mark_span(file, exc.problem_mark or exc.context_mark),
                f"YAML syntax error: {what}",
                SYNTAX_HINT,
                code="syntax",
            )
        )
    return problems


def _mark_span(file: str, mark: Any) -> Span:
    """Turn a PyYAML mark (0-based) into a 1-based Span."""
    if mark is None:
        return Span(file, 1, 1)
    return Span(file, mark.line + 1, mark.column + 1)


def _offset_span(file: str, data: bytes, offset: int) -> Span:
    """Return the 1-based line and column (in characters) of byte ``offset`` in ``data``."""
    before = data[:offset]
    line_start = before.rfind(b"\n") + 1
    column = len(before[line_start:].decode("utf-8", "replace")) + 1
    return Span(file, before.count(b"\n") + 1, column)


# --- reading the tree --------------------------------------------------------------------


_new_span = tuple.__new__


def span(node: Node) -> Span:
    """Return where ``node`` starts (its mark carries the file name ``read`` gave it)."""
    mark = node.start_mark
    return _new_span(Span, (mark.name, mark.line + 1, mark.column + 1))


def is_plain(node: Node) -> bool:
    """Tell whether ``node`` is an untagged plain scalar (resolved with YAML 1.2)."""
    return type(node) is ScalarNode and not node.tag


_RESOLVED: dict[str, Scalar] = {}
"""Plain scalars resolved by ``value``, by text: a library repeats its numbers."""


def value(node: Node | None) -> Plain:
    """Return a scalar's resolved value (None for anything else)."""
    if type(node) is not ScalarNode:
        return None
    text: str = node.value
    if node.tag:
        return text
    found = _RESOLVED.get(text, _RESOLVED)
    if found is _RESOLVED:
        if len(_RESOLVED) > 100_000:  # a long-lived process (watch) reads many files
            _RESOLVED.clear()
        found = _RESOLVED[text] = resolve_plain(text)
    return found  # type: ignore[return-value]


_NO_FIELDS: dict[str, Node] = {}


def fields(node: Node | None) -> dict[str, Node]:
    """Return a mapping's values by key text, as ``read`` recorded them (empty for others).

    The first of a duplicate key: the file was refused for it anyway.
    """
    found: dict[str, Node] = getattr(node, "fields", _NO_FIELDS)
    return found


def lookup(node: Node | None, path: Sequence[str | int]) -> Node | None:
    """Return the node at ``path`` (keys and indices), or the deepest one that exists."""
    cur = node
    for step in path:
        child: Node | None = None
        if type(cur) is MappingNode and isinstance(step, str):
            child = fields(cur).get(step)
        elif type(cur) is SequenceNode and isinstance(step, int) and step < len(cur.value):
            child = cur.value[step]
        if child is None:
            break
        cur = child
    return cur


def key_span(node: Node | None, path: Sequence[str | int]) -> Span | None:
    """Return where the last key of ``path`` is written, when ``path`` ends in a key."""
    if not path or not isinstance(path[-1], str):
        return None
    parent = lookup(node, path[:-1])
    if type(parent) is MappingNode:
        for key, _ in parent.value:
            if key.value == path[-1]:
                return span(key)
    return None


# --- YAML 1.2 core schema -----------------------------------------------------------------

_INT = re.compile(r"[-+]?[0-9]+\Z")
_OCT = re.compile(r"0o[0-7]+\Z")
_HEX = re.compile(r"0x[0-9a-fA-F]+\Z")
_FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?\Z")
_INF = re.compile(r"[-+]?\.(inf|Inf|INF)\Z")
_NAN = re.compile(r"\.(nan|NaN|NAN)\Z")
_MAX_INT_DIGITS = 4000
"""Longer integers read as infinite (out of every range, so refused where a number goes)."""
_MAY_BE_NON_TEXT = frozenset("~nNtTfF0123456789+-.")
"""First characters of every YAML 1.2 core null, boolean, integer and float."""
_MAY_BE_NUMBER = frozenset("0123456789+-.")
"""First characters of every YAML 1.2 core integer and float (no null or boolean)."""


def resolve_plain(text: str) -> Scalar:
    """Resolve a plain scalar with YAML 1.2's core schema (never ``no`` -> False).

    The tests run from the cheapest decisive one: names by their first character, then
    numbers (a library's many metrics) without the null and boolean spellings.
    """
    if not text:
        return None
    first = text[0]
    if first not in _MAY_BE_NON_TEXT:
        return text  # most names: no pattern can match, skip them all
    if first in _MAY_BE_NUMBER:
        if _INT.match(text):
            if len(text) > _MAX_INT_DIGITS:  # int() refuses more digits; no count is text
                return -math.inf if first == "-" else math.inf
            return int(text)
        if _FLOAT.match(text):
            return float(text)
        if _OCT.match(text):
            return int(text[2:], 8)
        if _HEX.match(text):
            return int(text[2:], 16)
        if _INF.match(text):
            return -math.inf if first == "-" else math.inf
        if _NAN.match(text):
            return math.nan
        return text
    if text in ("~", "null", "Null", "NULL"):
        return None
    if text in ("true", "True", "TRUE"):
        return True
    if text in ("false", "False", "FALSE"):
        return False
    return text
