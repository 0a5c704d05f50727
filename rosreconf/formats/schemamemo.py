"""Remember which parts of a document the fast JSON Schema validator found valid.

A large library writes the same few interfaces and requirements thousands of times (1000
roles x 10 candidates: 28,505 interfaces and 12,040 requirements, about 2,000 of them
distinct), and fastjsonschema's code checks every one again; a requirement with ``any_of``
even raises and catches three exceptions on its way through the ``anyOf``. A verdict
depends only on the content checked, so ``remember_valid`` wraps a ``$defs`` validator to
check each distinct content once. The shipped validator modules install it
(``structure.fast_validator_code``); only valid contents are remembered, so every error is
still raised by fastjsonschema's own code, on the first and on every later occurrence.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any

MAX_REMEMBERED = 100_000
"""Most contents remembered per ``$defs`` validator; more forget all (a long-lived ``watch``
process reads its files again and again, and must not grow without bound)."""


def content_key(value: Any) -> Hashable:
    """Return a hashable key equal for two values exactly when they are the same content.

    Types are part of the key (``True``, ``1``, ``1.0`` and ``"1"`` are four contents to a
    JSON Schema, though Python calls the first three equal), and so is the order of a
    mapping's keys (harmless: an equal mapping in another order is merely checked again).

    Raises:
        TypeError: ``value`` holds something no YAML reader makes (a mapping key that is not
            a string, an unhashable object): such a value is checked, never remembered.
    """
    kind = type(value)
    if kind is str:
        text: str = value
        return text
    if kind is dict:
        items = []
        for key, item in value.items():
            if type(key) is not str:
                raise TypeError(f"mapping key {key!r} is not a string")
            items.append((key, item if type(item) is str else content_key(item)))
        return (dict, tuple(items))
    if kind is list:
        return (list, tuple([i if type(i) is str else content_key(i) for i in value]))
    hash(value)
    return (kind, value)


def remember_valid(validate: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap a fastjsonschema ``$defs`` validator so that each valid content is checked once.

    The wrapper takes the generated function's arguments (data, custom formats, name prefix)
    and returns the data as it does; a content not seen valid before goes through
    ``validate``, which raises for invalid data exactly as without the wrapper.
    """
    valid: set[Hashable] = set()

    def remembering(data: Any, *rest: Any) -> Any:
        try:
            key = content_key(data)
            if key in valid:
                return data
        except TypeError:
            return validate(data, *rest)
        validate(data, *rest)
        if len(valid) >= MAX_REMEMBERED:
            valid.clear()
        valid.add(key)
        return data

    return remembering
