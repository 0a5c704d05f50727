"""Where a context variable's value changes a task's count of configurations.

A designer asks of ``visibility``: below what value does the pipeline inspection lose a
configuration, and below what value has it none? The bounds of the library's conditions on
the variable are the only places its answer can change: they split the number line into
points and open intervals, on each of which every condition on it holds or fails throughout.
So one count per piece (a value inside it), with adjacent pieces of equal count joined, is
the whole answer. The other variables stay at their ``--context`` values where given and are
otherwise unconstrained (conditions on them taken to hold): the table then shows what this
variable alone can do. A boolean or string variable (``equals``) has one row per value its
conditions name, and for strings one more for any other value.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass

from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.context import ContextValue, rule_out
from rosreconf.solve.listing import Listing


@dataclass(frozen=True)
class Interval:
    """A stretch of a numeric variable's values with one count of configurations.

    Attributes:
        low: where it starts (None: minus infinity).
        low_closed: whether ``low`` itself is in it.
        high: where it ends (None: plus infinity).
        high_closed: whether ``high`` itself is in it.
        configurations: the count of valid configurations throughout.
    """

    low: float | None
    low_closed: bool
    high: float | None
    high_closed: bool
    configurations: int

    def inside(self) -> float:
        """Return a value inside (every condition holds or fails alike throughout)."""
        if self.low is None and self.high is None:
            return 0.0
        if self.low is None:
            assert self.high is not None
            return self.high - 1.0
        if self.high is None:
            return self.low + 1.0
        return self.low if self.low_closed else (self.low + self.high) / 2


@dataclass(frozen=True)
class Value:
    """A boolean or string variable's value (None: any value no condition names)."""

    value: bool | str | None
    configurations: int


@dataclass(frozen=True)
class Thresholds:
    """One variable's table for one schema.

    Attributes:
        schema: the schema's name.
        variable: the context variable.
        given: the other variables' values held (the rest unconstrained).
        intervals: a number's pieces in increasing order, adjacent ones of equal count joined.
        values: a boolean or string variable's rows instead.
    """

    schema: str
    variable: str
    given: Mapping[str, ContextValue]
    intervals: tuple[Interval, ...] = ()
    values: tuple[Value, ...] = ()


def thresholds(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    variable: str,
    given: Mapping[str, ContextValue],
    failed: Collection[str] = (),
) -> Thresholds:
    """Return ``variable``'s table for ``schema``: counts per piece of its values.

    ``given`` holds the other variables' values (``variable``'s own, if any, is replaced);
    ``failed`` are the ``--fail`` components, gone throughout.
    """
    others = {k: v for k, v in given.items() if k != variable}
    conditions = [w for c in library for w in c.when if w.name == variable]

    def count(value: ContextValue) -> int:
        out = rule_out(library, {**others, variable: value})
        gone = {*failed, *(r.component for r in out)}
        return Listing(library, schema, gone, count_only=True).total or 0

    equals = [w.equals for w in conditions if w.equals is not None]
    if equals:
        named: list[bool | str | None] = list(dict.fromkeys(equals))
        if isinstance(named[0], bool):
            named = [True, False]
        else:
            named.append(None)
        rows = tuple(Value(v, count(v if v is not None else _other(named))) for v in named)
        return Thresholds(schema.name, variable, others, values=rows)
    bounds = sorted({b for w in conditions for b in (w.at_least, w.at_most) if b is not None})
    pieces: list[Interval] = []
    edges: list[float | None] = [None, *bounds, None]
    for i in range(len(edges) - 1):
        low, high = edges[i], edges[i + 1]
        gap = Interval(low, False, high, False, 0)
        pieces.append(Interval(low, False, high, False, count(gap.inside())))
        if high is not None:
            pieces.append(Interval(high, True, high, True, count(high)))
    return Thresholds(schema.name, variable, others, intervals=tuple(_joined(pieces)))


def _other(named: list[bool | str | None]) -> str:
    """Return a string none of the conditions names (``other``, ``other_``...)."""
    text = "other"
    while text in named:
        text += "_"
    return text


def _joined(pieces: list[Interval]) -> list[Interval]:
    """Join adjacent pieces of equal count into one interval."""
    out: list[Interval] = []
    for p in pieces:
        last = out[-1] if out else None
        if last is not None and last.configurations == p.configurations:
            out[-1] = Interval(last.low, last.low_closed, p.high, p.high_closed, p.configurations)
        else:
            out.append(p)
    return out
