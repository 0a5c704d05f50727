"""Plan a task switch at design time: the configuration of S2 reached with the fewest changes.

A switch from the running schema S1 to S2 is the re-plan of S2 (``replan.plan``: the solver
proves the fewest changes, the PDDL planner plans them, the plan is read back and checked)
whose "current" is what S1 runs, carried over into S2's roles
(``rosreconf.model.switching.carried_over``), and whose kept components restart when S2
wires them otherwise than S1 does now (``carried_wiring``, the solvers' ``wired`` facts).
What the switch does to each component, and how many changes that is, is the pure
``rosreconf.model.switching.switch_changes``, which a live watcher reuses. docs/pddl.md,
"Task switches", defines the changes and argues the count.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass, replace
from pathlib import Path

from rosreconf.model import EMPTY, ComponentLibrary, InteroperabilitySchema
from rosreconf.model.switching import (
    ComponentChange,
    carried_over,
    carried_wiring,
    count_changes,
    switch_changes,
)
from rosreconf.planning.narrative import Change, why_not_kept
from rosreconf.planning.planners import Planner
from rosreconf.planning.replan import ReplanResult, plan
from rosreconf.solve.search import Budget


@dataclass(frozen=True)
class SwitchResult:
    """A task switch's answer.

    Attributes:
        source: S1, the running schema.
        before: S1's running configuration (role -> component).
        result: the re-plan of S2 from what S1 runs (its ``configuration`` is None when the
            switch is impossible; ``why_not`` then says why); its ``changes`` are per S2
            role, its ``explanation`` the switch's, its ``fewest_changes`` the switch's.
        changes: per component keep, restart, start or stop (``switch_changes``).
    """

    source: InteroperabilitySchema
    before: Mapping[str, str]
    result: ReplanResult
    changes: tuple[ComponentChange, ...] = ()

    @property
    def count(self) -> int | None:
        """Return how many changes the switch makes (None when it is impossible)."""
        if self.result.configuration is None:
            return None
        return count_changes(self.changes)


def forced_changes(
    source: InteroperabilitySchema, before: Mapping[str, str], target: InteroperabilitySchema
) -> int:
    """Return the changes every configuration of S2 makes, which the solver does not count.

    Each running component standing in no S2 role stops; each mandatory S2 role nothing
    stands in starts one. Every configuration of S2 pays them alike, so the solver's
    optimum is the switch's, and its count plus these is the switch's fewest.
    """
    carried = carried_over(source, before, target)
    standing = set(carried.values())
    stops = sum(1 for c in before.values() if c != EMPTY and c not in standing)
    return stops + sum(1 for r in target.graph.roles if r.name not in carried)


def switch(
    library: ComponentLibrary,
    source: InteroperabilitySchema,
    before: Mapping[str, str],
    target: InteroperabilitySchema,
    failed: Collection[str],
    planner: Planner,
    *,
    weights: Mapping[str, float] | None = None,
    timeout: float = 60.0,
    keep_pddl: Path | None = None,
    budget: Budget | None = None,
) -> SwitchResult:
    """Plan the switch from ``before`` (a configuration of ``source``) to ``target``.

    ``failed`` components are unusable in S2. The planner runs even when S1's components
    already make a valid S2 configuration: they may have to restart to be rewired.
    """
    carried = carried_over(source, before, target)
    result = plan(
        library,
        target,
        failed,
        carried,
        planner,
        weights=weights,
        timeout=timeout,
        keep_pddl=keep_pddl,
        budget=budget,
        wired=carried_wiring(library, source, before, target),
    )
    if result.configuration is None:
        lines = [f"{c} ({r}) has failed." for r, c in before.items() if c in set(failed)]
        if result.why_not:
            lines.append(
                f"The switch from {source.display_name} to {target.display_name} is "
                f"impossible: {result.why_not}"
            )
        return SwitchResult(source, before, replace(result, explanation=tuple(lines)))
    after = result.configuration.mapping
    moves = tuple(switch_changes(library, source, before, target, after, failed))
    fewest = result.fewest_changes
    fewest = None if fewest is None else fewest + forced_changes(source, before, target)
    if fewest is None and not carried:
        fewest = count_changes(moves)  # nothing carried over: every configuration costs alike
    rewired = {m.role: m.why for m in moves if m.kind == "restart"}
    per_role = tuple(
        Change(role, carried.get(role), comp, rewired.get(role, "")) for role, comp in after.items()
    )
    sw = SwitchResult(source, before, replace(result, changes=per_role, fewest_changes=fewest))
    lines = explain_switch(library, sw, failed)
    return replace(sw, result=replace(sw.result, explanation=tuple(lines)), changes=moves)


def explain_switch(
    library: ComponentLibrary, sw: SwitchResult, failed: Collection[str]
) -> list[str]:
    """Explain a switch in the paper's words: what goes and why, what restarts, what stays.

    ``sw.changes`` may still be empty: the changes are recomputed here from the two
    configurations, so the sentences and the report never disagree.
    """
    r, source, target = sw.result, sw.source, sw.result.schema
    assert r.configuration is not None
    moves = switch_changes(library, source, sw.before, target, r.configuration.mapping, failed)
    lines = [f"The task switches from {source.display_name} to {target.display_name}."]
    lines += [f"{c} ({role}) has failed." for role, c in sw.before.items() if c in set(failed)]
    starts = {m.replaces: m.component for m in moves if m.kind == "start" and m.replaces}
    for m in moves:
        if m.kind == "stop" and m.component in starts:
            role = next(x.role for x in moves if x.replaces == m.component)
            why = why_not_kept(library, target, failed, r.configuration, role, m.component)
            because = "; ".join(why) or "the planner's choice"
            lines.append(
                f"{m.role}: {m.component} cannot stay ({because}); {starts[m.component]} "
                "takes over."
            )
        elif m.kind == "stop":
            lines.append(f"{m.role}: {m.component} stops: {m.why}.")
        elif m.kind == "start" and not m.replaces:
            lines.append(f"{m.role}: {m.component} starts: {m.why}.")
        elif m.kind == "restart":
            lines.append(
                f"{m.component} ({m.role}) restarts to be rewired, since ROS names are fixed "
                f"when a node starts: {m.why}."
            )
    kept = [m.component for m in moves if m.kind == "keep"]
    if kept:
        lines.append(f"Kept as they run, wired alike: {', '.join(kept)}.")
    n = count_changes(moves)
    kinds = {k: sum(1 for m in moves if m.kind == k) for k in ("start", "stop", "restart")}
    replaced = len(starts)
    said = (
        f"{n} change(s): {kinds['start']} start(s), {kinds['stop']} stop(s), "
        f"{kinds['restart']} restart(s); each of the {replaced} replacement(s) counts once"
    )
    if r.fewest_changes is not None:
        if n == r.fewest_changes:
            lines.append(f"{said}: the fewest possible.")
        else:
            lines.append(f"{said}; the fewest possible is {r.fewest_changes}.")
    lines.append(f"{target.display_name} can be done: {' '.join(target.skill.split())}")
    return lines
