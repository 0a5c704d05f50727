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
"""

from __future__ import annotations

import re
from typing import Any, Final

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


def fast_path_safe(text: str) -> bool:
    """Tell whether the text alone lets libyaml read it as PyYAML's pure parser would."""
    return (
        "\t" not in text
        and "\ufeff" not in text
        and not yaml.reader.Reader.NON_PRINTABLE.search(text)
    )


def fast_read(
    text: str, file: str, loader: type[yaml.CSafeLoader]
) -> tuple[YNode | None, Plain] | Declined:
    """Return the tree and its plain data for ``text``, or ``DECLINED`` (see the module doc).

    The cyclic garbage collector must be paused by the caller for speed: the tree only grows
    here, and every collection would walk all of it.
    """
    if not fast_path_safe(text):
        return DECLINED
    parser = loader(text)
    try:
        return _events(parser.get_event, file, len(text), text)
    except yaml.YAMLError:
        return DECLINED  # libyaml's own syntax error: the pure reader gives the message
    finally:
        parser.dispose()


def _events(get: Any, file: str, end: int, text: str) -> tuple[YNode | None, Plain] | Declined:
    """Consume libyaml's events from ``get`` into a tree and plain data; one flat loop."""
    scalar_event, alias_event = yaml.ScalarEvent, yaml.AliasEvent
    map_start, seq_start = yaml.MappingStartEvent, yaml.SequenceStartEvent
    map_end, seq_end = yaml.MappingEndEvent, yaml.SequenceEndEvent
    doc_start, stream_end = yaml.DocumentStartEvent, yaml.StreamEndEvent
    new_span = tuple.__new__
    resolved: dict[str, Scalar] = {}
    root: YNode | None = None
    root_plain: Plain = None
    stack: list[YMapping | YSequence] = []
    plains: list[Any] = []  # the plain dict or list beside each open collection
    keys: list[tuple[str, Span] | None] = []
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
            span = new_span(Span, (file, mark.line + 1, mark.column + 1))
            value = event.value
            style = event.style
            if not style:  # plain: "" from libyaml
                if flow and (not value or "?" in value):
                    return DECLINED
                if not value and mark.index >= end:
                    return DECLINED
            if not style and event.implicit[0]:
                if value in resolved:
                    plain = resolved[value]
                else:
                    plain = resolved[value] = resolve_plain(value)
                node = YScalar(span, plain, value, True)
            else:
                if (style == "|" or style == ">") and _BLOCK_HEADER_THEN_COMMENT.match(
                    text, mark.index
                ):
                    return DECLINED
                plain = value
                node = YScalar(span, value, value, False)
        elif cls is map_start or cls is seq_start:
            if event.anchor is not None or event.tag is not None or len(stack) >= MAX_DEPTH:
                return DECLINED
            if flow or event.flow_style:
                flow += 1
            mark = event.start_mark
            span = new_span(Span, (file, mark.line + 1, mark.column + 1))
            if cls is map_start:
                node, plain = YMapping(span), {}
            else:
                node, plain = YSequence(span), []
        elif cls is map_end or cls is seq_end:
            stack.pop()
            plains.pop()
            keys.pop()
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
        if stack:
            parent = stack[-1]
            if type(parent) is YSequence:
                parent.items.append(node)
                plains[-1].append(plain)
            else:
                assert isinstance(parent, YMapping)
                key = keys[-1]
                if key is None:
                    if type(node) is not YScalar:
                        return DECLINED  # a complex key
                    keys[-1] = (node.raw, node.span)
                    continue
                name, where = key
                if name in parent.items:
                    return DECLINED  # a duplicate key
                parent.items[name] = node
                parent.key_spans[name] = where
                plains[-1][name] = plain
                keys[-1] = None
        else:
            root, root_plain = node, plain
        if type(node) is not YScalar:
            stack.append(node)  # type: ignore[arg-type]
            plains.append(plain)
            keys.append(None)
