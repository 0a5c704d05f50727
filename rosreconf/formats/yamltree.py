"""The positioned tree rosreconf reads YAML into, and the YAML 1.2 core schema it resolves.

Both readers build this tree: the fast one over libyaml's events (``yamlfast``) and the one
that reports problems over PyYAML's pure parser (``yamlbuilder``); ``yamlsource.parse``
chooses between them. Every node keeps where it was written, so that every problem found
later (structure, values, semantics) can name ``file:line:column``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import TypeAlias

from rosreconf.model import Span

MAX_DEPTH = 32
"""Deepest nesting accepted; rosreconf's formats need 6 levels."""

Scalar: TypeAlias = str | int | float | bool | None
Plain: TypeAlias = "Scalar | dict[str, Plain] | list[Plain]"

STR_TAGS = {"tag:yaml.org,2002:str", "!"}
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
