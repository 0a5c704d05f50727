"""Read a clean YAML file at libyaml's speed, or decline it for the reader of record.

A thousand-role library is 380,000 libyaml events. This module turns them into the
positioned tree *and* the plain data the JSON Schema check needs, in one flat loop: no
per-event method calls, no problem list, plain scalars resolved once per distinct text.
It never reports anything itself: whatever the pure reader (``yamlbuilder``) would report
(a second document, an anchor or alias, a tag, a duplicate or complex key, nesting deeper
than ``MAX_DEPTH``, a syntax error) and wherever libyaml might read the text differently
from PyYAML's pure parser, it returns ``DECLINED`` and ``yamlsource.parse`` reads the file
again with the pure reader, so that trees, messages and positions never depend on whether
libyaml is installed. tests/test_fast_paths.py holds both paths to identical answers.

libyaml 0.2.5 and PyYAML 6's pure parser read the same text differently where:

* a tab separates tokens or sits in a plain scalar (libyaml accepts it, PyYAML does not);
* a character PyYAML's reader refuses is present;
* a byte order mark is present: libyaml skips one at the start of every line, PyYAML only
  at the start of the file, and PyYAML does not count it as a column;
* ``?`` is inside a plain scalar in a flow collection: libyaml keeps it in the scalar (as
  YAML 1.2 allows), PyYAML ends the scalar there and reads ``?`` as a key indicator, which
  is then a syntax error (``{type: r?obot}``, ``{e?lbow: x}``: "expected ',' or '}'");
* an empty value in a flow collection (``{a: }``): libyaml puts it at the next token,
  PyYAML right after the ``:``;
* an empty value at the end of the text (``? a`` with no line break after it): libyaml ends
  the stream on a line of its own, PyYAML where the text ends;
* characters allowed in tags (``,``, ``[`` and ``]``), so any tag is declined;
* a ``#`` right after a block scalar's header (``|#``), a comment to libyaml only.

The first three are seen in the text alone (``fast_path_safe``); the loop checks the rest.

The loop exists twice: in C (``_yamlc.c``, the extension ``rosreconf.formats._yamlc``, built
against libyaml when rosreconf is installed with a C compiler and libyaml's headers), which
reads libyaml's events without PyYAML's Python event objects, several times faster; and
here in Python (``_events``), used when the extension is not built or when the environment
variable ``ROSRECONF_PURE_YAML`` is set to anything but ``""`` or ``0`` (for debugging and
for comparing the two). Both give the same trees, plain data, positions and declines.

Either loop can also build the plain data alone (``positions=False``: no node, no Span, no
key position), which is how the loader reads every file first (``loader.load_reported``):
positions serve only to report problems, and a clean file has none. It declines in exactly
the same cases, so a file with anything to report is read again, with positions.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from typing import Any, Final, TypeAlias

import yaml

from rosreconf.formats.yamltree import (
    MAX_DEPTH,
    Plain,
    Scalar,
    YMapping,
    YNode,
    YScalar,
    YSequence,
    resolve_plain,
)
from rosreconf.model import Span


class Declined:
    """The type of ``DECLINED``."""


DECLINED: Final = Declined()
"""What ``fast_read`` returns for a file that the pure reader must read."""

_BLOCK_HEADER_THEN_COMMENT = re.compile(r"[|>](?:[-+][1-9]?|[1-9][-+]?)?#")
"""A block scalar header with a ``#`` right after it: libyaml reads a comment, PyYAML an error."""


PURE_ENV: Final = "ROSRECONF_PURE_YAML"
"""Set to anything but ``""`` or ``0``: read with the Python loop, not the compiled one."""

CompiledRead: TypeAlias = Callable[..., "tuple[YNode | None, Plain] | None"]
"""``_yamlc.read``'s type (see its stub): the tree and plain data, or None where it declines."""


def _compiled_read() -> CompiledRead | None:
    """Return the compiled loop's ``read``, or None when not built or not wanted.

    Read once at import: the choice is a property of the installation (and of the
    environment a process starts with), not of each file.
    """
    if os.environ.get(PURE_ENV, "") not in ("", "0"):
        return None
    try:
        from rosreconf.formats import _yamlc
    except ImportError:  # installed without a C compiler or libyaml's headers
        return None
    return _yamlc.read


COMPILED_READ: CompiledRead | None = _compiled_read()
"""The C loop (``_yamlc.read``) that ``fast_read`` uses, or None for the Python loop."""


_ASCII_READABLE = b"\n\r" + bytes(range(0x20, 0x7F))
"""The ASCII characters both parsers read alike: line breaks and the printable ones (no tab)."""


def fast_path_safe(text: str) -> bool:
    """Tell whether the text alone lets libyaml read it as PyYAML's pure parser would.

    Most files are ASCII: for them one pass over the bytes, deleting the readable ones,
    tells the same as the three searches (a tab, a byte order mark, a character PyYAML's
    reader refuses), several times faster than the regular expression.
    """
    if text.isascii():
        return not text.encode("ascii").translate(None, _ASCII_READABLE)
    return (
        "\t" not in text
        and "\ufeff" not in text
        and not yaml.reader.Reader.NON_PRINTABLE.search(text)
    )


def fast_read(
    text: str, file: str, loader: type[yaml.CSafeLoader], *, positions: bool = True
) -> tuple[YNode | None, Plain] | Declined:
    """Return the tree and its plain data for ``text``, or ``DECLINED`` (see the module doc).

    With ``positions=False`` the tree is None and only the plain data is built (no node, no
    Span): positions serve only to report problems, and a clean file has none. The declines
    are the same either way.

    The cyclic garbage collector must be paused by the caller for speed: the tree only grows
    here, and every collection would walk all of it.
    """
    if not fast_path_safe(text):
        return DECLINED
    if COMPILED_READ is not None:
        types = (Span, YScalar, YMapping, YSequence) if positions else (None, None, None, None)
        read = COMPILED_READ(
            text,
            file,
            MAX_DEPTH,
            *types,
            resolve_plain,
            _BLOCK_HEADER_THEN_COMMENT.match,
        )
        return DECLINED if read is None else read
    parser = loader(text)
    try:
        return _events(parser.get_event, file, len(text), text, positions)
    except yaml.YAMLError:
        return DECLINED  # libyaml's own syntax error: the pure reader gives the message
    finally:
        parser.dispose()


def _events(
    get: Any, file: str, end: int, text: str, positions: bool = True
) -> tuple[YNode | None, Plain] | Declined:
    """Consume libyaml's events from ``get`` into a tree and plain data; one flat loop.

    The open collection's containers live in local variables (saved on ``stack`` while a
    child is open), and a mapping key becomes no node at all, only its text and position:
    this loop runs once per event, 380,000 times for a thousand-role library. Without
    ``positions`` no node and no Span is made: ``items`` and ``spans`` stay None and the
    plain containers alone are filled (the tree returned is None).
    """
    scalar_event, alias_event = yaml.ScalarEvent, yaml.AliasEvent
    map_start, seq_start = yaml.MappingStartEvent, yaml.SequenceStartEvent
    map_end, seq_end = yaml.MappingEndEvent, yaml.SequenceEndEvent
    doc_start, stream_end = yaml.DocumentStartEvent, yaml.StreamEndEvent
    header_comment = _BLOCK_HEADER_THEN_COMMENT.match
    new_span = tuple.__new__
    resolved: dict[str, Scalar] = {}
    root: YNode | None = None
    root_plain: Plain = None
    stack: list[tuple[Any, ...]] = []  # the enclosing collections' state, innermost last
    # The open collection: a mapping's items, key positions and plain dict, or a sequence's
    # items and plain list (spans None); the key read and waiting for its value.
    items: Any = None
    spans: dict[str, Span] | None = None
    plains: Any = None
    mapping = False  # the open collection is a mapping (else a sequence, or none at the top)
    key: str | None = None
    key_span: Span | None = None
    flow = 0  # depth of flow collections; nothing inside one can be a block collection
    documents = 0
    while True:
        event = get()
        cls = type(event)
        node: YNode
        plain: Plain
        if cls is scalar_event:  # most events: the exact type is the cheapest test
            if event.anchor is not None or event.tag is not None:
                return DECLINED
            mark = event.start_mark
            value = event.value
            style = event.style
            if not style:  # plain: "" from libyaml
                if flow and (not value or "?" in value):
                    return DECLINED
                if not value and mark.index >= end:
                    return DECLINED
            elif (style == "|" or style == ">") and header_comment(text, mark.index):
                return DECLINED
            span: Any = (
                new_span(Span, (file, mark.line + 1, mark.column + 1)) if positions else None
            )
            if mapping and key is None:  # a mapping's key: its text, as written
                key, key_span = value, span
                continue
            if not style and event.implicit[0]:
                if value in resolved:
                    plain = resolved[value]
                else:
                    plain = resolved[value] = resolve_plain(value)
                if positions:
                    node = YScalar(span, plain, value, True)
            else:
                plain = value
                if positions:
                    node = YScalar(span, value, value, False)
        elif cls is map_start or cls is seq_start:
            if event.anchor is not None or event.tag is not None or len(stack) >= MAX_DEPTH:
                return DECLINED
            if mapping and key is None:
                return DECLINED  # a complex key
            if flow or event.flow_style:
                flow += 1
            plain = {} if cls is map_start else []
            if positions:
                mark = event.start_mark
                span = new_span(Span, (file, mark.line + 1, mark.column + 1))
                node = YMapping(span) if cls is map_start else YSequence(span)
        elif cls is map_end or cls is seq_end:
            items, spans, plains, mapping, key, key_span = stack.pop()
            if flow:
                flow -= 1
            continue
        elif cls is doc_start:
            documents += 1
            if documents > 1:
                return DECLINED
            continue
        elif cls is stream_end:
            return root, root_plain
        elif cls is alias_event:
            return DECLINED
        else:
            continue  # stream start and document end
        if mapping:  # a value in a mapping
            assert key is not None
            if key in plains:
                return DECLINED  # a duplicate key
            if positions:
                assert spans is not None and key_span is not None
                items[key] = node
                spans[key] = key_span
            plains[key] = plain
            key = None
        elif plains is not None:  # an item in a sequence
            if positions:
                items.append(node)
            plains.append(plain)
        else:
            root_plain = plain
            if positions:
                root = node
        if cls is not scalar_event:  # a collection opens: its children come next
            stack.append((items, spans, plains, mapping, key, key_span))
            mapping, plains = cls is map_start, plain
            if not positions:
                items = spans = None
            elif type(node) is YMapping:
                items, spans = node.items, node.key_spans
            else:
                assert isinstance(node, YSequence)
                items, spans = node.items, None
            key = key_span = None
