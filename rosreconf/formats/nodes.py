"""Read a value of a document in either form the builder gets it: positioned tree or plain data.

``build`` turns a checked document into the model through these few readers, so that it is
written once for both forms (``Node``): a node of the positioned tree (``yamltree``), or a
value of the plain data alone (``yamlsource.parse_plain_only``), which has no position.
Each reader dispatches on the value's type (plain data holds no node, a tree no plain
container), testing the plain form first: it is the one every clean load takes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TypeAlias

from rosreconf.formats import yamlsource as ys
from rosreconf.model import NOWHERE, Span

Node: TypeAlias = "ys.YNode | ys.Plain"
"""What the builder reads: a node of the positioned tree, or a value of the plain data."""


NUMBER = (int, float)
SCALAR = (str, int, float, bool)
"""Tuples for isinstance: ``int | float`` in a test builds a union each time it runs, and
the builder runs some tests 30,000 times for a thousand-role library."""


class NeedsPositions(Exception):
    """Plain data cannot give what the positioned tree would: build from the tree instead."""


def text_of(node: Node) -> str:
    """Return a scalar as the text the user wrote (so names are never turned into numbers).

    A string's plain value is its text as written (quoted or not: ``resolve_plain`` returns
    the text itself for every string); any other plain value is not, so the builder asks
    for the tree rather than guess whether ``1.0`` was written ``1.0`` or ``1.00``.
    """
    if type(node) is str:
        return node
    if isinstance(node, ys.YScalar):
        return node.raw
    if isinstance(node, ys.YNode):
        return ""
    raise NeedsPositions(f"the text of {node!r} as written")


def field_text(items: Mapping[str, Node], key: str, default: str = "") -> str:
    """Return the text of ``items[key]`` as written, or ``default`` when the key is absent."""
    return text_of(items[key]) if key in items else default


def span_of(node: Node) -> Span:
    """Return where ``node`` was written: ``NOWHERE`` for plain data."""
    return node.span if isinstance(node, ys.YNode) else NOWHERE


def value_of(node: Node) -> ys.Plain:
    """Return a scalar's resolved value."""
    return node.value if isinstance(node, ys.YScalar) else node  # type: ignore[return-value]


def seq_of(node: Node) -> Sequence[Node]:
    """Return a sequence's items (none for anything else, which the JSON Schema refused)."""
    if type(node) is list:
        return node
    return node.items if isinstance(node, ys.YSequence) else []


def map_of(node: Node) -> Mapping[str, Node]:
    """Return a mapping's items by key (none for anything else, which the Schema refused)."""
    if type(node) is dict:
        return node
    return node.items if isinstance(node, ys.YMapping) else {}


def scalars_of(node: Node) -> dict[str, object]:
    """Return a (schema-checked) mapping of scalars as plain Python values."""
    collections = (dict, list, ys.YMapping, ys.YSequence)
    return {k: value_of(v) for k, v in map_of(node).items() if not isinstance(v, collections)}
