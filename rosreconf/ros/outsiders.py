"""Nodes of the configuration that someone else restarts: back, unwired, or squatted on.

A robot's team restarts its own nodes by hand (a launch file run again, ``respawn``, a person
at a terminal), with whatever ``-r`` rules it had. ``watch`` judges such a node by what it
offers and how it is wired, never by its name alone::

    a failed component's node is live again    ``back``: no longer failed (its hold is
    under a new process, with the component's   dropped); a configuration that could not do
    endpoints                                    without it is whole again
    ... with none of them (a name clash)         not back: ``clashes`` judges it
    a node rosreconf did not start uses          ``unwired``, with the ``-r`` rules that wire
    another name for an edge (``unwired``)       it, and a person is asked to restart it so
                                                 (``await_rewire``); never ``failed``
    the other node of a clash is gone            a candidate again (``clashes.over``)
    two nodes announce one name                  ``duplicate``, said when it appears

"A new process" is read off the middleware (``Actuator.incarnations``: on ROS 2, the DDS
participants announcing the node): the participants announcing a component's node when it
failed are remembered, and only another one brings it back, so a node failed while it still
runs (hung, ``--fail``, a lifecycle fault) is never taken back on its name. The watcher never
starts a node whose name is live (``ros2.squatting``). Every decision is an event; nothing
here prints or acts.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from dataclasses import dataclass, field

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.actuator import Actuator
from rosreconf.ros.clashes import NameClashes
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.launchfiles import wiring
from rosreconf.ros.restarts import Restarts

GONE = frozenset({"missing-node", "dead-node", "name-clash"})
"""Findings that say a component's node is not the component running."""


@dataclass
class Outsiders:
    """Follow the nodes of the configuration that rosreconf did not start (module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        say: how an event is said (``Watcher._say``).
        role: the role a component fills in the current configuration.
        actuator: who announces a node, and how a person is asked to restart one.
        clashes: the watcher's name clashes (squatters gone, duplicates).
        restarts: the watcher's holds (a component back is held no more).
        failed_with: failed component -> who announced its node when it failed.
        unwired_said: component -> the ``unwired`` findings last said of it.
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    say: Callable[..., None]
    role: Callable[[str], str]
    actuator: Actuator
    clashes: NameClashes
    restarts: Restarts
    failed_with: dict[str, frozenset[str]] = field(default_factory=dict)
    unwired_said: dict[str, tuple[str, ...]] = field(default_factory=dict)

    def note(self, failed: Collection[str]) -> None:
        """Remember who announces each newly failed component's node (before a new read)."""
        for comp in set(self.failed_with) - set(failed):
            del self.failed_with[comp]
        for comp in set(failed) - set(self.failed_with):
            now = self.actuator.incarnations(node_live_name(self.library[comp]))
            if now is not None:
                self.failed_with[comp] = now

    def check(
        self,
        check: Conformance,
        clashing: Collection[str],
        current: Configuration,
        failed: set[str],
    ) -> tuple[set[str], bool]:
        """Act on one look at the live graph; return (components back, something to confirm).

        Components back (restarted by hand, or their name free again after a clash) are
        taken out of ``failed`` and out of their hold.
        """
        own = self.actuator.started()
        self.clashes.freed.clear()  # started on this look, as missing
        back = self._back(check, clashing, current, failed, own)
        back |= self.clashes.over(check.live, failed)
        for comp in back:
            self.restarts.drop(comp)
        failed -= back
        names = {node_live_name(self.library[c]): c for c in current.components}
        news = self.clashes.duplicated(check, names)
        news = self._unwired(check, current, failed | own) or news
        return back, bool(back) or news

    def _back(
        self,
        check: Conformance,
        clashing: Collection[str],
        current: Configuration,
        failed: Collection[str],
        own: Collection[str],
    ) -> set[str]:
        """Say and return the failed components whose node runs again in a new process."""
        out = set()
        for comp in sorted(set(failed) & set(current.components) - set(clashing) - set(own)):
            then, node = self.failed_with.get(comp), node_live_name(self.library[comp])
            now = self.actuator.incarnations(node)
            if then is None or not now or not now - then:
                continue
            if any(f.code in GONE for f in check.findings if f.component == comp):
                continue
            self.say(
                "back",
                f"{comp} ({self.role(comp)}) runs again: {node} was started anew outside "
                "rosreconf (restarted by hand), with its endpoints: no longer failed",
                component=comp,
                node=node,
            )
            out.add(comp)
        return out

    def _unwired(self, check: Conformance, current: Configuration, skip: Collection[str]) -> bool:
        """Say each node rosreconf did not start that is wired for another configuration,
        with the ``-r`` rules that wire it, and ask a person to restart it so; True if said.

        ``skip``: failed components and rosreconf's own (restarted by it when rewired).
        """
        awaited = self.actuator.awaited()
        found: dict[str, list[str]] = {}
        for f in check.findings:
            c = f.component
            if f.code == "unwired" and c in current.components and c not in skip:
                found.setdefault(c, []).append(f.message)
        for comp in set(self.unwired_said) - set(found):
            del self.unwired_said[comp]
        said = False
        for comp, messages in sorted(found.items()):
            key = tuple(sorted(messages))
            if comp in awaited or self.unwired_said.get(comp) == key:
                continue
            self.unwired_said[comp] = key
            remaps = wiring(self.library, self.schema, current).get(comp, [])
            rules = [f"{a}:={b}" for a, b, _ in remaps]
            node, role = node_live_name(self.library[comp]), self.role(comp)
            self.say(
                "unwired",
                f"{comp} ({role}): {node} runs with its endpoints, but wired for another "
                f"configuration: {key[0]}"
                + (f" and {len(key) - 1} more" if len(key) > 1 else "")
                + f"; restart it with --ros-args {' '.join(f'-r {r}' for r in rules)}",
                component=comp,
                node=node,
                remappings=rules,
                findings=list(key),
            )
            self.actuator.await_rewire(comp, role, current)
            said = True
        return said
