"""What a task switch changes: per component keep, restart, start or stop, and how many changes.

A task switch moves the robot from a configuration of one interoperability schema (S1, the
running task) to a configuration of another (S2). The two schemas may share components (a
component's ``schemas`` names both), and usually share roles (the paper's Object
Repositioning and Disc Loading have one system graph). docs/pddl.md ("Task switches") gives
the definitions this module computes; ``plan --switch-to`` (``rosreconf.planning.switch``)
finds the S2 configuration with the fewest of them, and a live watcher performs them.

**Which S1 component stands where in S2** (``carried_over``): S2's role of the same name and
abstraction holds S1's component of that role; a running component whose role S2 does not
have stands in the first remaining S2 role of its abstraction. A component of S1 standing in
no S2 role is stopped whatever S2's configuration is.

**The changes**, counted per S2 role as ``plan`` counts a re-plan (``Objective``): a role
whose component stays, wired alike, is kept (no change); stays, rewired, restarts (one); gets
another component: the old one stops and the new one starts in its place (one change, a
replacement); is filled where nothing stood: start (one); is left empty where a component
stood: stop (one). Each S1 component standing in no S2 role: stop (one). So stops count,
and a replacement counts once, as in a failure's re-plan: the switch to S2 is the re-plan of
S2 from what S1 runs.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass

from rosreconf.model.library import ComponentLibrary
from rosreconf.model.schema import EMPTY, InteroperabilitySchema
from rosreconf.model.wiring import Wire, wiring_of

KINDS = ("keep", "restart", "start", "stop")
"""What a switch does to one component, in the order a report lists them."""


@dataclass(frozen=True)
class ComponentChange:
    """What a task switch does to one component.

    Attributes:
        component: the component.
        kind: ``keep`` (runs in both, wired alike), ``restart`` (runs in both, rewired),
            ``start`` (runs only in S2's configuration) or ``stop`` (only in S1's).
        role: its S2 role (keep, restart, start), or its S1 role (stop).
        counted: whether it counts as a change: every restart, start and stop, except the
            stop of a component that another replaces in the same role (the replacement is
            one change, counted at the start).
        replaces: for a start, the S1 component it takes the place of (empty: none).
        why: the reason in words, in the paper's style.
    """

    component: str
    kind: str
    role: str
    counted: bool
    replaces: str = ""
    why: str = ""

    def __str__(self) -> str:
        if self.kind == "start" and self.replaces:
            return f"start {self.component} as {self.role} (in place of {self.replaces})"
        verb = {"keep": "keep", "restart": "restart", "start": "start", "stop": "stop"}[self.kind]
        suffix = " (rewired)" if self.kind == "restart" else ""
        return f"{verb} {self.component} as {self.role}{suffix}"


def carried_over(
    source: InteroperabilitySchema, before: Mapping[str, str], target: InteroperabilitySchema
) -> dict[str, str]:
    """Return S2 role -> the S1 component standing there (``EMPTY``: an empty optional role).

    The module's pairing: the role of the same name and abstraction first; then each
    remaining running component in the first unpaired S2 role of its abstraction, both in
    schema order. A mandatory S2 role nothing stands in is left out (whatever fills it
    starts); an optional one maps to ``EMPTY`` (filling it starts something, leaving it
    empty changes nothing).
    """
    abstraction = {r.name: r.abstraction for r in source.graph.roles}
    out: dict[str, str] = {}
    placed: set[str] = set()
    for role in target.graph.roles:
        if role.name in before and abstraction.get(role.name) == role.abstraction:
            out[role.name] = before[role.name]
            placed.add(role.name)
    for r1 in source.graph.roles:
        comp = before.get(r1.name, EMPTY)
        if r1.name in placed or comp == EMPTY:
            continue
        for role in target.graph.roles:
            if role.name not in out and role.abstraction == r1.abstraction:
                out[role.name] = comp
                placed.add(r1.name)
                break
    for role in target.graph.roles:
        if role.optional and role.name not in out:
            out[role.name] = EMPTY
    return out


def carried_wiring(
    library: ComponentLibrary,
    source: InteroperabilitySchema,
    before: Mapping[str, str],
    target: InteroperabilitySchema,
) -> dict[str, frozenset[Wire]]:
    """Return S2 role -> what the S1 component standing there is wired to now, under S1.

    The solvers' ``RestartTable.wired`` for a switch: a kept component restarts when S2's
    configuration wires it otherwise than S1's edges and providers do now.
    """
    now = wiring_of(library, source, before)
    role_of = {c: r for r, c in before.items() if c != EMPTY}
    return {
        role: now.get(role_of[comp], frozenset())
        for role, comp in carried_over(source, before, target).items()
        if comp != EMPTY and comp in library.by_name
    }


def switch_changes(
    library: ComponentLibrary,
    source: InteroperabilitySchema,
    before: Mapping[str, str],
    target: InteroperabilitySchema,
    after: Mapping[str, str],
    failed: Collection[str] = (),
) -> list[ComponentChange]:
    """Return what switching from ``before`` (of ``source``) to ``after`` (of ``target``) does.

    A pure function of the two configurations (role -> component; ``EMPTY`` or absent: an
    empty role): ``plan --switch-to`` reports it, and a live watcher performs it, so both
    say the same. S2's roles come first, in schema order (a replacement as the old
    component's stop, uncounted, then the new one's start); then the stops of S1 components
    standing in no S2 role. ``count_changes`` sums it. ``failed`` only words the reasons.
    """
    carried = carried_over(source, before, target)
    role_of = {c: r for r, c in before.items() if c != EMPTY}
    was, now = wiring_of(library, source, before), wiring_of(library, target, after)
    out: list[ComponentChange] = []
    down = set(failed)
    for role in target.graph.roles:
        comp, old = after.get(role.name, EMPTY), carried.get(role.name, EMPTY)
        if comp != EMPTY and comp == old:
            wired, wires = was.get(role_of[comp], frozenset()), now.get(role.name, frozenset())
            if wired == wires:
                out.append(ComponentChange(comp, "keep", role.name, False, why="wired alike"))
            else:
                why = _rewired(wired, wires)
                out.append(ComponentChange(comp, "restart", role.name, True, why=why))
            continue
        if old != EMPTY:
            why = f"{old} has failed" if old in down else f"{target.name} runs {comp} there"
            if comp == EMPTY:
                why = f"{target.name} leaves {role.name} empty"
            out.append(ComponentChange(old, "stop", role_of[old], comp == EMPTY, why=why))
        if comp != EMPTY:
            why = f"{target.name} needs it as {role.name}"
            out.append(ComponentChange(comp, "start", role.name, True, old, why))
    standing = set(carried.values())
    abstractions = {r.abstraction for r in target.graph.roles}
    for r1 in source.graph.roles:
        comp = before.get(r1.name, EMPTY)
        if comp != EMPTY and comp not in standing:
            why = f"{target.name} has no role of its abstraction"
            if r1.abstraction in abstractions:
                why = f"each {target.name} role of its abstraction stands for another"
            out.append(ComponentChange(comp, "stop", r1.name, True, why=why))
    return out


def count_changes(changes: Collection[ComponentChange]) -> int:
    """Return how many changes a switch makes (``ComponentChange.counted``)."""
    return sum(1 for c in changes if c.counted)


def _rewired(was: frozenset[Wire], now: frozenset[Wire]) -> str:
    """Say how a kept component's wiring changes (ROS names are fixed when a node starts)."""
    came = sorted(f"{i.label} at {n}" for i, n in now - was)
    gone = sorted(f"{i.label} at {n}" for i, n in was - now)
    if not came:
        how = f"it no longer uses {', '.join(gone[:2])}"
    elif not gone:
        how = f"it now also uses {', '.join(came[:2])}"
    else:
        how = f"it now uses {', '.join(came[:2])}, instead of {', '.join(gone[:2])}"
    more = len(came) + len(gone) - min(len(came), 2) - min(len(gone), 2)
    return how + (f" and {more} more" if more else "")
