"""Where a value was written (``Span``): shared by the library, its context and the schemas."""

from __future__ import annotations

from typing import NamedTuple


class Span(NamedTuple):
    """Where a value was written: file, 1-based line and column.

    A NamedTuple rather than a dataclass: a large library creates one per YAML event
    (hundreds of thousands), and tuples are several times cheaper to build; they are just as
    immutable, ordered and hashable.

    Attributes:
        file: the path as the user gave it (or a bundled resource name).
        line: 1-based line number.
        column: 1-based column number.
    """

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


NOWHERE = Span("<model>", 0, 0)
"""The span of values built in code rather than read from a file."""
