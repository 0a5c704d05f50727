"""Name clashes at run time: a node with a component's name that is not the component.

``conformance`` reports a node that has a component's live name but none of its endpoints
(``name-clash``). ``watch`` must never take such a node for the component: it would say the
component runs, never start it, and wait for ever on endpoints nobody serves. But a node
just started shows itself before its endpoints are discovered (seconds, on a busy machine),
so a clash counts only once it has lasted ``CLASH_SECONDS``, and never for a node whose
process rosreconf started itself. Then the component is failed (``how``: ``name-clash``) and
the configuration moves away from it; the other node is not rosreconf's and keeps running.
Once the configuration no longer holds the component, that node is outside it like any other
node of the robot and offers nothing the configuration uses (that is what made it a clash),
so its ``extra-node`` finding is excused: it does not keep ``conformant`` from being said.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection
from dataclasses import dataclass, field, replace

from rosreconf.ros.conformance import Conformance

CLASH_SECONDS = 3.0
"""How long a node must show none of its component's endpoints to be another node."""


@dataclass
class NameClashes:
    """Follow the ``name-clash`` findings of successive checks (see the module docstring).

    Attributes:
        say: how an event is said (``Watcher._say``).
        role: the role a component fills, for the message.
        since: component -> when its clash was first seen (monotonic seconds).
        impostors: the live names of the nodes taken for no component (a clash failed it).
    """

    say: Callable[..., None]
    role: Callable[[str], str]
    since: dict[str, float] = field(default_factory=dict)
    impostors: set[str] = field(default_factory=set)

    def excused(self, check: Conformance) -> Conformance:
        """Return ``check`` without the ``extra-node`` findings of nodes failed as clashes."""
        keep = tuple(
            f for f in check.findings if f.code != "extra-node" or f.live_name not in self.impostors
        )
        return check if len(keep) == len(check.findings) else replace(check, findings=keep)

    def clashing(self, check: Conformance, own: Collection[str]) -> set[str]:
        """Return the components whose name another node holds now (own processes never)."""
        return {
            f.component
            for f in check.findings
            if f.code == "name-clash" and f.component is not None and f.component not in own
        }

    def failed(self, check: Conformance, own: Collection[str], failed: Collection[str]) -> set[str]:
        """Say and return the components failed by a clash that has lasted long enough."""
        now, clashing = time.monotonic(), self.clashing(check, own)
        for comp in set(self.since) - clashing:
            del self.since[comp]
        first = {f.component: f for f in check.findings if f.code == "name-clash"}
        out: set[str] = set()
        for comp in sorted(clashing - set(failed)):
            if now - self.since.setdefault(comp, now) < CLASH_SECONDS:
                continue
            finding = first[comp]
            self.say(
                "failed",
                f"{comp} ({self.role(comp)}) is not running: {finding.message}: failed",
                component=comp,
                how="name-clash",
                node=finding.live_name,
            )
            out.add(comp)
            self.impostors.add(finding.live_name)
        return out
