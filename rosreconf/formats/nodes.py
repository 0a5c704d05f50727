"""The plain data a YAML document is read into, and YAML 1.2's resolution of plain scalars.

``yamlsource.read`` turns each file into plain data (``Plain``); where each value is written
is kept beside it (``positions``). A plain scalar resolves with YAML 1.2's core schema
(``resolve_plain``: ``no``, ``on``, ``yes`` stay text); a quoted one is its text.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import TypeAlias

Scalar: TypeAlias = str | int | float | bool | None
Plain: TypeAlias = "Scalar | dict[str, Plain] | list[Plain]"

NUMBER = (int, float)
"""A tuple for isinstance: ``int | float`` in a test builds a union each time it runs."""


def path_text(path: Sequence[str | int]) -> str:
    """Return a path of keys and indices as messages write it: ``components[0].dynamics``."""
    return "".join(f"[{s}]" if isinstance(s, int) else f".{s}" for s in path).lstrip(".")


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
