"""Switch a running ``watch`` to another task, with the fewest changes, when asked.

A task is one interoperability schema of watch's files; the paper's robot has two,
Object Repositioning and Disc Loading, and its agent picks the one for the work at hand.
A request (``Tasks.ask``, from any thread: the ROS 2 face's parameter, a test) waits in a
queue that the watcher drains at the start of its next step (``Tasks.take``), so a switch
never runs beside a repair. One switch at a time: a request that comes while a switch is
under way (from its ``task`` event until ``conformant`` or ``not-conformant``) is refused
with that reason, never queued behind it, because the task asked for may no longer make sense
once the first switch is done.

The target is ``switch_target``, the same switch ``plan --switch-to`` plans
(``rosreconf.model.switching``: what runs carried over into the new task's roles, kept
components restarted where the new task wires them otherwise), found by the exact optimiser
of the fewest changes over the new task's valid configurations without the failed
components; every running component the new configuration does not use is stopped.
Nothing here prints.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from rosreconf.model import EMPTY, ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.switching import carried_over, carried_wiring, switch_changes
from rosreconf.ros.events import Event
from rosreconf.ros.facestate import Health, Verdict, snapshot
from rosreconf.ros.livecontext import VariableState
from rosreconf.ros.replanning import Change, changes_data, changes_text
from rosreconf.solve.running import change_objective
from rosreconf.solve.solver import best_configuration, why_not

Say = Callable[..., None]


def switch_target(
    library: ComponentLibrary,
    source: InteroperabilitySchema,
    running: Configuration,
    s2: InteroperabilitySchema,
    failed: Collection[str],
) -> tuple[Configuration, list[Change]] | None:
    """Return ``s2``'s configuration reached from ``running`` with the fewest changes, and them.

    The same switch as ``plan --switch-to`` (``rosreconf.planning.switch``): what ``running``
    (a configuration of ``source``) runs is carried over into ``s2``'s roles
    (``rosreconf.model.switching.carried_over``), and a kept component restarts when ``s2``
    wires it otherwise than ``source`` does now (``carried_wiring``); the exact optimiser
    proves the fewest. Changes are ``replanning.Change`` tuples, one per change counted: a
    role of ``s2`` whose component starts, is replaced or restarts rewired, and (``role``,
    component, "") for each running component ``s2``'s configuration does not use (``role``
    is then its role in ``running``). None when ``s2`` has no valid configuration without
    ``failed``.
    """
    before = running.mapping
    kept = carried_over(source, before, s2)
    wired = carried_wiring(library, source, before, s2)
    objective = change_objective(library, s2, kept, wired=wired)
    new = best_configuration(library, s2, objective, failed)
    if new is None:
        return None
    moves = switch_changes(library, source, before, s2, new.mapping, failed)
    restarted = {m.role for m in moves if m.kind == "restart"}
    changes = [
        (r, kept.get(r, EMPTY), c)
        for r, c in new.assignment
        if kept.get(r, EMPTY) != c or r in restarted
    ]
    standing = {c for c in kept.values() if c != EMPTY}
    changes += [
        (m.role, m.component, EMPTY)
        for m in moves
        if m.kind == "stop" and m.component not in standing
    ]
    return new, changes


def feasibility(
    library: ComponentLibrary,
    schemas: Mapping[str, InteroperabilitySchema],
    current_task: str,
    running: Configuration,
    failed: Collection[str],
) -> list[Verdict]:
    """Return a verdict per task: the one running, those reachable, those that are not."""
    out = []
    for name, s in schemas.items():
        if name == current_task:
            out.append(Verdict(name, s.display_name, True, "the task running now", 0))
            continue
        found = switch_target(library, schemas[current_task], running, s, failed)
        if found is None:
            why = why_not(library, s, failed)
            out.append(Verdict(name, s.display_name, False, f"{s.display_name}: {why}"))
        else:
            out.append(Verdict(name, s.display_name, True, "", len(found[1])))
    return out


class Face(Protocol):
    """What shows a watch to the rest of the robot (ROS 2: ``ros2.face.FaceNode``)."""

    def state(self, doc: dict[str, Any]) -> None:
        """Show the watch's state (``rosreconf.ros.facestate.snapshot``)."""

    def line(self, event: Event) -> None:
        """Say one decision of the log."""

    def close(self) -> None:
        """End it."""


@dataclass
class Tasks:
    """The tasks a watch knows, the switch requests waiting, and the faces that show it.

    Attributes:
        schemas: every schema of watch's files, by name.
        faces: where state and decisions are shown (none: only the log).
        switching: the task a switch under way goes to, until it is confirmed.
    """

    schemas: Mapping[str, InteroperabilitySchema] = field(default_factory=dict)
    faces: list[Face] = field(default_factory=list)
    switching: str | None = None
    health: Health = field(default_factory=Health)
    _shown: dict[str, Any] | None = None
    _asked: queue.Queue[tuple[str, str]] = field(default_factory=queue.Queue)
    _lock: threading.Lock = field(default_factory=threading.Lock)
    _table: tuple[Any, list[Verdict]] | None = None

    def ask(self, task: str, refused: str = "") -> None:
        """Ask for a switch to ``task`` (any thread); with ``refused``, note a refusal made
        by a face (said in the log at the next step)."""
        self._asked.put((task, refused))

    def waiting(self) -> bool:
        """Tell whether a request waits (the poll loop then steps at once, not after its
        interval)."""
        return not self._asked.empty()

    def take(self, say: Say) -> str | None:
        """Return the task of the first switch request waiting; refuse the others (said)."""
        first = None
        while True:
            try:
                task, refused = self._asked.get_nowait()
            except queue.Empty:
                return first
            busy = self.switching or first
            if refused:
                say(
                    "task-refused",
                    f"switch to {task} refused: {refused}",
                    task=task,
                    reason=refused,
                )
            elif busy:
                why = f"a switch to {busy} is under way; ask again once it is conformant"
                say("task-refused", f"switch to {task} refused: {why}", task=task, reason=why)
            else:
                first = task

    def decide(
        self,
        library: ComponentLibrary,
        task: str,
        current: Configuration,
        schema: InteroperabilitySchema,
        failed: Collection[str],
        say: Say,
        acting: bool = True,
    ) -> tuple[InteroperabilitySchema, Configuration, list[Change]] | None:
        """Decide a switch to ``task``: the target (said as a ``task`` event), or None (said
        as ``task-refused`` with the reason; nothing changes). With ``acting`` (``--apply``)
        the switch is under way until its check; else it is over once said."""
        s2 = self.schemas.get(task)
        found = None if s2 is None else switch_target(library, schema, current, s2, failed)
        if s2 is None or task == schema.name or found is None:
            if s2 is None:
                why = f"no task {task}: the tasks are {', '.join(sorted(self.schemas))}"
            elif task == schema.name:
                why = f"{s2.display_name} is the task running now"
            else:
                why = f"{s2.display_name} has no configuration now: {why_not(library, s2, failed)}"
            say("task-refused", f"switch to {task} refused: {why}", task=task, reason=why)
            return None
        new, changes = found
        self.switching = task if acting else None
        say(
            "task",
            f"switching from {schema.display_name} to {s2.display_name}: {len(changes)} "
            f"change(s), the fewest possible (exact optimum): {changes_text(changes) or 'none'}",
            task=task,
            previous=schema.name,
            configuration=new.shown,
            changes=changes_data(changes),
        )
        return s2, new, changes

    def table(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        current: Configuration,
        failed: Collection[str],
    ) -> list[Verdict]:
        """Return ``feasibility`` now, computed again only when the configuration or the
        failures changed (a face asks on every look)."""
        key = (schema.name, current, frozenset(failed))
        with self._lock:
            if self._table is None or self._table[0] != key:
                verdicts = feasibility(library, self.schemas, schema.name, current, failed)
                self._table = (key, verdicts)
            return self._table[1]

    def show(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        current: Configuration,
        failed: Collection[str],
        running: Collection[str],
        event: Event | None = None,
        context: Sequence[VariableState] = (),
    ) -> None:
        """Note a decision (a switch ends with its check), have every face say it, and show
        them the state when it changed. A ``failed`` event comes before the watcher adds
        the component to ``failed``: it counts as failed here already."""
        if event is not None:
            if event.kind in ("conformant", "not-conformant"):
                self.switching = None
            self.health.saw(event)
            for face in self.faces:
                face.line(event)
            if event.kind == "failed":
                failed = {*failed, str(event.data.get("component", ""))} - {""}
            if event.kind == "task-refused":  # a face that took it shows the task again
                self._shown = None
        if not self.faces:
            return
        # on a decision's path (a failure's replan) the last table serves: the next read
        # renews it, so a repair never waits on the other tasks' optimisations
        cached = self._table[1] if event is not None and self._table is not None else None
        verdicts = cached if cached is not None else self.table(library, schema, current, failed)
        args = library, schema, current, failed, running, self.health, verdicts
        doc = snapshot(*args, self.switching, context)
        if doc != self._shown:
            self._shown = doc
            for face in self.faces:
                face.state(doc)

    def close(self) -> None:
        """End every face."""
        for face in self.faces:
            face.close()
