"""Context read live: which components what the robot measures rules out now, with a dwell.

At design time a context value is given (``--context visibility=2.0``); a running ``watch
--ros2`` reads it off the robot: its face node subscribes to each declared topic
(``ros2.face``) and hands every reading here (``LiveContext.heard``, from the reader
thread). The watcher asks at each step (``LiveContext.assess``) which components context
rules out now, and replans away from a chosen one as from a failed one (never restarting it
in place: restarting does not change the water).

**Dwell.** A component's usability (every condition of its ``when`` holds) changes only
after the readings have said the new answer without a break for ``dwell`` seconds: a noisy
reading that crosses a threshold and back within the dwell changes nothing. Every reading is
judged as it comes, not only at the watcher's steps, so a dip between two steps still breaks
a run. Before its first reading a variable is unknown, and its conditions are taken to hold:
no evidence, no change.

**Silence.** A topic with no reading for ``silence`` seconds (since its last one, or since
the watch began) is said once (``context-lost``), and said again when heard
(``context-back``). Then ``lost_fails`` decides: False (``--context-lost keep``, the
default) keeps the last value; True (``fail``) takes its conditions to fail, so the
components needing it are ruled out after the dwell. Keep is the default because a silent
publisher is a fault of the sensor's process, not a measurement: a watch acts only on what
it has confirmed, and replacing a working configuration on no reading would act on a guess.

Every change is said as an event (``context``: the component, whether it is usable, the
values and the conditions, in the design-time reports' words). Nothing here prints or acts.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from rosreconf.model import Component, ComponentLibrary
from rosreconf.model.context import ContextValue, ContextVariable, rule_out, show

Say = Callable[..., None]

DWELL = 2.0
"""Seconds a component's usability must be said without a break before it changes: two
readings of a 1 Hz topic (the slowest rate of a sensor a robot acts on), and well inside the
time a mission's conditions take to change."""
SILENCE = 5.0
"""Seconds without a reading before a topic is said silent: the diagnostic aggregator's
default ``timeout`` for a status, after which it marks it stale."""


@dataclass
class _Usability:
    """What the readings say of one conditioned component, and what counts (after the dwell)."""

    usable: bool = True
    said: bool = True
    since: float = 0.0
    reason: str = ""
    values: dict[str, ContextValue] = field(default_factory=dict)


@dataclass(frozen=True)
class VariableState:
    """One context variable as a face shows it (``facestate.context_rows``)."""

    name: str
    topic: str
    value: ContextValue | None
    lost: bool
    rules_out: tuple[tuple[str, str], ...]
    """(component, why) of the components it rules out now."""


@dataclass
class LiveContext:
    """The context values read live, and the components they rule out after the dwell.

    Attributes:
        library: the context variables and the components' conditions.
        dwell: seconds a change of usability must last before it counts (``--dwell``).
        silence: seconds without a reading before a topic is silent (``--context-silence``).
        lost_fails: a silent topic's conditions fail (``--context-lost fail``), else its
            last value is kept.
        begun: when the topics were first listened to (monotonic; ``listening``): a topic
            never heard is silent ``silence`` seconds after it.
    """

    library: ComponentLibrary
    dwell: float = DWELL
    silence: float = SILENCE
    lost_fails: bool = False
    begun: float = field(default_factory=time.monotonic)
    _values: dict[str, ContextValue] = field(default_factory=dict)
    _heard: dict[str, float] = field(default_factory=dict)
    _lost: set[str] = field(default_factory=set)
    _back: set[str] = field(default_factory=set)
    _errors: dict[str, str] = field(default_factory=dict)
    _usability: dict[str, _Usability] = field(default_factory=dict)
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def __post_init__(self) -> None:
        self._usability = {c.name: _Usability(since=self.begun) for c in self.conditioned}

    @property
    def variables(self) -> tuple[ContextVariable, ...]:
        """The variables read: the library's declared context."""
        return self.library.context

    @property
    def conditioned(self) -> list[Component]:
        """The components with a ``when``: the only ones context can rule out."""
        return [c for c in self.library if c.when]

    def listening(self, at: float | None = None) -> None:
        """Note that the subscriptions are made: silence is counted from now, not from when
        the watch began (its first read and its face take seconds to come up)."""
        with self._lock:
            self.begun = time.monotonic() if at is None else at
            for u in self._usability.values():
                u.since = max(u.since, self.begun)

    def heard(self, name: str, value: ContextValue, at: float | None = None) -> None:
        """Take one reading (any thread); judge the components conditioned on it at once."""
        now = time.monotonic() if at is None else at
        with self._lock:
            if name not in {v.name for v in self.variables}:
                return
            self._values[name] = value
            self._heard[name] = now
            if name in self._lost:  # said back at the next look; judged as heard from now
                self._lost.discard(name)
                self._back.add(name)
            self._judge(now, {name})

    def unreadable(self, name: str, why: str) -> None:
        """Note a context topic that cannot be read (any thread); said at the next look."""
        with self._lock:
            self._errors[name] = why

    def assess(self, say: Say, now: float | None = None) -> dict[str, str]:
        """Say what changed since the last look; return the components ruled out now and why.

        A silent topic (``context-lost``) or one heard again (``context-back``) is said
        once; a component whose usability has been said the other way for the dwell changes
        (``context``). Returns component -> the reason it is ruled out.
        """
        now = time.monotonic() if now is None else now
        notes: list[tuple[str, str, dict[str, Any]]] = []
        with self._lock:
            for name, why in self._errors.items():
                notes.append(("context-error", f"context {name}: {why}", {"name": name}))
            self._errors.clear()
            for v in self.variables:
                notes += self._silence(v, now)
            self._judge(now, {v.name for v in self.variables})
            for name, u in self._usability.items():
                if u.usable != u.said and now - u.since >= self.dwell:
                    u.said = u.usable
                    notes.append(self._change(name, u, now))
            out = self._ruled()
        for kind, message, data in notes:
            say(kind, message, **data)
        return out

    def ruled_out(self) -> dict[str, str]:
        """Return the components ruled out now (after the dwell), and why."""
        with self._lock:
            return self._ruled()

    def next_due(self) -> float | None:
        """Return when a dwell ends or a topic falls silent (monotonic seconds), if ever."""
        with self._lock:
            dues = [u.since + self.dwell for u in self._usability.values() if u.usable != u.said]
            dues += [
                self._heard.get(v.name, self.begun) + self.silence
                for v in self.variables
                if v.name not in self._lost
            ]
        return min(dues, default=None)

    def states(self) -> list[VariableState]:
        """Return each variable's value, silence and what it rules out (for a face)."""
        with self._lock:
            ruled = [(c, self._usability[c.name]) for c in self.conditioned]
            return [
                VariableState(
                    v.name,
                    v.topic,
                    self._values.get(v.name),
                    v.name in self._lost,
                    tuple((c.name, u.reason) for c, u in ruled
                          if not u.said and any(w.name == v.name for w in c.when)),
                )
                for v in self.variables
            ]  # fmt: skip

    def _ruled(self) -> dict[str, str]:
        return {n: u.reason for n, u in self._usability.items() if not u.said}

    def _silence(self, v: ContextVariable, now: float) -> list[tuple[str, str, dict[str, Any]]]:
        """Note a topic falling silent, or heard again; at most one note."""
        last = self._heard.get(v.name)
        quiet = now - (self.begun if last is None else last)
        if v.name in self._back:
            self._back.discard(v.name)
            value = self._values[v.name]
            return [("context-back", f"{v.name} ({v.topic}) is heard again: {show(value)}",
                     {"name": v.name, "topic": v.topic, "value": value})]  # fmt: skip
        if v.name in self._lost or quiet < self.silence:
            return []
        self._lost.add(v.name)
        since = "since the watch began" if last is None else "since its last reading"
        if self.lost_fails:
            then = "the conditions on it are taken to fail (--context-lost fail)"
        elif last is None:
            then = "the conditions on it are taken to hold until it is heard"
        else:
            then = f"its last value {show(self._values[v.name])} is kept (--context-lost keep)"
        return [("context-lost",
                 f"{v.name} ({v.topic}) is silent: no reading for {quiet:.1f} s {since}; {then}",
                 {"name": v.name, "topic": v.topic, "seconds": round(quiet, 3),
                  "policy": "fail" if self.lost_fails else "keep"})]  # fmt: skip

    def _judge(self, now: float, names: set[str]) -> None:
        """Judge the components conditioned on ``names`` under the values now."""
        values = dict(self._values)
        silent = self._lost if self.lost_fails else set()
        for c in self.conditioned:
            if not any(w.name in names for w in c.when):
                continue
            u = self._usability[c.name]
            mute = [w for w in c.when if w.name in silent]
            found = rule_out([c], {k: x for k, x in values.items() if k not in silent})
            usable = not found and not mute
            if mute:
                gone = ", ".join(sorted({w.name for w in mute}))
                reason = f"{c.name} needs {mute[0]}; {gone} is silent (--context-lost fail)"
            else:
                reason = found[0].reason if found else ""
            if usable != u.usable:
                u.usable, u.since = usable, now
            if not usable:
                u.reason = reason
            u.values = {w.name: values[w.name] for w in c.when if w.name in values}

    def _change(self, name: str, u: _Usability, now: float) -> tuple[str, str, dict[str, Any]]:
        """Say a component's usability changing, with the values and conditions."""
        comp = self.library.by_name[name]
        held = f"for {now - u.since:.1f} s, dwell {self.dwell:g} s"
        if u.said:
            given = ", ".join(f"{k} = {show(x)}" for k, x in u.values.items()) or "no reading"
            needs = " and ".join(map(str, comp.when))
            text = f"{name} is usable again: {needs} holds ({given}, {held})"
        else:
            text = f"{name} is ruled out: {u.reason} ({held})"
        return ("context", text,
                {"component": name, "usable": u.said, "values": dict(u.values),
                 "conditions": [str(w) for w in comp.when], "reason": "" if u.said else u.reason,
                 "seconds": round(now - u.since, 3)})  # fmt: skip
