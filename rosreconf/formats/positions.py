"""Where each value of a YAML document is written: a compact side table of its plain data.

``yamlsource.read`` builds a document's plain data (dicts, lists, scalars) straight from
libyaml's event stream and records, per event, only numbers: the start line and column of
every key and value, where its subtree ends, and what it is (plain scalar, other scalar,
mapping, list). A few bytes per value instead of a Python node object and two marks each:
reading the largest library rosreconf accepts took 80 times the file's size in memory with
PyYAML's composed tree.

A value is found by walking its path through the plain data and the table side by side
(``Positions.lookup``): the events are in document order, so a mapping's n-th key is the
n-th key event under it. The table is read only when a problem is reported.
"""

from __future__ import annotations

from array import array
from collections.abc import Sequence
from typing import NamedTuple

from rosreconf.formats.nodes import Plain
from rosreconf.model import Span

PLAIN_SCALAR, TEXT_SCALAR, MAPPING, SEQUENCE = 0, 1, 2, 3
"""What an event is (``Positions.kinds``): a plain scalar (resolved with YAML 1.2), a quoted,
block or ``!!str`` scalar (a string as written), a mapping, a list."""

_MANY = 32
"""Collections with more children than this keep their children's indices once looked up
(a library's component list is walked again for each problem it has)."""


class Place(NamedTuple):
    """One value of a document: its event's index in the table (``event``), its plain value."""

    event: int
    value: Plain


class Positions:
    """The positions of one document's values, by event index (see the module docstring).

    Attributes:
        file: the file name every span carries.
        plain: the document's plain data, which ``lookup`` walks beside the table.
    """

    __slots__ = ("_cols", "_ends", "_kids", "_kinds", "_lines", "_texts", "file", "plain")

    def __init__(
        self,
        file: str,
        plain: Plain,
        lines: array[int],
        cols: array[int],
        ends: array[int],
        kinds: bytearray,
        texts: dict[int, str],
    ) -> None:
        self.file, self.plain = file, plain
        self._lines, self._cols, self._ends, self._kinds = lines, cols, ends, kinds
        self._texts = texts  # scalars whose text is not their value's own spelling
        self._kids: dict[int, list[int]] = {}

    @property
    def root(self) -> Place:
        """Return the document's top value."""
        return Place(0, self.plain)

    def span(self, place: Place | int) -> Span:
        """Return where a value (or a key, by its index) starts, 1-based."""
        i = place if isinstance(place, int) else place.event
        return Span(self.file, self._lines[i] + 1, self._cols[i] + 1)

    def kind(self, place: Place) -> int:
        """Return what the value is: ``PLAIN_SCALAR``, ``TEXT_SCALAR``, ``MAPPING``..."""
        return self._kinds[place.event]

    def text(self, place: Place) -> str:
        """Return a scalar as the user wrote it ("" for a collection)."""
        if self._kinds[place.event] >= MAPPING:
            return ""
        found = self._texts.get(place.event)
        return found if found is not None else spelling(place.value)

    def _children(self, i: int) -> list[int]:
        """Return the event indices of a collection's items, or of a mapping's keys."""
        found = self._kids.get(i)
        if found is not None:
            return found
        ends, out = self._ends, []
        mapping = self._kinds[i] == MAPPING
        k, end = i + 1, ends[i]
        while k < end:
            out.append(k)
            k = ends[ends[k]] if mapping else ends[k]  # past a key's value
        if len(out) > _MANY:
            self._kids[i] = out
        return out

    def fields(self, place: Place) -> dict[str, Place]:
        """Return a mapping's values by key (nothing for anything else)."""
        if self._kinds[place.event] != MAPPING or type(place.value) is not dict:
            return {}
        keys = self._children(place.event)
        return {k: Place(at + 1, v) for (k, v), at in zip(place.value.items(), keys, strict=True)}

    def items(self, place: Place | None) -> list[Place]:
        """Return a list's items (nothing for anything else, which the JSON Schema refused)."""
        if place is None or self._kinds[place.event] != SEQUENCE or type(place.value) is not list:
            return []
        at = self._children(place.event)
        return [Place(i, v) for i, v in zip(at, place.value, strict=True)]

    def _step(self, place: Place, step: str | int) -> tuple[Place, int] | None:
        """Return the value one ``step`` (key or index) under ``place``, and its key's index."""
        i, value = place
        kind = self._kinds[i]
        if kind == MAPPING and type(value) is dict and isinstance(step, str) and step in value:
            keys = self._children(i)
            at = keys[0] if len(keys) == 1 else keys[list(value).index(step)]
            return Place(at + 1, value[step]), at
        listed = kind == SEQUENCE and type(value) is list
        if listed and isinstance(step, int) and 0 <= step < len(value):  # type: ignore[arg-type]
            return Place(self._children(i)[step], value[step]), -1  # type: ignore[index]
        return None

    def lookup(self, path: Sequence[str | int]) -> Place:
        """Return the value at ``path`` (keys and indices), or the deepest one that exists."""
        cur = self.root
        for step in path:
            found = self._step(cur, step)
            if found is None:
                break
            cur = found[0]
        return cur

    def key_span(self, path: Sequence[str | int]) -> Span | None:
        """Return where the last key of ``path`` is written, when ``path`` ends in a key."""
        if not path or not isinstance(path[-1], str):
            return None
        found = self._step(self.lookup(path[:-1]), path[-1])
        return self.span(found[1]) if found is not None else None


def spelling(value: Plain) -> str:
    """Return the text a scalar ``value`` is read from when written in its usual spelling.

    ``yamlsource.read`` records the text of a scalar only when it is written otherwise
    (``0.50``, ``1e3``, ``~``): most numbers of a library are written this way, and need
    no copy of their text.
    """
    if type(value) is str:
        return value
    if value is None:
        return ""
    if value is True:
        return "true"
    if value is False:
        return "false"
    return repr(value)
