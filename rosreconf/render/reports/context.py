"""Say what context a command ran under: the values, the components ruled out, and why.

Every report of a command that applies ``--context`` (enumerate, analyse, plan, simulate,
whatif) says it the same way: a short block before the text report, and one ``context``
member of the JSON document (``context_doc``, the ``context`` definition every output
schema shares). Libraries without context get neither, so their reports are unchanged.
``analyse`` adds its threshold tables (``analysis.thresholds``) to both.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rosreconf.analysis.thresholds import Interval, Thresholds
from rosreconf.formats.selection import Selection
from rosreconf.model.context import show
from rosreconf.planning.narrative import ruled_out_wording


def context_doc(sel: Selection) -> dict[str, Any] | None:
    """Return the JSON ``context`` member, or None when the library uses no context."""
    if not sel.has_context:
        return None
    return {
        "values": {name: value for name, value in sel.context.items()},
        "ruled_out": [
            {
                "component": r.component,
                "conditions": [str(w) for w in r.failing],
                "reason": r.reason,
            }
            for r in sel.ruled_out
        ],
        "ignored": list(sel.ignored),
    }


def context_text(sel: Selection) -> str:
    """Return the text block (ends with a blank line), or "" when the library uses no context."""
    if not sel.has_context:
        return ""
    given = ", ".join(f"{name} = {show(value)}" for name, value in sel.context.items())
    lines = [f"context: {given or 'none given'}"]
    lines += [f"  ruled out: {r.reason}" for r in sel.ruled_out]
    if sel.ignored:
        lines.append(f"  conditions taken to hold (--ignore-context): {', '.join(sel.ignored)}")
    if not sel.ruled_out:
        lines.append("  ruled out: nothing")
    return "\n".join(lines) + "\n\n"


def reworded(lines: Sequence[str], sel: Selection) -> list[str]:
    """Return the planner's explanation with a ruled-out component's reason for "failed"
    (``planning.narrative.ruled_out_wording``)."""
    return ruled_out_wording(lines, {r.component: r.reason for r in sel.ruled_out})


def thresholds_text(tables: Sequence[Thresholds]) -> str:
    """Return the analyse tables: per schema and variable, each interval and its count."""
    if not tables:
        return ""
    lines = ["context thresholds (counts of configurations; other context values as given by"]
    lines.append("--context, else unconstrained):")
    for t in tables:
        held = ", ".join(f"{k} = {show(v)}" for k, v in t.given.items())
        lines.append(f"  {t.schema}, by {t.variable}" + (f" ({held})" if held else "") + ":")
        rows = [(interval_text(t.variable, i), i.configurations) for i in t.intervals]
        rows += [(_value_text(t.variable, v.value), v.configurations) for v in t.values]
        width = max(len(r[0]) for r in rows)
        lines += [f"    {text:<{width}}  {n}" for text, n in rows]
    return "\n".join(lines) + "\n\n"


def thresholds_doc(tables: Sequence[Thresholds]) -> list[dict[str, Any]]:
    """Return the analyse tables as the JSON ``context.thresholds`` member."""
    return [
        {
            "schema": t.schema,
            "variable": t.variable,
            "given": dict(t.given),
            "intervals": [
                {
                    "from": i.low,
                    "from_included": i.low_closed,
                    "to": i.high,
                    "to_included": i.high_closed,
                    "text": interval_text(t.variable, i),
                    "configurations": i.configurations,
                }
                for i in t.intervals
            ],
            "values": [
                {
                    "equals": v.value,
                    "text": _value_text(t.variable, v.value),
                    "configurations": v.configurations,
                }
                for v in t.values
            ],
        }
        for t in tables
    ]


def interval_text(name: str, i: Interval) -> str:
    """Write an interval as a designer reads it: ``1.25 <= visibility < 2.25``."""
    if i.low is not None and i.low == i.high:
        return f"{name} = {show(i.low)}"
    low = "" if i.low is None else f"{show(i.low)} {'<=' if i.low_closed else '<'} "
    high = "" if i.high is None else f" {'<=' if i.high_closed else '<'} {show(i.high)}"
    if not low and not high:
        return f"any {name}"
    if not low:
        return f"{name}{high}"
    if not high:
        return f"{name} {'>=' if i.low_closed else '>'} {show(i.low)}"
    return f"{low}{name}{high}"


def _value_text(name: str, value: bool | str | None) -> str:
    return f"{name} = {show(value)}" if value is not None else f"{name} = any other value"
