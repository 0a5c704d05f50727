"""Where each value of a YAML document is written: a compact side table of its plain data.

``yamlsource.read`` builds a document's plain data (dicts, lists, scalars) straight from
libyaml's event stream and records, per event, only numbers in flat arrays: the start line
and column of every key and value, where its subtree ends, and what it is (plain scalar,
other scalar, mapping, list; for a key, which key). 16 bytes per value instead of a Python
node object and two marks each: reading the largest library rosreconf accepts took 80 times
the file's size in memory with PyYAML's composed tree.

A value is found by walking its path through the table (``Positions.lookup``): a mapping's
keys by name, a list's items by index, each subtree skipped by its end. The plain data,
when kept, gives the values met on the way (for their text as written). The table is read
only when a problem is reported.
"""

from __future__ import annotations

from array import array
from collections.abc import Sequence
from typing import NamedTuple

from rosreconf.formats.nodes import Plain
from rosreconf.model import Span

PLAIN_SCALAR, TEXT_SCALAR, MAPPING, SEQUENCE = 0, 1, 2, 3
"""What an event is (the low two bits of its tag in ``Positions``): a plain scalar (resolved
with YAML 1.2), a quoted, block or ``!!str`` scalar (a string as written), a mapping, a list."""

_MANY = 32
"""Collections with more children than this keep their children's indices once looked up
(a library's component list is walked again for each problem it has)."""


class Place(NamedTuple):
    """One value of a document: its event's index in the table (``event``), its plain value."""

    event: int
    value: Plain


class Positions:
    """The positions of one document's values, by event index (see the module docstring).

    Each event's ``tags`` entry is its kind (``PLAIN_SCALAR``...) in the low two bits and,
    for a mapping key, the key's number in ``names`` above them (0 for no key): keys are
    found by name without the plain data, so a library's table can outlive it
    (``without_plain``) and place its components' problems with no second reading.

    Attributes:
        file: the file name every span carries.
        plain: the document's plain data (None once dropped): the values of places.
    """

    __slots__ = ("_cols", "_ends", "_kids", "_lines", "_names", "_tags", "_texts", "file", "plain")

    def __init__(
        self,
        file: str,
        plain: Plain,
        table: tuple[array[int], array[int], array[int], array[int]],
        names: list[str],
        texts: dict[int, str],
    ) -> None:
        self.file, self.plain = file, plain
        self._lines, self._cols, self._ends, self._tags = table
        self._names = names
        self._texts = texts  # scalars whose text is not their value's own spelling
        self._kids: dict[int, dict[str | int, int]] = {}

    def without_plain(self) -> Positions:
        """Return the same table without the plain data (spans only: no ``text``)."""
        table = (self._lines, self._cols, self._ends, self._tags)
        return Positions(self.file, None, table, self._names, self._texts)

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
        return self._tags[place.event] & 3

    def text(self, place: Place) -> str:
        """Return a scalar as the user wrote it ("" for a collection)."""
        if self._tags[place.event] & 3 >= MAPPING:
            return ""
        found = self._texts.get(place.event)
        return found if found is not None else spelling(place.value)

    def _children(self, i: int) -> dict[str | int, int]:
        """Return a collection's items' event indices by index, or its keys' by name."""
        found = self._kids.get(i)
        if found is not None:
            return found
        ends, tags, names = self._ends, self._tags, self._names
        out: dict[str | int, int] = {}
        k, end = i + 1, ends[i]
        if tags[i] & 3 == MAPPING:
            while k < end:
                out.setdefault(names[tags[k] >> 2], k)
                k = ends[ends[k]]  # past the key's value
        else:
            while k < end:
                out[len(out)] = k
                k = ends[k]
        if len(out) > _MANY:
            self._kids[i] = out
        return out

    def fields(self, place: Place) -> dict[str, Place]:
        """Return a mapping's values by key (nothing for anything else)."""
        if self._tags[place.event] & 3 != MAPPING:
            return {}
        value = place.value
        get = value.get if type(value) is dict else _NOTHING.get
        keys = self._children(place.event)
        return {k: Place(at + 1, get(k)) for k, at in keys.items() if type(k) is str}

    def items(self, place: Place | None) -> list[Place]:
        """Return a list's items (nothing for anything else, which the JSON Schema refused)."""
        if place is None or self._tags[place.event] & 3 != SEQUENCE:
            return []
        value = place.value if type(place.value) is list else None
        at = self._children(place.event).values()
        return [Place(e, value[i] if value else None) for i, e in enumerate(at)]

    def _step(self, place: Place, step: str | int) -> tuple[Place, int] | None:
        """Return the value one ``step`` (key or index) under ``place``, and its key's index."""
        i, value = place
        kind = self._tags[i] & 3
        if kind == MAPPING and isinstance(step, str):
            at = self._children(i).get(step)
            if at is None:
                return None
            return Place(at + 1, value.get(step) if type(value) is dict else None), at
        if kind == SEQUENCE and isinstance(step, int) and step >= 0:
            at = self._children(i).get(step)
            if at is None:
                return None
            return Place(at, value[step] if type(value) is list else None), -1
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

    def find(self, path: Sequence[str | int]) -> Place | None:
        """Return the value at ``path``, or None when the document has no value there."""
        cur = self.root
        for step in path:
            found = self._step(cur, step)
            if found is None:
                return None
            cur = found[0]
        return cur

    def key_span(self, path: Sequence[str | int]) -> Span | None:
        """Return where the last key of ``path`` is written, when ``path`` ends in a key."""
        if not path or not isinstance(path[-1], str):
            return None
        found = self._step(self.lookup(path[:-1]), path[-1])
        return self.span(found[1]) if found is not None else None


_NOTHING: dict[str, Plain] = {}


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
