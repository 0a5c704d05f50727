"""Read YAML with PyYAML's pure parser into the positioned tree, reporting every problem.

This is the reader of record: the fast path (``yamlfast``) hands any file it declines, and
every file with something to report, to this one, so that messages and positions never depend
on whether libyaml is installed. It builds the tree from PyYAML's event stream (a
non-recursive state machine, so deep nesting cannot exhaust Python's stack) and applies
rosreconf's rules: one document, no anchors or aliases, no tags but the string ones, no
duplicate or complex keys, at most ``MAX_DEPTH`` levels, YAML 1.2 plain scalars.
"""

from __future__ import annotations

from typing import Any

import yaml

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.formats.yamltree import (
    MAX_DEPTH,
    STR_TAGS,
    Scalar,
    YMapping,
    YNode,
    YScalar,
    YSequence,
    resolve_plain,
)
from rosreconf.model import Span


def read_pure(text: str, file: str) -> YNode | None:
    """Parse ``text`` with PyYAML's pure parser; ``None`` for an empty document.

    Raises:
        InvalidInputError: with every structural problem found (a YAML syntax error stops
            parsing at the first one, because nothing after it can be trusted).
    """
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
                span_of(file, mark),
                f"YAML syntax error: {what}",
                "check the indentation, and quote values that contain ': ' or start with a symbol",
                code="syntax",
            )
        )
    except yaml.reader.ReaderError as exc:
        builder.problems.append(
            Problem(
                offset_span(file, text, exc.position),
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


def span_of(file: str, mark: Any) -> Span:
    """Turn a PyYAML mark (0-based, pure-Python or C variant) into a 1-based Span."""
    if mark is None:
        return Span(file, 1, 1)
    return Span(file, mark.line + 1, mark.column + 1)


def offset_span(file: str, text: str, offset: int) -> Span:
    """Return the 1-based line and column of character ``offset`` in ``text``."""
    before = text[:offset]
    line = before.count("\n") + 1
    column = offset - (before.rfind("\n") + 1) + 1
    return Span(file, line, column)


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
        span = span_of(self.file, event.start_mark)
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
        if tag is None or (not collection and tag in STR_TAGS):
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
