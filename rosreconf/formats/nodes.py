"""Read a value of the positioned tree as the builder needs it: text, number, items, position.

``build`` turns a checked document into the model through these few readers, over the nodes
``yamlsource.read`` composed (PyYAML's ``ScalarNode``, ``MappingNode`` and ``SequenceNode``,
each with its start mark). The document passed its JSON Schema check first, so a reader
meeting a value of another shape answers empty rather than fail.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TypeAlias

from rosreconf.formats import yamlsource as ys
from rosreconf.model import Span

Node: TypeAlias = "ys.Node | None"
"""What the builder reads: a node of the positioned tree, or None for an absent key."""

NUMBER = (int, float)
SCALAR = (str, int, float, bool)
"""Tuples for isinstance: ``int | float`` in a test builds a union each time it runs, and
the builder runs some tests 30,000 times for a thousand-role library."""


def text_of(node: Node) -> str:
    """Return a scalar as the text the user wrote (so names are never turned into numbers)."""
    return node.value if type(node) is ys.ScalarNode else ""


def field_text(items: Mapping[str, Node], key: str, default: str = "") -> str:
    """Return the text of ``items[key]`` as written, or ``default`` when the key is absent."""
    return text_of(items[key]) if key in items else default


span_of: Callable[[Node], Span] = ys.span  # type: ignore[assignment]
"""Return where a node was written (a present one: ``ys.span`` itself, without a call)."""


def value_of(node: Node) -> ys.Plain:
    """Return a scalar's resolved value (None when absent or not a scalar)."""
    return ys.value(node)


def seq_of(node: Node) -> Sequence[ys.Node]:
    """Return a sequence's items (none for anything else, which the JSON Schema refused)."""
    return node.value if type(node) is ys.SequenceNode else []


def map_of(node: Node) -> Mapping[str, ys.Node]:
    """Return a mapping's items by key (none for anything else, which the Schema refused)."""
    return ys.fields(node)


def scalars_of(node: Node) -> dict[str, object]:
    """Return a (schema-checked) mapping of scalars as plain Python values."""
    return {k: ys.value(v) for k, v in map_of(node).items() if type(v) is ys.ScalarNode}
