"""Report ``rosreconf plan``: each schema's plan, new configuration and why, as text or JSON."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol

from rosreconf import jsonout
from rosreconf.formats.selection import Selection
from rosreconf.model import Configuration, shown, shown_text
from rosreconf.planning.planners import Planner, PlanStatus
from rosreconf.planning.replan import ReplanResult
from rosreconf.render.reports import Output
from rosreconf.render.reports.context import context_doc, context_text, reworded

if TYPE_CHECKING:  # drawn only with --graph: render.pictures is imported then
    from rosreconf.render.pictures import RosPicture


class PlanReporter(Protocol):
    """Render the re-planning of the selected schemas."""

    def render(self, sel: Selection, planner: Planner, results: Sequence[ReplanResult]) -> str:
        """Return the whole report."""
        ...


class TextReporter:
    """Per schema: the plan's steps, the new configuration, the changes and why (Figure 8)."""

    def render(self, sel: Selection, planner: Planner, results: Sequence[ReplanResult]) -> str:
        """Return one block per schema."""
        return context_text(sel) + "".join(_text(r, sel) for r in results)


class JsonReporter:
    """One JSON document (output-plan.schema.json); a schema's first configuration is new."""

    def render(self, sel: Selection, planner: Planner, results: Sequence[ReplanResult]) -> str:
        """Return the JSON document."""
        doc: dict[str, object] = {
            "library": {"name": sel.library.name, "components": len(sel.library)},
            "files": sel.loaded.files,
            "failed": list(sel.failed),
            "planner": planner.label,
            "schemas": [schema_doc(r, sel) for r in results],
        }
        if sel.has_context:
            doc["context"] = context_doc(sel)
        return jsonout.dumps(doc, indent=2) + "\n"


REPORTERS: dict[Output, PlanReporter] = {Output.TEXT: TextReporter(), Output.JSON: JsonReporter()}


def _text(r: ReplanResult, sel: Selection) -> str:
    out = [f"{r.schema.display_name} ({r.schema.name}):"]
    if r.status is PlanStatus.UNSOLVABLE_PROVEN:
        out.append("  no configuration is possible")
    elif r.configuration is None:
        out.append(f"  planner failed ({r.status}): {r.message}")
    else:
        run = r.planner
        if r.unaffected:
            out.append(f"  unaffected, keeps running: {r.unaffected}")
        if run is not None:
            out.append(f"  plan ({run.planner}, {run.elapsed:.2f} s, cost {run.cost}):")
        out += [f"  {n:>4}. {step}" for n, step in enumerate(r.steps, start=1)]
        out.append("  new configuration:")
        out += [f"    {role:<20} {shown_text(comp)}" for role, comp in r.configuration.assignment]
        out.append("  change:")
        out += [f"    {c}" for c in r.changes]
    if r.explanation:
        out.append("  why:")
        out += [f"    {line}" for line in reworded(r.explanation, sel)]
    return "\n".join(out) + "\n\n"


def schema_doc(r: ReplanResult, sel: Selection) -> dict[str, Any]:
    run = r.planner
    configs = [] if r.configuration is None else [{"assignment": r.configuration.shown}]
    return {
        "name": r.schema.name,
        "title": r.schema.display_name,
        "status": str(r.status),
        "configurations": configs,
        "current": shown(r.current),
        "steps": list(r.steps),
        "actions": list(r.actions),
        "changes": [
            {
                "role": c.role,
                "before": c.before or None,  # None: not running, or left empty
                "after": c.after or None,
                "kind": c.kind,
            }
            for c in r.changes
        ],
        "fewest_changes": r.fewest_changes,
        "explanation": reworded(r.explanation, sel),
        "why_not": r.why_not or None,
        "message": r.message,
        "cost": run.cost if run else None,
        "elapsed": round(run.elapsed, 3) if run else None,
        "unaffected": r.unaffected or None,
    }


def pictures(results: Sequence[ReplanResult]) -> list[RosPicture]:
    """Return each new configuration's ROS-graph against the running one (none: left out)."""
    from rosreconf.render.pictures import RosPicture

    return [
        RosPicture(
            r.schema,
            r.configuration,
            before=Configuration.of(r.schema.name, dict(r.current), r.schema.graph.roles)
            if {role.name for role in r.schema.graph.roles if not role.optional} <= set(r.current)
            else None,
        )
        for r in results
        if r.configuration is not None
    ]
