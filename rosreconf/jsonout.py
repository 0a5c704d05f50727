"""Write JSON the one way rosreconf allows: never NaN or Infinity, integers of any size exact.

``json.dumps`` writes ``NaN`` and ``Infinity`` by default, which are not JSON: a consumer's
parser (``jq``, JavaScript's ``JSON.parse``, a JSON Schema validator) then rejects the whole
document. Every JSON document rosreconf prints or writes goes through ``dumps`` here, with
``allow_nan=False``; input that could carry such a number is refused by ``validate`` first, so
reaching the error below is a bug, not a user mistake.

Counts are exact integers of any size (a 10,000-role library has counts of thousands of
digits). They are written as JSON integers, digit for digit: valid JSON, read exactly by
Python's ``json`` and by any parser with big-integer support; a consumer limited to doubles
(JavaScript) must read them as big integers or text. Python refuses to turn an int of more than
4,300 digits into text unless told otherwise, so ``allow_big_ints`` lifts that limit for the
process (the CLI calls it once at start).
"""

from __future__ import annotations

import json
import sys
from typing import Any


def dumps(doc: Any, *, indent: int | None = None) -> str:
    """Return ``doc`` as JSON text; raise ``ValueError`` on NaN or Infinity (never written)."""
    allow_big_ints()
    return json.dumps(doc, indent=indent, allow_nan=False)


def allow_big_ints() -> None:
    """Let ``str(int)`` print integers of any size (counts, in text and JSON output)."""
    if hasattr(sys, "set_int_max_str_digits") and sys.get_int_max_str_digits() != 0:
        sys.set_int_max_str_digits(0)
