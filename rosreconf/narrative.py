"""Tell an operator, in plain words, what a reconfiguration changes and why.

Every sentence is derived from the model, never invented: a part "had to go" only when putting
it back into the new configuration breaks a rule of ``rosreconf.validity``, and the sentence
names that rule (a requirement only other parts provide, a coupling, an edge).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    Requirement,
)
from rosreconf.validity import requirement_met, violations


@dataclass(frozen=True)
class Change:
    """What happens to one role: keep its component, replace it, or start one in it.

    Attributes:
        role: the role.
        before: the component running now (None when nothing runs there).
        after: the component of the new configuration.
    """

    role: str
    before: str | None
    after: str

    @property
    def kind(self) -> str:
        """Return ``keep``, ``replace`` or ``start``."""
        if self.before == self.after:
            return "keep"
        return "start" if self.before is None else "replace"

    def __str__(self) -> str:
        if self.kind == "keep":
            return f"{self.role}: keep {self.after}"
        if self.kind == "start":
            return f"{self.role}: start {self.after}"
        return f"{self.role}: stop {self.before}, start {self.after}"


def changes(current: Mapping[str, str], new: Configuration) -> list[Change]:
    """Compare the running configuration with the new one, role by role."""
    return [Change(role, current.get(role), comp) for role, comp in new.assignment]


def _providers(library: ComponentLibrary, req: Requirement) -> list[str]:
    return [c.name for c in library if any(o in c.provides for o in req.options)]


def _labels(req: Requirement) -> str:
    return " or ".join(o.label for o in req.options)


def _why_not_kept(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    new: Configuration,
    role: str,
    old: str,
) -> list[str]:
    """Say what breaks if ``old`` is put back into ``role`` of the new configuration."""
    if old in failed:
        return [f"{old} has failed"]
    if old not in library:
        return [f"{old} is not in the library"]
    trial = {**new.mapping, role: old}
    chosen: dict[str, Component] = {r: library[c] for r, c in trial.items() if c in library}
    comp = library[old]
    reasons = []
    for req in comp.requires:
        if not requirement_met(req, role, schema, chosen):
            who = _providers(library, req)
            dead = [p for p in who if p in failed]
            text = f"{old} requires {_labels(req)}, which only {', '.join(who) or 'nothing'} "
            text += "provides" if len(who) == 1 else "provide"
            if dead:
                text += f" ({', '.join(dead)} failed)"
            reasons.append(text)
    config = Configuration.of(schema.name, trial, schema.graph.roles)
    strangers: list[str] = []
    for v in violations(config, library, schema, failed):  # the new one has none: all are old's
        if v.code == "requirement-unmet" and v.components == (old,):
            continue  # said above, with who could provide it
        if v.code == "edge-unrealised":
            strangers += [c for c in v.components if c != old]
            continue
        reasons.append(v.message)
    if strangers:
        partners = ", ".join(dict.fromkeys(strangers))
        reasons.append(f"it shares no interface with {partners} along their edges")
    return list(dict.fromkeys(reasons))


def explain_replan(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
    new: Configuration,
    fewest_changes: int | None = None,
) -> list[str]:
    """Explain a new configuration: what failed, why each replaced part went, what still works."""
    lines = []
    for role, comp in current.items():
        if comp in failed:
            lines.append(f"{comp} ({role}) has failed.")
    replaced = [c for c in changes(current, new) if c.kind == "replace"]
    for change in replaced:
        assert change.before is not None
        why = _why_not_kept(library, schema, failed, new, change.role, change.before)
        if why:
            because = "; ".join(why)
            lines.append(
                f"{change.role}: {change.before} cannot stay ({because}); "
                f"{change.after} takes over."
            )
        else:
            lines.append(
                f"{change.role}: {change.before} is replaced by {change.after} although it could "
                "have stayed (the planner's choice; see the change count below)."
            )
    if not replaced:
        lines.append("Nothing has to change." if current else "")
    n = len(replaced)
    if fewest_changes is not None and current:
        if n == fewest_changes:
            lines.append(f"{n} part(s) change: the fewest possible.")
        else:
            lines.append(
                f"{n} part(s) change; the fewest possible is {fewest_changes} (try --search "
                "seq-sat-lama-2011 or a longer --timeout)."
            )
    lines.append(f"{schema.display_name} still works: {' '.join(schema.skill.split())}")
    return [line for line in lines if line]


def explain_impossible(
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
    why_not: str,
) -> list[str]:
    """Explain that a task can no longer be done, and why."""
    lines = [f"{comp} ({role}) has failed." for role, comp in current.items() if comp in failed]
    lines.append(f"{schema.display_name} is no longer possible: {why_not}")
    return lines
