"""Read YAML into a tree that remembers where every value was written.

PyYAML's ``safe_load`` forgets positions, follows YAML 1.1 (where ``no`` and ``on`` become
booleans), accepts duplicate keys silently and recurses once per nesting level. Users need
``file:line:column`` in every error, so this module builds its own tree from PyYAML's
event stream (which is produced by a non-recursive state machine) and applies the rules
rosreconf promises:

* safe by construction: no tags other than the standard string ones, nothing is constructed;
* duplicate keys are errors naming both lines;
* anchors and aliases are rejected (they hide structure and allow "billion laughs");
* input over ``MAX_BYTES`` and nesting deeper than ``MAX_DEPTH`` are errors, not crashes;
* plain scalars are resolved with YAML 1.2's core schema: only ``true``/``false`` are
  booleans, so ``no``, ``on`` and ``yes`` stay strings; the written text is always kept
  (``raw``) so a value such as ``0755`` can be reported exactly as the user wrote it.
"""

from __future__ import annotations

import gc
import math
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any, TypeAlias

import yaml

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.model import Span

MAX_BYTES = 64 * 1024 * 1024
"""Largest YAML file rosreconf reads: room for a 10,000-role, 10-candidate library (27 MB as
``rosreconf generate`` writes it); the loader reads no more than this of any file."""

MAX_DEPTH = 32
"""Deepest nesting accepted; rosreconf's formats need 6 levels."""

FAST_LOADER: type[yaml.CSafeLoader] | None = (
    yaml.CSafeLoader if getattr(yaml, "__with_libyaml__", False) else None
)
"""libyaml's parser when PyYAML was built with it (the wheels are), else None."""

Scalar: TypeAlias = str | int | float | bool | None
Plain: TypeAlias = "Scalar | dict[str, Plain] | list[Plain]"

_STR_TAGS = {"tag:yaml.org,2002:str", "!"}
_INT = re.compile(r"[-+]?[0-9]+\Z")
_OCT = re.compile(r"0o[0-7]+\Z")
_HEX = re.compile(r"0x[0-9a-fA-F]+\Z")
_FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?\Z")
_INF = re.compile(r"[-+]?\.(inf|Inf|INF)\Z")
_MAX_INT_DIGITS = 4000
"""Longer integers read as infinite (out of every range, so refused where a number goes)."""
_NAN = re.compile(r"\.(nan|NaN|NAN)\Z")


@dataclass(slots=True)
class YNode:
    """A value in the tree and where it starts."""

    span: Span


@dataclass(slots=True)
class YScalar(YNode):
    """A scalar: its resolved value, the text as written, and whether it was plain."""

    value: Scalar
    raw: str
    plain: bool


@dataclass(slots=True)
class YMapping(YNode):
    """A mapping with string keys, in file order; ``key_spans`` says where each key is."""

    items: dict[str, YNode] = field(default_factory=dict)
    key_spans: dict[str, Span] = field(default_factory=dict)


@dataclass(slots=True)
class YSequence(YNode):
    """A sequence of values, in file order."""

    items: list[YNode] = field(default_factory=list)


_MAY_BE_NON_TEXT = frozenset("~nNtTfF0123456789+-.")
"""First characters of every YAML 1.2 core null, boolean, integer and float."""


def resolve_plain(text: str) -> Scalar:
    """Resolve a plain scalar with YAML 1.2's core schema (never ``no`` -> False)."""
    if text and text[0] not in _MAY_BE_NON_TEXT:
        return text  # most names: no pattern can match, skip them all
    if text in ("", "~", "null", "Null", "NULL"):
        return None
    if text in ("true", "True", "TRUE"):
        return True
    if text in ("false", "False", "FALSE"):
        return False
    if _INT.match(text):
        if len(text) > _MAX_INT_DIGITS:  # int() refuses more digits; no count of ours is text
            return -math.inf if text.startswith("-") else math.inf
        return int(text)
    if _OCT.match(text):
        return int(text[2:], 8)
    if _HEX.match(text):
        return int(text[2:], 16)
    if _FLOAT.match(text):
        return float(text)
    if _INF.match(text):
        return -math.inf if text.startswith("-") else math.inf
    if _NAN.match(text):
        return math.nan
    return text


def _span(file: str, mark: Any) -> Span:
    """Turn a PyYAML mark (0-based, pure-Python or C variant) into a 1-based Span."""
    if mark is None:
        return Span(file, 1, 1)
    return Span(file, mark.line + 1, mark.column + 1)


def _offset_span(file: str, text: str, offset: int) -> Span:
    before = text[:offset]
    line = before.count("\n") + 1
    column = offset - (before.rfind("\n") + 1) + 1
    return Span(file, line, column)


def too_large(file: str, size: int) -> Problem:
    """Return the problem of a file over ``MAX_BYTES`` (checked before reading it whole)."""
    return Problem(
        Span(file, 1, 1),
        f"file is {size} bytes, over the limit of {MAX_BYTES} bytes",
        "split the library into several files",
        code="too-large",
    )


def parse(data: bytes, file: str) -> YNode | None:
    """Parse one YAML document into a positioned tree; ``None`` for an empty file.

    Raises:
        InvalidInputError: with every structural problem found (the YAML syntax errors stop
            parsing at the first one, because nothing after it can be trusted).
    """
    if len(data) > MAX_BYTES:
        raise InvalidInputError([too_large(file, len(data))])
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        good = data[: exc.start].decode("utf-8", errors="replace")
        raise InvalidInputError(
            [
                Problem(
                    _offset_span(file, good, len(good)),
                    "file is not valid UTF-8 text",
                    "save it as UTF-8",
                    code="encoding",
                )
            ]
        ) from None
    if FAST_LOADER is not None and _fast_path_safe(text):
        # libyaml parses about six times faster. On any problem the pure-Python parser reads the
        # file again, so that messages and positions never depend on which parser is installed.
        fast = _fast_tree(text, file)
        if fast is not _UNCLEAN:
            return fast
    builder = _Builder(file)
    try:
        for event in yaml.parse(text, Loader=yaml.SafeLoader):
            builder.feed(event)
    except _StopParsing:
        pass
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        what = " ".join(p for p in (exc.context, exc.problem) if p)
        builder.problems.append(
            Problem(
                _span(file, mark),
                f"YAML syntax error: {what}",
                "check the indentation, and quote values that contain ': ' or start with a symbol",
                code="syntax",
            )
        )
    except yaml.reader.ReaderError as exc:
        builder.problems.append(
            Problem(
                _offset_span(file, text, exc.position),
                f"character U+{_codepoint(exc.character):04X} is not allowed in YAML",
                "remove control characters; rosreconf reads text files only",
                code="syntax",
            )
        )
    except yaml.YAMLError as exc:  # pragma: no cover - PyYAML raises marked errors
        builder.problems.append(Problem(Span(file, 1, 1), f"YAML error: {exc}", code="syntax"))
    if builder.problems:
        raise InvalidInputError(builder.problems)
    return builder.root


def _fast_path_safe(text: str) -> bool:
    """Tell whether libyaml is known to read ``text`` exactly as PyYAML's pure parser does.

    The two differ on tabs (libyaml accepts a tab inside a plain scalar, PyYAML's scanner
    does not), on ``?`` (libyaml accepts ``e?lbow`` as a plain key inside ``{...}``, PyYAML
    stops there with a syntax error) and on characters PyYAML's reader refuses; such text
    takes the pure path (slower, same answer).
    tests/test_fast_paths.py searches for other differences.
    """
    return (
        FAST_LOADER is not None
        and "\t" not in text
        and "?" not in text
        and not yaml.reader.Reader.NON_PRINTABLE.search(text)
    )


_UNCLEAN = YScalar(Span("<unclean>", 0, 0), None, "", False)
"""What ``_fast_tree`` returns when the file needs the full reader (and its messages)."""


def _fast_tree(text: str, file: str) -> YNode | None:
    """Build the tree from libyaml's events in one tight loop, or return ``_UNCLEAN``.

    Valid files are the common case and a thousand-role library has 380,000 events, so this
    loop does only what a clean file needs: no problem list, no per-event method calls, plain
    scalars resolved once per distinct text. Anything ``_Builder`` would report (a second
    document, an anchor or alias, a tag, a duplicate or complex key, too deep a nesting, a
    syntax error) returns ``_UNCLEAN``, and ``parse`` reads the file again with the full
    reader. tests/test_fast_paths.py holds both paths to identical trees.
    """
    assert FAST_LOADER is not None
    loader = FAST_LOADER(text)
    collecting = gc.isenabled()
    gc.disable()  # the tree only grows here: cycle collections would find nothing to free
    try:
        return _fast_events(loader.get_event, file)
    except yaml.YAMLError:
        return _UNCLEAN
    finally:
        loader.dispose()
        if collecting:
            gc.enable()


def _fast_events(get: Any, file: str) -> YNode | None:
    """Consume events from ``get`` into a tree (see ``_fast_tree``); one flat loop for speed."""
    scalar_event, alias_event = yaml.ScalarEvent, yaml.AliasEvent
    map_start, seq_start = yaml.MappingStartEvent, yaml.SequenceStartEvent
    map_end, seq_end = yaml.MappingEndEvent, yaml.SequenceEndEvent
    doc_start, stream_end = yaml.DocumentStartEvent, yaml.StreamEndEvent
    new_span = tuple.__new__
    resolved: dict[str, Scalar] = {}
    root: YNode | None = None
    stack: list[YMapping | YSequence] = []
    keys: list[tuple[str, Span] | None] = []
    documents = 0
    while True:
        event = get()
        cls = type(event)
        node: YNode
        if cls is scalar_event:
            if event.anchor is not None:
                return _UNCLEAN
            mark = event.start_mark
            span = new_span(Span, (file, mark.line + 1, mark.column + 1))
            tag, text = event.tag, event.value
            if tag is None and not event.style and event.implicit[0]:
                if text in resolved:
                    value = resolved[text]
                else:
                    value = resolved[text] = resolve_plain(text)
                node = YScalar(span, value, text, True)
            elif tag is None or tag in _STR_TAGS:
                node = YScalar(span, text, text, False)
            else:
                return _UNCLEAN
        elif cls is map_start or cls is seq_start:
            if event.anchor is not None or event.tag is not None or len(stack) >= MAX_DEPTH:
                return _UNCLEAN
            mark = event.start_mark
            span = new_span(Span, (file, mark.line + 1, mark.column + 1))
            node = YMapping(span) if cls is map_start else YSequence(span)
        elif cls is map_end or cls is seq_end:
            stack.pop()
            keys.pop()
            continue
        elif cls is doc_start:
            documents += 1
            if documents > 1:
                return _UNCLEAN
            continue
        elif cls is stream_end:
            return root
        elif cls is alias_event:
            return _UNCLEAN
        else:
            continue  # stream and document ends
        if stack:
            parent = stack[-1]
            if isinstance(parent, YSequence):
                parent.items.append(node)
            else:
                key = keys[-1]
                if key is None:
                    if not isinstance(node, YScalar):
                        return _UNCLEAN  # a complex key
                    keys[-1] = (node.raw, node.span)
                    continue
                name, where = key
                if name in parent.items:
                    return _UNCLEAN  # a duplicate key
                parent.items[name] = node
                parent.key_spans[name] = where
                keys[-1] = None
        else:
            root = node
        if not isinstance(node, YScalar):
            stack.append(node)
            keys.append(None)


class _StopParsing(Exception):
    """Stop reading events once a limit is hit (the problem is already recorded)."""


def _codepoint(character: str | int) -> int:
    return character if isinstance(character, int) else ord(character)


class _Builder:
    """Turn PyYAML events into YNodes without recursion, collecting problems."""

    def __init__(self, file: str) -> None:
        self.file = file
        self.root: YNode | None = None
        self.stack: list[YMapping | YSequence] = []
        self.pending_key: list[tuple[str, Span] | None] = []
        self.problems: list[Problem] = []
        self.documents = 0

    def feed(self, event: yaml.Event) -> None:
        """Consume one event."""
        span = _span(self.file, event.start_mark)
        if isinstance(event, yaml.DocumentStartEvent):
            self.documents += 1
            if self.documents > 1:
                self.problems.append(
                    Problem(
                        span,
                        "file holds more than one YAML document",
                        "keep one library or one schema per file",
                        code="multi-document",
                    )
                )
            return
        if isinstance(event, yaml.AliasEvent):
            self.problems.append(
                Problem(
                    span,
                    f"alias '*{event.anchor}' is not allowed",
                    "write the value out in full; rosreconf rejects anchors and aliases",
                    code="alias",
                )
            )
            self._attach(YScalar(span, None, "", True), span)
            return
        if isinstance(event, yaml.NodeEvent) and event.anchor is not None:
            self.problems.append(
                Problem(
                    span,
                    f"anchor '&{event.anchor}' is not allowed",
                    "write the value out in full; rosreconf rejects anchors and aliases",
                    code="alias",
                )
            )
        if isinstance(event, yaml.ScalarEvent):
            self._attach(self._scalar(event, span), span)
        elif isinstance(event, yaml.MappingStartEvent | yaml.SequenceStartEvent):
            self._check_tag(event.tag, span, collection=True)
            node: YMapping | YSequence = (
                YMapping(span) if isinstance(event, yaml.MappingStartEvent) else YSequence(span)
            )
            if len(self.stack) >= MAX_DEPTH:
                self.problems.append(
                    Problem(
                        span,
                        f"nesting is deeper than {MAX_DEPTH} levels",
                        "rosreconf's formats need far fewer; check the indentation",
                        code="too-deep",
                    )
                )
                raise _StopParsing  # reported above; nothing deeper is read
            self._attach(node, span)
            self.stack.append(node)
            self.pending_key.append(None)
        elif isinstance(event, yaml.MappingEndEvent | yaml.SequenceEndEvent):
            self.stack.pop()
            self.pending_key.pop()

    def _check_tag(self, tag: str | None, span: Span, *, collection: bool) -> bool:
        if tag is None or (not collection and tag in _STR_TAGS):
            return True
        self.problems.append(
            Problem(
                span,
                f"YAML tag '{tag}' is not allowed",
                "remove the tag; quote the value if you mean a string",
                code="tag",
            )
        )
        return False

    def _scalar(self, event: yaml.ScalarEvent, span: Span) -> YScalar:
        # A plain scalar has no style: None from PyYAML's parser, "" from libyaml's.
        plain = not event.style and event.implicit[0]
        if event.tag is not None and not self._check_tag(event.tag, span, collection=False):
            return YScalar(span, event.value, event.value, False)
        value: Scalar = resolve_plain(event.value) if plain and event.tag is None else event.value
        return YScalar(span, value, event.value, bool(plain and event.tag is None))

    def _attach(self, node: YNode, span: Span) -> None:
        if not self.stack:
            self.root = node
            return
        parent = self.stack[-1]
        if isinstance(parent, YSequence):
            parent.items.append(node)
            return
        key = self.pending_key[-1]
        if key is None:
            self.pending_key[-1] = (self._key_text(node), span)
            return
        name, key_span = key
        self.pending_key[-1] = None
        if name in parent.items:
            first = parent.key_spans[name]
            self.problems.append(
                Problem(
                    key_span,
                    f"duplicate key '{name}' (first written at line {first.line})",
                    "remove or rename one of the two",
                    code="duplicate-key",
                )
            )
            return
        parent.items[name] = node
        parent.key_spans[name] = key_span

    def _key_text(self, node: YNode) -> str:
        if isinstance(node, YScalar):
            return node.raw
        self.problems.append(
            Problem(
                node.span,
                "a mapping key must be a plain value, not a list or mapping",
                code="complex-key",
            )
        )
        return f"<complex key at {node.span.line}:{node.span.column}>"


def to_plain(node: YNode | None) -> Plain:
    """Return the tree as plain Python values (for JSON Schema validation).

    Recursion is safe here: ``parse`` has already refused anything deeper than ``MAX_DEPTH``.
    """
    if node is None:
        return None
    if isinstance(node, YScalar):
        return node.value
    if isinstance(node, YMapping):
        return {k: to_plain(v) for k, v in node.items.items()}
    assert isinstance(node, YSequence)
    return [to_plain(v) for v in node.items]


def lookup(node: YNode | None, path: Sequence[str | int]) -> YNode | None:
    """Return the node at ``path`` (keys and indices), or the deepest one that exists."""
    cur = node
    for step in path:
        child: YNode | None = None
        if isinstance(cur, YMapping) and isinstance(step, str):
            child = cur.items.get(step)
        elif isinstance(cur, YSequence) and isinstance(step, int) and step < len(cur.items):
            child = cur.items[step]
        if child is None:
            break
        cur = child
    return cur


def key_span(node: YNode | None, path: Sequence[str | int]) -> Span | None:
    """Return where the last key of ``path`` is written, when ``path`` ends in a key."""
    if not path or not isinstance(path[-1], str):
        return None
    parent = lookup(node, path[:-1])
    if isinstance(parent, YMapping):
        return parent.key_spans.get(path[-1])
    return None


def walk(node: YNode | None) -> Iterator[YNode]:
    """Yield every node of the tree, parents before children."""
    stack = [node] if node is not None else []
    while stack:
        cur = stack.pop()
        yield cur
        if isinstance(cur, YMapping):
            stack.extend(reversed(list(cur.items.values())))
        elif isinstance(cur, YSequence):
            stack.extend(reversed(cur.items))
