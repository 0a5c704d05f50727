"""Read YAML into PyYAML's positioned node tree and plain data, applying rosreconf's rules.

The reader of record is PyYAML's composer over libyaml (``yaml.CSafeLoader``, else the pure
``yaml.SafeLoader``): every node keeps its start mark, so ``file:line:column`` comes from the
library. rosreconf's rules: no tags but the string ones; duplicate keys are errors naming
both lines; no anchors or aliases ("billion laughs"); at most ``MAX_BYTES`` and ``MAX_DEPTH``;
plain scalars resolve with YAML 1.2's core schema (``nodes.resolve_plain``). What shows in
libyaml's event stream alone (a tag, an anchor or alias, a second document, a syntax error)
is found by one pass over it (``_event_problems``), made only when it may be there: when the
text holds ``!``, ``&`` or ``*``, or libyaml stopped at a syntax error.

This is rosreconf's one YAML reader: every file (libraries, schemas, configuration files) is
composed once, here, and its problems placed with the marks of its nodes.
"""

from __future__ import annotations

import io
from typing import Any

import yaml

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.formats.nodes import (
    MappingNode,
    Node,
    Plain,
    ScalarNode,
    span,
    value,
)
from rosreconf.model import Span
from rosreconf.resources import MAX_YAML_BYTES

MAX_BYTES = MAX_YAML_BYTES
"""Largest YAML file rosreconf reads (``resources.MAX_YAML_BYTES``, which ``generate`` keeps
to); the loader reads no more than this of any file."""

MAX_DEPTH = 32
"""Deepest nesting accepted; rosreconf's formats need 6 levels."""

PLAIN = ""
"""The tag ``read`` gives an untagged plain scalar (resolved with YAML 1.2) and an untagged
collection: PyYAML's own resolver (YAML 1.1, ``no`` -> False) is never asked."""
TEXT = "tag:yaml.org,2002:str"
"""The tag of a quoted or block scalar, and of ``!!str``: a string as written."""
STR_TAGS = frozenset({TEXT, "!"})
"""The explicit tags a scalar may carry: both mean a string."""

BASE_LOADER: type[Any] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
"""libyaml's composer when PyYAML was built with it (the wheels are), else the pure one."""

_SYNTAX = "check the indentation, and quote values that contain ': ' or start with a symbol"
_ALIAS = "write the value out in full; rosreconf rejects anchors and aliases"
_TAG = "remove the tag; quote the value if you mean a string"
_DEEP = "rosreconf's formats need far fewer; check the indentation"
_MULTI, _ONE_FILE = (
    "file holds more than one YAML document",
    "keep one library or one schema per file",
)
_TEXT = "remove control characters; rosreconf reads text files only"


class _TooDeep(Exception):
    """Raised by ``_plain`` at a collection nested deeper than ``MAX_DEPTH``."""


class _Loader(BASE_LOADER):  # type: ignore[misc]
    """The composer with rosreconf's resolver: no YAML 1.1 tags (``PLAIN`` is resolved later).

    Its nesting is bounded by libyaml itself (measured: over 1000 levels) or, for the pure
    parser, by Python's recursion limit; ``_plain`` applies ``MAX_DEPTH``.
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
        collection = root is not None and type(root) is not ScalarNode
        plain = _plain(root, problems, 1) if collection else value(root)  # type: ignore[arg-type]
    except (yaml.YAMLError, RecursionError, _TooDeep):
        raise InvalidInputError(_event_problems(data, file)) from None
    finally:
        loader.dispose()
    if problems:
        raise InvalidInputError(problems)
    return root, plain


def _plain(node: Node, problems: list[Problem], depth: int) -> Plain:
    """Return ``node`` (a collection at ``depth``) as plain data; add key problems to ``problems``.

    Each mapping node also keeps its values by key (``nodes.fields``).

    Raises:
        _TooDeep: a collection is nested deeper than ``MAX_DEPTH``.
    """
    if depth > MAX_DEPTH:
        raise _TooDeep
    if type(node) is not MappingNode:
        return [
            value(item) if type(item) is ScalarNode else _plain(item, problems, depth + 1)
            for item in node.value
        ]
    out: dict[str, Plain] = {}
    by_key: dict[str, Node] = {}
    for key, item in node.value:
        if type(key) is not ScalarNode:
            message = "a mapping key must be a plain value, not a list or mapping"
            fix = "write the key as a plain name or quoted text"
            problems.append(Problem(span(key), message, fix, "complex-key"))
        elif key.value in out:
            first = next(k for k, _ in node.value if k.value == key.value).start_mark.line + 1
            message = f"duplicate key '{key.value}' (first written at line {first})"
            problems.append(
                Problem(span(key), message, "remove or rename one of the two", "duplicate-key")
            )
        else:
            by_key[key.value] = item
            scalar = type(item) is ScalarNode
            out[key.value] = value(item) if scalar else _plain(item, problems, depth + 1)
    node.fields = by_key  # type: ignore[attr-defined]
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
            said = problems.append
            if isinstance(event, yaml.DocumentStartEvent):
                documents += 1
                if documents > 1:
                    said(Problem(where, _MULTI, _ONE_FILE, "multi-document"))
            elif isinstance(event, yaml.AliasEvent):
                said(Problem(where, f"alias '*{event.anchor}' is not allowed", _ALIAS, "alias"))
            elif isinstance(event, yaml.NodeEvent):
                if event.anchor is not None:
                    said(
                        Problem(where, f"anchor '&{event.anchor}' is not allowed", _ALIAS, "alias")
                    )
                collection = isinstance(event, yaml.CollectionStartEvent)
                tag = getattr(event, "tag", None)
                if tag is not None and (collection or tag not in STR_TAGS):
                    said(Problem(where, f"YAML tag '{tag}' is not allowed", _TAG, "tag"))
                if collection and depth >= MAX_DEPTH:
                    said(
                        Problem(
                            where, f"nesting is deeper than {MAX_DEPTH} levels", _DEEP, "too-deep"
                        )
                    )
                    break  # nothing deeper is read
                depth += collection
            elif isinstance(event, yaml.CollectionEndEvent):
                depth -= 1
    except yaml.reader.ReaderError as exc:
        character = exc.character if isinstance(exc.character, int) else ord(exc.character)
        at = _offset_span(file, data, exc.position)
        problems.append(
            Problem(at, f"character U+{character:04X} is not allowed in YAML", _TEXT, "syntax")
        )
    except yaml.MarkedYAMLError as exc:
        what = " ".join(p for p in (exc.context, exc.problem) if p)
        at = _mark_span(file, exc.problem_mark or exc.context_mark)
        problems.append(Problem(at, f"YAML syntax error: {what}", _SYNTAX, "syntax"))
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
