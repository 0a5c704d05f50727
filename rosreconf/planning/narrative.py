"""Tell an operator, in plain words, what a reconfiguration changes and why.

Every sentence is derived from the model, never invented: a part "had to go" only when putting
it back into the new configuration breaks a rule of ``rosreconf.model.validity``, and the sentence
names that rule (a requirement only other parts provide, a coupling, an edge).
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass

from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    Requirement,
)
from rosreconf.model.validity import requirement_met, violations
from rosreconf.model.wiring import rewiring


@dataclass(frozen=True)
class Change:
    """What happens to one role: keep it, replace its component, start one, or stop it.

    Attributes:
        role: the role.
        before: the component running now (None when nothing is known to run there,
            ``EMPTY`` when the optional role is left empty now).
        after: the component of the new configuration (``EMPTY``: left empty).
        rewired: why a kept component restarts to be rewired (``rosreconf.model.wiring``);
            empty when it needs not.
    """

    role: str
    before: str | None
    after: str
    rewired: str = ""

    @property
    def kind(self) -> str:
        """Return ``keep``, ``restart`` (kept, rewired), ``replace``, ``start`` or ``stop``."""
        if (self.before or EMPTY) == self.after:
            return "restart" if self.rewired else "keep"
        if not self.before:
            return "start"
        return "stop" if self.after == EMPTY else "replace"

    @property
    def counted(self) -> bool:
        """Tell whether the objective counts this as a change (something ran, or was empty)."""
        return self.before is not None and (self.before != self.after or bool(self.rewired))

    def __str__(self) -> str:
        if self.kind == "restart":
            return f"{self.role}: restart {self.after} (rewired)"
        if self.kind == "keep":
            return f"{self.role}: keep {self.after or 'it empty'}"
        if self.kind == "start":
            return f"{self.role}: start {self.after}"
        if self.kind == "stop":
            return f"{self.role}: stop {self.before}, leave it empty"
        return f"{self.role}: stop {self.before}, start {self.after}"


def changes(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Mapping[str, str],
    new: Configuration,
) -> list[Change]:
    """Compare the running configuration with the new one, role by role.

    A kept component whose wiring changes is a ``restart`` (the wiring model,
    ``rosreconf.model.wiring``): it is counted as a change, with the reason.
    """
    rewired = rewiring(library, schema, current, new.mapping)
    return [
        Change(role, current.get(role), comp, rewired.get(role, ""))
        for role, comp in new.assignment
    ]


def _providers(library: ComponentLibrary, req: Requirement) -> list[str]:
    return [c.name for c in library if any(o in c.provides for o in req.options)]


def _labels(req: Requirement) -> str:
    return " or ".join(o.label for o in req.options)


def _names(names: list[str]) -> str:
    """Join names as an operator reads them: "A", "A and B", "A, B and C"."""
    names = list(dict.fromkeys(names))
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def why_not_kept(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    new: Configuration,
    role: str,
    old: str,
) -> list[str]:
    """Say, in the fewest true words, what breaks if ``old`` is put back into ``role``.

    Reasons come from the rules of ``rosreconf.model.validity`` and are given most causal first:
    the failure itself; a need of ``old`` that only failed or departed parts meet; a coupling;
    parts of the new configuration that need something ``old`` does not provide (grouped by
    what they need); and, only when nothing else explains it, the unrealised edges.
    """
    if old in failed:
        return [f"{old} has failed"]
    if old not in library:
        return [f"{old} is not in the library"]
    trial = {**new.mapping, role: old}
    chosen: dict[str, Component] = {r: library[c] for r, c in trial.items() if c in library}
    comp = library[old]
    own: list[str] = []
    for req in comp.requires:
        if not requirement_met(req, role, schema, chosen):
            who = _providers(library, req)
            dead = [p for p in who if p in failed]
            text = f"it needs {_labels(req)}, which only {_names(who) or 'nothing'} "
            text += ("provides" if len(who) == 1 else "provide") + (
                f" and {_names(dead)} failed" if dead else ""
            )
            own.append(text)
    own.sort(key=lambda t: "failed" not in t)  # the need a failure broke explains most
    config = Configuration.of(schema.name, trial, schema.graph.roles)
    couplings = [
        v.message
        for v in violations(config, library, schema, failed)
        if v.code in ("needs", "excludes", "reused", "not-in-schema", "wrong-abstraction")
    ]
    others: dict[str, list[str]] = {}
    for other_role, other in chosen.items():
        if other_role == role:
            continue
        for req in other.requires:
            if not requirement_met(req, other_role, schema, chosen):
                others.setdefault(_labels(req), []).append(other.name)
    needed = [
        f"{_names(users)} need{'s' if len(users) == 1 else ''} {labels}, which {old} "
        "does not provide"
        for labels, users in others.items()
    ]
    reasons = own[:1] + couplings + needed[:1]
    hidden = len(own[1:]) + len(needed[1:])
    if hidden:
        reasons.append(f"and {hidden} more unmet need(s)")
    if not reasons:
        strangers = [
            c
            for v in violations(config, library, schema, failed)
            if v.code == "edge-unrealised"
            for c in v.components
            if c != old
        ]
        if strangers:
            reasons.append(f"it shares no interface with {_names(strangers)} along their edges")
    return reasons


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
    every = changes(library, schema, current, new)
    replaced = [c for c in every if c.kind in ("replace", "stop")]
    for change in replaced:
        assert change.before is not None
        why = why_not_kept(library, schema, failed, new, change.role, change.before)
        after = f"{change.after} takes over" if change.after else "the role is left empty"
        if why:
            because = "; ".join(why)
            lines.append(f"{change.role}: {change.before} cannot stay ({because}); {after}.")
        else:
            lines.append(
                f"{change.role}: {change.before} is replaced by {change.after} although it could "
                "have stayed (the planner's choice; see the change count below)."
            )
    lines += [f"{c.rewired}." for c in every if c.kind == "restart"]
    n = sum(1 for c in every if c.counted)
    restarts = sum(1 for c in every if c.kind == "restart")
    parts = f"{n} part(s) change"
    if restarts:
        parts += f" ({n - restarts} replaced or started, {restarts} restarted to be rewired)"
    if not n:
        lines.append("Nothing has to change." if current else "")
    if fewest_changes is not None and current:
        if n == fewest_changes:
            lines.append(f"{parts}: the fewest possible.")
        else:
            lines.append(
                f"{parts}; the fewest possible is {fewest_changes} (try --search "
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


def ruled_out_wording(lines: Sequence[str], why: Mapping[str, str]) -> list[str]:
    """Return an explanation with a ruled-out component's reason where it says "failed".

    The explanation says "X has failed" of every unusable part; for one that context ruled
    out (``why``: component -> its unmet condition, ``model.context.RuledOut.reason``), the
    true reason is the condition: "X (role) is ruled out: X needs visibility >= 3.25; it is
    2.0". Used by ``plan``'s reports and by ``watch``'s replans alike.
    """
    if not why:
        return list(lines)
    pattern = re.compile(
        r"\b(" + "|".join(re.escape(n) for n in why) + r")( \([^)]*\))? has failed"
    )

    def say(m: re.Match[str]) -> str:
        return f"{m.group(1)}{m.group(2) or ''} is ruled out: {why[m.group(1)]}"

    return [pattern.sub(say, line) for line in lines]
