"""Perform lifecycle transitions through rosreconf's lifecycle agent, and say each one.

The actuator's parts (``actuator``, ``bringup``, ``standby``) decide which managed node goes
to which state; this module owns the talking: the agent process
(``rosreconf.ros.ros2.lifecycle.LifecycleAgent``, started on first use and not retried once
it could not start), one batch request per group of transitions, each confirmed by reading
the state back (kept here alone: ``state``, ``forget``), and one ``lifecycle`` event per
outcome. Nothing here raises for a failed transition: a failure is said and returned.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.ros.ros2.fastdds_ids import may_be_of
from rosreconf.ros.ros2.lifecycle import AGENT_NODE, HUNG_SECONDS, TIMEOUT, LifecycleAgent, Outcome
from rosreconf.ros.ros2.runtime import node_env, own_profile

START_AGAIN_FIRST = 5.0
"""Seconds after a lifecycle agent failed to start before it is started again (then doubled)."""
START_AGAIN_MOST = 60.0
"""The longest wait between two starts of an agent that keeps failing to start: each start
may hold the watch loop for 10 s (``ANSWER_SECONDS``), so at most a seventh of its time."""


@dataclass
class Transitions:
    """The lifecycle agent of one watcher, and the states it read back.

    Attributes:
        env: the environment the agent runs in (ROS_DOMAIN_ID set).
        directory: where the agent's log goes.
        say: receives every event.
        node_of: component -> its live node name.
        timeout: seconds each transition may take.
        states: component -> the lifecycle state last read back.
        helpers: agent deaths seen, each once, for the caller to say. A helper's death is no
            component's failure: a dead agent is started anew, and a request it died in is
            asked again of the new one, once.
        timeouts: component -> when its last transition timed out (``Outcome.timed_out``,
            or the agent could not be asked), until one of its transitions is answered:
            what ``rosreconf.ros.ros2.retrying`` tries again.
        dead_agents: the pids of agents that died, until their participants are seen
            (``ghosts``).
    """

    env: Mapping[str, str]
    directory: Path
    say: Callable[..., None]
    node_of: Callable[[str], str]
    timeout: float = TIMEOUT
    states: dict[str, str] = field(default_factory=dict)
    helpers: list[str] = field(default_factory=list)
    timeouts: dict[str, float] = field(default_factory=dict)
    dead_agents: set[int] = field(default_factory=set)
    _agent: LifecycleAgent | None = None
    _agent_error: str | None = None
    _agent_retry_at: float = 0.0
    _agent_backoff: float = START_AGAIN_FIRST

    def _agent_died(self) -> bool:
        """Note an agent that ended on its own (killed, crashed) or hung; True if so.

        A hung agent (stopped, deadlocked: silent for ``HUNG_SECONDS``) is killed, and from
        then on it is a dead one: started anew, its request asked again of the new one.
        """
        agent = self._agent
        if agent is None:
            return False
        hung = agent.died() is None and agent.hung()
        if agent.died() is None and not hung:
            return False
        self._agent = None
        agent.close()
        self.dead_agents.add(agent.process.pid)
        how = (
            f"was hung (said nothing for {HUNG_SECONDS:g} s): killed"
            if hung
            else f"exited ({agent.process.returncode})"
        )
        self.helpers.append(
            f"{agent.name} (pid {agent.process.pid}) {how}, and started anew (a helper's "
            "death is no component's failure)"
        )
        return True

    def state(self, component: str) -> str | None:
        """Return the lifecycle state last read back from ``component``'s node, if any."""
        return self.states.get(component)

    def forget(self, component: str) -> None:
        """Forget ``component``'s state: its process is gone, and a new one starts unconfigured."""
        self.states.pop(component, None)

    def take_helpers(self) -> list[str]:
        """Return the agent deaths seen since the last call; a dead agent is started anew."""
        if self._agent_died():
            with contextlib.suppress(ExternalToolError):  # said by the next call, if it fails
                self.agent()
        helpers, self.helpers = self.helpers, []
        return helpers

    def ghosts(self, participants: Mapping[bytes, Collection[str]]) -> set[bytes]:
        """Return the participants of the agents that died, among ``participants``.

        A killed agent's participant is announced until its lease ends: its node beside the
        new agent's would be two nodes of one name, a duplicate that is nobody's doing
        (fresh clone: said, then "conformant" again, in the middle of a repair). Only a
        participant naming the agent's node and carrying a dead agent's pid bits is one.
        """
        found: set[bytes] = set()
        for pid in list(self.dead_agents):  # one participant each; kept until it is seen
            ghost = {g for g, ns in participants.items() if AGENT_NODE in ns and may_be_of(g, pid)}
            if ghost:
                found |= ghost
                self.dead_agents.discard(pid)
        return found

    def agent(self) -> LifecycleAgent:
        """Return the lifecycle agent, started on first use (and again after it died).

        An agent that could not start (no ``ready`` within 10 s: a host too loaded to import
        rclpy in time, or a broken ROS 2 Python) is started again ``START_AGAIN_FIRST`` s
        later, then after twice as long each time up to ``START_AGAIN_MOST``; until then a
        call fails at once with the error, as each start may hold the watch loop 10 s.
        """
        self._agent_died()
        if self._agent is None:
            now = time.monotonic()
            if self._agent_error is not None and now < self._agent_retry_at:
                left = self._agent_retry_at - now
                raise ExternalToolError(f"{self._agent_error}; started again in {left:.0f} s")
            self.directory.mkdir(parents=True, exist_ok=True)
            try:
                env = node_env(self.env, own_profile(self.directory))  # one of rosreconf's own
                self._agent = LifecycleAgent(
                    env, self.directory / "lifecycle-agent.log", self.timeout
                )
            except ExternalToolError as exc:
                self._agent_error = str(exc)
                self._agent_retry_at = time.monotonic() + self._agent_backoff
                self._agent_backoff = min(2 * self._agent_backoff, START_AGAIN_MOST)
                raise
            if self._agent_error is not None:
                why = self._agent_error.removeprefix(f"{self._agent.name} ")
                self.helpers.append(
                    f"{self._agent.name} (pid {self._agent.process.pid}) started, after a "
                    f"start that failed: it {why}"
                )
                self._agent_error, self._agent_backoff = None, START_AGAIN_FIRST
        return self._agent

    def call(self, call: Callable[[LifecycleAgent], Any]) -> Any:
        """Ask the lifecycle agent something; a failure is said (never raised), None returned."""
        try:
            try:
                return call(self.agent())
            except ExternalToolError:
                if not self._agent_died():
                    raise
                return call(self.agent())  # it died in this call: once more, of a new one
        except ExternalToolError as exc:
            self.say("lifecycle", f"lifecycle agent: {exc}", ok=False, error=str(exc))
            return None

    def perform(
        self,
        steps: list[tuple[str, str]],
        appear: float | None = None,
        timeout: float | None = None,
    ) -> dict[str, bool]:
        """Perform several (component, transition) at once; say each; component -> ok.

        ``timeout``: seconds each may take (default: ``self.timeout``). A step listed twice is
        performed once (the agent asks each node once per batch).
        """
        steps = list(dict.fromkeys(steps))
        if not steps:
            return {}
        nodes = {self.node_of(c): c for c, _ in steps}
        items = [(self.node_of(c), t) for c, t in steps]
        try:
            try:
                outcomes = self.agent().transitions(items, appear, timeout)
            except ExternalToolError:
                if not self._agent_died():
                    raise
                outcomes = self.agent().transitions(items, appear, timeout)  # once more
        except ExternalToolError as exc:
            return {c: self.failed(c, t, str(exc)) for c, t in steps}
        return {nodes[o.node]: self._said(nodes[o.node], o) for o in outcomes}

    def failed(self, component: str, transition: str, error: str) -> bool:
        """Say that ``transition`` of ``component`` failed, and why; return False."""
        self.timeouts[component] = time.monotonic()  # the agent was not asked: nothing known
        node = self.node_of(component)
        self.say(
            "lifecycle",
            f"{node}: {transition} failed: {error}",
            component=component,
            node=node,
            transition=transition,
            ok=False,
            error=error,
        )
        return False

    def _said(self, component: str, outcome: Outcome) -> bool:
        """Say how one transition went (event ``lifecycle``); return whether it held."""
        if outcome.state is not None:
            self.states[component] = outcome.state
        if outcome.timed_out:
            self.timeouts[component] = time.monotonic()
        else:
            self.timeouts.pop(component, None)  # answered: done, or refused for good
        result = (
            f"now {outcome.state} ({outcome.seconds * 1000:.0f} ms)"
            if outcome.ok
            else f"failed: {outcome.error}"
        )
        self.say(
            "lifecycle",
            f"{outcome.node}: {outcome.transition} {result}",
            component=component,
            node=outcome.node,
            transition=outcome.transition,
            ok=outcome.ok,
            state=outcome.state,
            seconds=round(outcome.seconds, 4),
            **({"error": outcome.error} if outcome.error else {}),
        )
        return bool(outcome.ok)

    def close(self) -> None:
        """End the agent, if it was started."""
        if self._agent is not None:
            self._agent.close()
            self._agent = None
