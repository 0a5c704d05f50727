"""Name clashes at run time: a node with a component's name that is not the component.

``conformance`` reports a node that has a component's live name but none of its endpoints
(``name-clash``): an impostor with endpoints of its own, or a bare node with none at all (a
squatter on the name). ``watch`` must never take such a node for the component: it would say
the component runs, never start it, and wait for ever on endpoints nobody serves. But a node
just started shows itself before its endpoints are discovered (seconds, on a busy machine),
and a real driver may create its endpoints only once its hardware answers: so a clash counts
only once it has lasted ``CLASH_SECONDS`` (a node showing no endpoints at all:
``BARE_SECONDS``), and never for a node whose process rosreconf started itself. Then the
other node is handed to ``squat``. With ``--stop-outside`` its process is stopped when /proc
confirmed it: the name is free, and the component is started in it (one start, where a
replacement moves its role and rewires its neighbours). Otherwise the component is failed
(``how``: ``name-clash``), the configuration moves away from it, and the other node, not
rosreconf's, is named for a person and keeps running. Once the configuration no longer holds
the component, that node is outside it like any other node of the robot and offers nothing
the configuration uses (that is what made it a clash), so its ``extra-node`` finding is
excused: it does not keep ``conformant`` from being said. When no node holds the name any
more, the component is a candidate again (``release``): with no configuration left without
it, it is started.

Two nodes of one name (ROS 2 allows it; service calls and parameters reach either one) are a
``duplicate``, said when it appears. Beside the running component, a bare one is a squatter
too, handed to ``squat``; the component keeps running (it is not at fault).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field, replace

from rosreconf.ros.conformance import Conformance
from rosreconf.ros.livegraph import LiveGraph, LiveNode, without_plumbing

CLASH_SECONDS = 3.0
"""How long a node must show none of its component's endpoints to be another node."""
BARE_SECONDS = 10.0
"""How long a node must show no endpoints at all to be another node: a real driver may
create its node first and its endpoints only once its device answers."""

Squat = Callable[[str, str, str, bool], bool]
"""Hand on a node squatting on a component's name: (component, role, node, beside the
running component); the actuator names it for a person or stops its process (True: stopped,
the name is free)."""


def _empty(node: LiveNode) -> bool:
    return not (node.publishes or node.subscribes or node.serves or node.clients)


def bare(graph: LiveGraph, name: str) -> bool:
    """Tell whether every node named ``name`` has no endpoints at all (plumbing aside)."""
    return all(_empty(n) for n in without_plumbing(graph).nodes if n.name == name)


@dataclass
class NameClashes:
    """Follow the ``name-clash`` findings of successive checks (see the module docstring).

    Attributes:
        say: how an event is said (``Watcher._say``).
        role: the role a component fills, for the message.
        squat: hands on the other node of a clash (the actuator's ``squatter``).
        since: component -> when its clash was first seen (monotonic seconds).
        impostors: the live names of the nodes taken for no component (a clash failed it).
        squatted: component failed by a clash -> the live name the other node holds.
        duplicates: live name -> how many nodes had it when said (said again if it grows).
        beside: live name -> since when a bare node has had it beside the component (None:
            handed to ``squat`` already).
        freed: components whose squatter was stopped since the last look (to start now).
    """

    say: Callable[..., None]
    role: Callable[[str], str]
    squat: Squat = lambda *_: False
    since: dict[str, float] = field(default_factory=dict)
    impostors: set[str] = field(default_factory=set)
    squatted: dict[str, str] = field(default_factory=dict)
    duplicates: dict[str, int] = field(default_factory=dict)
    beside: dict[str, float | None] = field(default_factory=dict)
    freed: set[str] = field(default_factory=set)

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
            finding, role = first[comp], self.role(comp)
            grace = BARE_SECONDS if bare(check.live, finding.live_name) else CLASH_SECONDS
            if now - self.since.setdefault(comp, now) < grace:
                continue
            self.say(
                "failed",
                f"{comp} ({role}) is not running: {finding.message}: failed",
                component=comp,
                how="name-clash",
                node=finding.live_name,
            )
            if self.squat(comp, role, finding.live_name, False):
                del self.since[comp]  # stopped: the name is free, the component starts in it
                self._released(comp, finding.live_name, "is stopped")
                self.freed.add(comp)
                continue
            out.add(comp)
            self.impostors.add(finding.live_name)
            self.squatted[comp] = finding.live_name
        return out

    def over(self, graph: LiveGraph, failed: Collection[str]) -> set[str]:
        """Say and return the components failed by a clash whose name no node holds now.

        The other node is gone (stopped by a person, or by rosreconf): the component is a
        candidate again.
        """
        out: set[str] = set()
        for comp, node in sorted(self.squatted.items()):
            if node in graph.names:
                continue
            del self.squatted[comp]
            self.impostors.discard(node)
            if comp not in failed:
                continue
            self._released(comp, node, "is gone")
            out.add(comp)
        return out

    def _released(self, comp: str, node: str, how: str) -> None:
        self.say(
            "release",
            f"{comp} is a candidate again: {node}, the other node that had its name, {how}",
            component=comp,
            node=node,
        )

    def duplicated(self, check: Conformance, components: Mapping[str, str]) -> bool:
        """Say each name two or more nodes hold, when it appears; True when one was said.

        ``components``: live name -> the configuration's component of that name. A node of
        that name with no endpoints beside one with them is a squatter once that has lasted
        ``BARE_SECONDS`` (a node just started may not show its endpoints yet): it is handed
        to ``squat``, once.
        """
        live, now = check.live, time.monotonic()
        counts = {n: live.names.count(n) for n in live.duplicates}
        for name in set(self.duplicates) - set(counts):
            del self.duplicates[name]
            self.beside.pop(name, None)
        said = False
        for name, count in sorted(counts.items()):
            comp = components.get(name)
            entries = [n for n in without_plumbing(live).nodes if n.name == name]
            empty = sum(1 for n in entries if _empty(n))
            if comp is not None and 0 < empty < len(entries):
                since = self.beside.setdefault(name, now)
                if since is not None and now - since >= BARE_SECONDS:
                    self.beside[name] = None  # handed on once
                    self.squat(comp, self.role(comp), name, True)
            elif self.beside.get(name, 0.0) is not None:
                self.beside.pop(name, None)  # a squatter has to stay bare that long at a stretch
            if self.duplicates.get(name, 0) >= count:
                continue
            self.duplicates[name] = count
            whose = f" ({comp}, {self.role(comp)})" if comp is not None else ""
            self.say(
                "duplicate",
                f"{count} nodes are named {name}{whose}: service calls, parameters and lifecycle "
                "requests reach either one (ROS 2 allows it; give each its own name)"
                + (f"; {empty} of them with no endpoints at all (yet)" if empty else ""),
                node=name,
                component=comp,
                count=count,
            )
            said = True
        return said
