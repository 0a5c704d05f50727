"""Report ``rosreconf plan --switch-to``: the switch's plan, new configuration, changes and why.

The JSON document is ``plan``'s (output-plan.schema.json) with S2 as its one schema, so that
it works as the next ``--current``, and a ``switch`` object: the running schema, what it
runs, and per component keep, restart, start or stop.
"""

from __future__ import annotations

from typing import Any, Protocol

from rosreconf import jsonout
from rosreconf.formats.selection import Selection
from rosreconf.model import shown, shown_text
from rosreconf.planning.planners import Planner, PlanStatus
from rosreconf.planning.switch import SwitchResult
from rosreconf.render.reports import Output
from rosreconf.render.reports.context import context_doc, context_text, reworded
from rosreconf.render.reports.plan import schema_doc


class SwitchReporter(Protocol):
    """Render a task switch."""

    def render(self, sel: Selection, planner: Planner, sw: SwitchResult) -> str:
        """Return the whole report."""
        ...


class TextReporter:
    """The plan's steps (Figure 8), the new configuration, the changes per component, why."""

    def render(self, sel: Selection, planner: Planner, sw: SwitchResult) -> str:
        """Return the report."""
        r = sw.result
        s1, s2 = sw.source, r.schema
        out = [f"switch from {s1.display_name} ({s1.name}) to {s2.display_name} ({s2.name}):"]
        if r.status is PlanStatus.UNSOLVABLE_PROVEN:
            out.append("  the switch is impossible: no configuration of it is possible")
        elif r.configuration is None:
            out.append(f"  planner failed ({r.status}): {r.message}")
        else:
            run = r.planner
            if run is not None:
                out.append(f"  plan ({run.planner}, {run.elapsed:.2f} s, cost {run.cost}):")
            out += [f"  {n:>4}. {step}" for n, step in enumerate(r.steps, start=1)]
            out.append("  new configuration:")
            out += [f"    {role:<20} {shown_text(c)}" for role, c in r.configuration.assignment]
            out.append(f"  changes ({sw.count}, fewest possible: {r.fewest_changes}):")
            out += [f"    {m.kind:<8} {m.component:<10} {m.role:<20} {m.why}" for m in sw.changes]
        if r.explanation:
            out.append("  why:")
            out += [f"    {line}" for line in reworded(r.explanation, sel)]
        return context_text(sel) + "\n".join(out) + "\n"


class JsonReporter:
    """One JSON document: ``plan``'s, with S2 as its schema, and the ``switch`` object."""

    def render(self, sel: Selection, planner: Planner, sw: SwitchResult) -> str:
        """Return the JSON document."""
        doc: dict[str, Any] = {
            "library": {"name": sel.library.name, "components": len(sel.library)},
            "files": sel.loaded.files,
            "failed": list(sel.failed),
            "planner": planner.label,
            "schemas": [schema_doc(sw.result, sel)],
            "switch": switch_doc(sw),
        }
        if sel.has_context:
            doc["context"] = context_doc(sel)
        return jsonout.dumps(doc, indent=2) + "\n"


def switch_doc(sw: SwitchResult) -> dict[str, Any]:
    """Return the ``switch`` object of the JSON document (output-plan.schema.json)."""
    return {
        "from": sw.source.name,
        "to": sw.result.schema.name,
        "running": shown(sw.before),
        "changes": [
            {
                "component": m.component,
                "kind": m.kind,
                "role": m.role,
                "counted": m.counted,
                "replaces": m.replaces or None,
                "why": m.why,
            }
            for m in sw.changes
        ],
        "count": sw.count,
        "fewest_changes": sw.result.fewest_changes,
    }


REPORTERS: dict[Output, SwitchReporter] = {
    Output.TEXT: TextReporter(),
    Output.JSON: JsonReporter(),
}
