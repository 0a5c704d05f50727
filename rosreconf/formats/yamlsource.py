"""Read YAML into plain data and a positions table, applying rosreconf's rules, in one pass.

libyaml's event parser (``yaml.CSafeLoader``, else the pure ``yaml.SafeLoader``) runs once
over each file; ``_Reader`` builds the plain data (dicts, lists, scalars) straight from its
events and records where each value and key starts in a compact side table
(``positions.Positions``), looked up only to report a problem. PyYAML's composed node tree,
a Python object and two marks per value, took 80 times a large file's size in memory.

rosreconf's rules, applied on the way: no tags but the string ones; duplicate keys are
errors naming both lines; no anchors or aliases ("billion laughs"); at most ``MAX_BYTES``
and ``MAX_DEPTH``; one document; plain scalars resolve with YAML 1.2's core schema
(``nodes.resolve_plain``; ``no`` stays text). Every problem keeps libyaml's
``file:line:column``.

This is rosreconf's one YAML reader: every file (libraries, schemas, configuration files) is
read once, here.
"""

from __future__ import annotations

from array import array
from collections.abc import Callable
from typing import Any

import yaml
from yaml.events import (
    AliasEvent,
    DocumentStartEvent,
    MappingEndEvent,
    MappingStartEvent,
    ScalarEvent,
    SequenceEndEvent,
    SequenceStartEvent,
    StreamEndEvent,
)

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.formats.nodes import Plain, Scalar, resolve_plain
from rosreconf.formats.positions import (
    MAPPING,
    PLAIN_SCALAR,
    SEQUENCE,
    TEXT_SCALAR,
    Positions,
    spelling,
)
from rosreconf.model import Span
from rosreconf.resources import MAX_YAML_BYTES

MAX_BYTES = MAX_YAML_BYTES
"""Largest YAML file rosreconf reads (``resources.MAX_YAML_BYTES``, which ``generate`` keeps
to); the loader reads no more than this of any file."""

MAX_DEPTH = 32
"""Deepest nesting accepted; rosreconf's formats need 6 levels."""

TEXT = "tag:yaml.org,2002:str"
"""The tag of ``!!str``: a string as written."""
STR_TAGS = frozenset({TEXT, "!"})
"""The explicit tags a scalar may carry: both mean a string (``!`` on a plain scalar leaves
it plain, as PyYAML's composer did)."""

BASE_LOADER: type[Any] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
"""libyaml's parser when PyYAML was built with it (the wheels are), else the pure one."""

_SYNTAX = "check the indentation, and quote values that contain ': ' or start with a symbol"
_ALIAS = "write the value out in full; rosreconf rejects anchors and aliases"
_TAG = "remove the tag; quote the value if you mean a string"
_DEEP = "rosreconf's formats need far fewer; check the indentation"
_MULTI, _ONE_FILE = (
    "file holds more than one YAML document",
    "keep one library or one schema per file",
)
_TEXT = "remove control characters; rosreconf reads text files only"


def too_large(file: str, size: int) -> Problem:
    """Return the problem of a file over ``MAX_BYTES`` (checked before reading it whole)."""
    return Problem(
        Span(file, 1, 1),
        f"file is {size} bytes, over the limit of {MAX_BYTES} bytes",
        "split the library into several files",
        code="too-large",
    )


def read(data: bytes, file: str) -> tuple[Positions | None, Plain]:
    """Return the positions of one YAML document and its plain data; None for no document.

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
    reader = _Reader(file)
    loader = BASE_LOADER(data)
    try:
        reader.run(loader.get_event)
    except yaml.reader.ReaderError as exc:
        character = exc.character if isinstance(exc.character, int) else ord(exc.character)
        at = _offset_span(file, data, exc.position)
        reader.shown.append(
            Problem(at, f"character U+{character:04X} is not allowed in YAML", _TEXT, "syntax")
        )
    except yaml.MarkedYAMLError as exc:
        what = " ".join(p for p in (exc.context, exc.problem) if p)
        at = _mark_span(file, exc.problem_mark or exc.context_mark)
        reader.shown.append(Problem(at, f"YAML syntax error: {what}", _SYNTAX, "syntax"))
    finally:
        loader.dispose()
    if reader.shown or reader.keys:  # what the event stream shows first: keys mean little then
        raise InvalidInputError(reader.shown or reader.keys)
    if not reader.tags:
        return None, None
    return reader.positions(), reader.root


_NO_KEY: Any = object()
"""What an open mapping's frame holds while it waits for its next key."""


class _Reader:
    """Build a document's plain data and positions from libyaml's events, in one pass.

    Attributes:
        shown: what the event stream shows wrong (tags, anchors, aliases, documents, depth,
            syntax), in document order.
        keys: the mappings' key problems (duplicate or complex keys), said only when the
            stream shows nothing wrong.
        root: the document's plain data.
    """

    def __init__(self, file: str) -> None:
        self.file = file
        self.shown: list[Problem] = []
        self.keys: list[Problem] = []
        self.root: Plain = None
        self.lines: array[int] = array("I")
        self.cols: array[int] = array("I")
        self.ends: array[int] = array("I")
        self.tags: array[int] = array("I")  # kind | key number << 2 (positions.Positions)
        self.names: list[str] = [""]  # the keys' texts by number; 0 is no key
        self.texts: dict[int, str] = {}

    def positions(self) -> Positions:
        """Return the side table of the document read (``positions.Positions``)."""
        table = (self.lines, self.cols, self.ends, self.tags)
        return Positions(self.file, self.root, table, self.names, self.texts)

    def run(self, get_event: Callable[[], Any]) -> None:
        """Read every event; stop past ``MAX_DEPTH`` (nothing deeper is read).

        One loop with the events' types compared by identity: it runs once per value of
        the largest files, and a call per event would cost a third more.

        Raises:
            yaml.YAMLError: at a syntax error (``read`` says it).
        """
        texts, ends, names = self.texts, self.ends, self.names
        numbers = {"": 0}
        line_of, col_of, end_of, kind_of = (
            self.lines.append,
            self.cols.append,
            ends.append,
            self.tags.append,
        )
        resolved = _RESOLVED
        # An open collection's frame: [its plain value, its index, the key waiting for its
        # value (or _NO_KEY), that key's index, and once one is said, its bad keys' indices];
        # a list's frame never waits for a key.
        stack: list[list[Any]] = []
        frame: list[Any] | None = None
        want_key = False  # the next node is a key of the open mapping
        documents = n = 0  # n: the events recorded (the next one's index)
        value: Plain
        while True:
            event = get_event()
            kind = type(event)
            if kind is ScalarEvent:
                mark = event.start_mark
                line_of(mark.line)
                col_of(mark.column)
                n += 1
                end_of(n)
                tag = event.tag
                if event.anchor is not None or (tag is not None and tag not in STR_TAGS):
                    self._node_problems(event)
                text = event.value
                if want_key:
                    number = numbers.get(text)  # a key: always its text, by its number
                    if number is None:
                        number = numbers[text] = len(names)
                        names.append(text)
                    kind_of(TEXT_SCALAR | number << 2)
                    frame[2] = names[number]  # type: ignore[index]  # one string per key text
                    frame[3] = n - 1  # type: ignore[index]
                    want_key = False
                    continue
                if event.implicit[0] and (tag is None or tag == "!"):
                    kind_of(PLAIN_SCALAR)
                    found = resolved.get(text)
                    if found is None:
                        if len(resolved) > 100_000:  # a long-lived process reads many files
                            resolved.clear()
                        found = resolved[text] = _resolved(text)
                    value = found[0]
                    if not found[1]:
                        texts[n - 1] = text
                else:
                    kind_of(TEXT_SCALAR)
                    value = text
            elif kind is MappingStartEvent or kind is SequenceStartEvent:
                mark = event.start_mark
                line_of(mark.line)
                col_of(mark.column)
                end_of(0)  # set at its end
                n += 1
                want_key = kind is MappingStartEvent
                kind_of(MAPPING if want_key else SEQUENCE)
                if event.anchor is not None or event.tag is not None:
                    self._node_problems(event)
                if len(stack) >= MAX_DEPTH:
                    message = f"nesting is deeper than {MAX_DEPTH} levels"
                    self.shown.append(Problem(self._span(n - 1), message, _DEEP, "too-deep"))
                    return
                frame = [{} if want_key else [], n - 1, _NO_KEY, -1]
                stack.append(frame)
                continue
            elif kind is MappingEndEvent or kind is SequenceEndEvent:
                done = stack.pop()
                ends[done[1]] = n
                frame = stack[-1] if stack else None
                value = done[0]
                if frame is not None and frame[2] is _NO_KEY and type(frame[0]) is dict:
                    frame[2] = value  # a complex key, said with its value
                    frame[3] = done[1]
                    want_key = False
                    continue
            elif kind is AliasEvent:
                line_of(event.start_mark.line)
                col_of(event.start_mark.column)
                n += 1
                end_of(n)
                kind_of(TEXT_SCALAR)
                message = f"alias '*{event.anchor}' is not allowed"
                self.shown.append(Problem(self._span(n - 1), message, _ALIAS, "alias"))
                value = None
                if want_key:
                    frame[2] = ""  # type: ignore[index]
                    frame[3] = n - 1  # type: ignore[index]
                    want_key = False
                    continue
            elif kind is DocumentStartEvent:
                documents += 1
                if documents > 1:
                    where = _mark_span(self.file, event.start_mark)
                    self.shown.append(Problem(where, _MULTI, _ONE_FILE, "multi-document"))
                continue
            elif kind is StreamEndEvent:
                return
            else:
                continue
            if frame is None:
                if documents == 1:
                    self.root = value
                continue
            held = frame[0]
            if type(held) is list:
                held.append(value)
                continue
            want_key = True
            key = frame[2]
            if type(key) is str and key not in held and len(frame) == 4:
                held[key] = value
                frame[2] = _NO_KEY
            else:
                self._put(frame, value)

    def _put(self, frame: list[Any], value: Plain) -> None:
        """Add ``value`` under the key ``frame`` waits with; a bad key is a problem instead."""
        mapping, start, key, at = frame[:4]
        frame[2] = _NO_KEY
        if type(key) is str and key not in mapping:
            mapping[key] = value
            return
        if len(frame) == 4:
            frame.append(set())
        if type(key) is not str:
            message = "a mapping key must be a plain value, not a list or mapping"
            fix = "write the key as a plain name or quoted text"
            self.keys.append(Problem(self._span(at), message, fix, "complex-key"))
        else:
            first = self.lines[self._first_key(start, mapping, key, frame[4])] + 1
            message = f"duplicate key '{key}' (first written at line {first})"
            fix = "remove or rename one of the two"
            self.keys.append(Problem(self._span(at), message, fix, "duplicate-key"))
        frame[4].add(at)

    def _first_key(self, start: int, mapping: dict[str, Plain], key: str, bad: set[int]) -> int:
        """Return the event index of ``key`` in the open mapping at ``start``.

        The keys' events are walked in order, beside the keys kept: a key said wrong
        (``bad``) was not kept.
        """
        k, ends = start + 1, self.ends
        for written in mapping:
            while k in bad:
                k = ends[ends[k]]
            if written == key:
                return k
            k = ends[ends[k]]
        return k

    def _span(self, index: int) -> Span:
        return Span(self.file, self.lines[index] + 1, self.cols[index] + 1)

    def _node_problems(self, event: Any) -> None:
        """Say a node event's anchor, and its tag unless a string's (``STR_TAGS``)."""
        where = _mark_span(self.file, event.start_mark)
        if event.anchor is not None:
            message = f"anchor '&{event.anchor}' is not allowed"
            self.shown.append(Problem(where, message, _ALIAS, "alias"))
        tag = event.tag
        collection = type(event) is not ScalarEvent
        if tag is not None and (collection or tag not in STR_TAGS):
            self.shown.append(Problem(where, f"YAML tag '{tag}' is not allowed", _TAG, "tag"))


_RESOLVED: dict[str, tuple[Scalar, bool]] = {}
"""Plain scalars resolved, by text, and whether the text is the value's usual spelling
(``positions.spelling``, so its text need not be kept): a library repeats its numbers."""


def _resolved(text: str) -> tuple[Scalar, bool]:
    value = resolve_plain(text)
    try:
        return value, spelling(value) == text
    except ValueError:  # an integer of more digits than Python prints
        return value, False


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
