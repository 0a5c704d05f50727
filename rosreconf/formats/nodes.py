"""Read the positioned tree: where a value is, its text as written, its YAML 1.2 value.

``yamlsource.read`` composes each file into PyYAML's nodes, each with its start mark. A
scalar keeps its text as written (names are never turned into numbers); a plain one
resolves with YAML 1.2's core schema (``resolve_plain``: ``no``, ``on``, ``yes`` stay text).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import TypeAlias

from yaml.nodes import MappingNode as MappingNode
from yaml.nodes import Node as Node
from yaml.nodes import ScalarNode as ScalarNode
from yaml.nodes import SequenceNode as SequenceNode

from rosreconf.model import Span

Scalar: TypeAlias = str | int | float | bool | None
Plain: TypeAlias = "Scalar | dict[str, Plain] | list[Plain]"

NUMBER = (int, float)
"""A tuple for isinstance: ``int | float`` in a test builds a union each time it runs."""


_new_span = tuple.__new__


def span(node: Node | None) -> Span:
    """Return where ``node`` starts (its mark carries the file name ``yamlsource.read`` gave)."""
    mark = node.start_mark  # type: ignore[union-attr]  # a present node: None has no span
    return _new_span(Span, (mark.name, mark.line + 1, mark.column + 1))


def path_text(path: Sequence[str | int]) -> str:
    """Return a path of keys and indices as messages write it: ``components[0].dynamics``."""
    return "".join(f"[{s}]" if isinstance(s, int) else f".{s}" for s in path).lstrip(".")


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
    """Return a mapping's values by key text, as ``yamlsource.read`` recorded them."""
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


def text_of(node: Node | None) -> str:
    """Return a scalar as the text the user wrote ("" for anything else)."""
    return node.value if type(node) is ScalarNode else ""


def seq_of(node: Node | None) -> list[Node]:
    """Return a sequence's items (none for anything else, which the JSON Schema refused)."""
    return node.value if type(node) is SequenceNode else []


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
