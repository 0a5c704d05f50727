"""Context: what the robot measures, and the conditions on it under which a component is usable.

A library may declare context variables (``context:``, each read from one field of one
topic's messages), and a component may be usable only while conditions on them hold
(``when:``). SUAVE's search paths are the example: the path flown at 3 m is usable only
while the water visibility is at least 3.25. At design time the values are given
(``--context visibility=2.0``) and a component whose conditions fail is ruled out, exactly
as a failed one is: so the solvers need nothing new, only a longer failed set, and every
report can say why from ``RuledOut.reason``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Protocol

from rosreconf.model.span import NOWHERE, Span

ContextValue = float | bool | str
"""A context value: a number (bounds), or a boolean or string (``equals``)."""


@dataclass(frozen=True)
class ContextVariable:
    """One thing the robot measures: a named field of one topic's messages.

    Attributes:
        name: the name conditions use (``visibility``).
        topic: the topic it is read from (``/water_visibility``).
        type: the topic's message type as written (``std_msgs/msg/Float64``).
        field: the field of that message holding the value; nested fields as ``a.b``.
        span: where it was declared.
        field_span: where its field was written (for a field its type does not have).
    """

    name: str
    topic: str
    type: str
    field: str
    span: Span = dataclasses.field(default=NOWHERE, compare=False)
    field_span: Span = dataclasses.field(default=NOWHERE, compare=False)


@dataclass(frozen=True)
class Condition:
    """One condition of a component's ``when``: bounds on a number, or a value to equal.

    Every condition of a component must hold for it to be usable. ``at_least`` and
    ``at_most`` are inclusive, so ``{at_least: 3.25}`` holds at 3.25 itself.

    Attributes:
        name: the context variable it is on.
        at_least: the least value allowed, if any.
        at_most: the greatest value allowed, if any.
        equals: the one value allowed (a boolean or string context), if any.
        span: where it was written.
    """

    name: str
    at_least: float | None = None
    at_most: float | None = None
    equals: bool | str | None = None
    span: Span = dataclasses.field(default=NOWHERE, compare=False)

    @property
    def numeric(self) -> bool:
        """Tell whether this condition bounds a number (rather than asking for equality)."""
        return self.equals is None

    def holds(self, value: ContextValue) -> bool:
        """Tell whether ``value`` satisfies this condition (a number against bounds)."""
        if not self.numeric:
            return value == self.equals and type(value) is type(self.equals)
        if isinstance(value, bool) or not isinstance(value, int | float):
            return False
        low = self.at_least is None or value >= self.at_least
        return low and (self.at_most is None or value <= self.at_most)

    def __str__(self) -> str:
        if not self.numeric:
            return f"{self.name} = {show(self.equals)}"
        if self.at_least is not None and self.at_most is not None:
            return f"{show(self.at_least)} <= {self.name} <= {show(self.at_most)}"
        if self.at_least is not None:
            return f"{self.name} >= {show(self.at_least)}"
        if self.at_most is not None:
            return f"{self.name} <= {show(self.at_most)}"
        return f"{self.name} (any value)"


def show(value: ContextValue | None) -> str:
    """Write a context value or bound as reports show it (``2.0``, ``true``, ``clear``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float | int):
        return repr(float(value)) if math.isfinite(value) else str(value)
    return str(value)


class Conditioned(Protocol):
    """What ``rule_out`` reads of a component (``model.library.Component``, which imports this)."""

    @property
    def name(self) -> str: ...

    @property
    def when(self) -> tuple[Condition, ...]: ...


@dataclass(frozen=True)
class RuledOut:
    """A component that context rules out, and why (in the paper's plain style).

    Attributes:
        component: its name.
        failing: the conditions that do not hold.
        reason: ``spiral_high needs visibility >= 3.25; it is 2.0``.
    """

    component: str
    failing: tuple[Condition, ...]
    reason: str


def rule_out(
    components: Iterable[Conditioned], values: Mapping[str, ContextValue]
) -> tuple[RuledOut, ...]:
    """Return the components some of whose conditions fail under ``values``, in order.

    A condition on a name ``values`` does not give is taken to hold: callers that must
    refuse one first ask ``unset`` (``formats.selection`` does, unless told to ignore it).
    """
    out = []
    for c in components:
        failing = tuple(w for w in c.when if w.name in values and not w.holds(values[w.name]))
        if failing:
            out.append(RuledOut(c.name, failing, _reason(c.name, failing, values)))
    return tuple(out)


def unset(components: Iterable[Conditioned], values: Mapping[str, ContextValue]) -> dict[str, str]:
    """Return each context name some condition uses but ``values`` does not give.

    Mapped to the first component whose condition uses it, for the error message.
    """
    missing: dict[str, str] = {}
    for c in components:
        for w in c.when:
            if w.name not in values:
                missing.setdefault(w.name, c.name)
    return missing


def _reason(name: str, failing: tuple[Condition, ...], values: Mapping[str, ContextValue]) -> str:
    if len(failing) == 1:
        return f"{name} needs {failing[0]}; it is {show(values[failing[0].name])}"
    parts = [f"{w} (it is {show(values[w.name])})" for w in failing]
    return f"{name} needs " + " and ".join(parts)
