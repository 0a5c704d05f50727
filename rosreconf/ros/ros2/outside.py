"""Watch the processes of configuration nodes rosreconf did not start (detection).

A node the team's own launch files started is seen failing by DDS only when its lease runs
out (Fast DDS: 20 s). On this host its process can be watched instead: ``hostprocs``
confirms which process runs a participant (its Fast DDS GUID, proved through /proc, never
guessed), and ``pidwatch`` sees that process exit in milliseconds (a pidfd) or stop (state
``T``: SIGSTOP, a tracer). So::

    node of the configuration                     how its failure is seen
    --------------------------------------------  ------------------------------------------
    started by rosreconf                          its process's exit (``nodes``), at once
    outside, process confirmed on this host       its process's exit at once; stopped for
                                                  ``HUNG_SECONDS``: hung, failed
    outside, not confirmed (another host, another the DDS lease only; said once per node,
    middleware, /proc not readable, ambiguous)     with why
    outside, its process proven gone when looked   at once (``hostprocs``' ``GONE``: killed
    for (this host's GUID, no process could hold   before it was located), unless another
    it)                                            participant runs the node too

A process that runs several nodes (a component container, an executor with many nodes)
fails them all at once. Nothing here signals a process: stopping outside nodes is not this
module's business. Every decision is said through ``say``; nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

from rosreconf.ros.ros2.hostprocs import Found, HostProcesses, ProcId, boot_seconds
from rosreconf.ros.ros2.pidwatch import ProcessWatch
from rosreconf.ros.ros2.provenance import SourcePorts
from rosreconf.ros.ros2.stopproc import Stopped, StopResult, stop_node_process

HUNG_SECONDS = 1.0
"""Seconds a watched process may stay stopped before its nodes count as hung (failed)."""


@dataclass
class OutsideNodes:
    """The watched processes of one domain's outside nodes (see the module docstring).

    Attributes:
        domain: the DDS domain the participants are on (their ports prove their processes).
        say: receives the ``watched`` events (by process, or by lease and why).
        nodes: confirmed process -> the nodes it runs.
        lease_only: node -> why it is watched by its DDS lease only.
        seen_at: participant -> when it was first seen (seconds since boot), so that a
            process started after it cannot be taken for it.
        stopped_since: process -> when it was first found stopped (``time.monotonic``).
        gone: node -> how its process ended (``exited`` or ``hung``), until ``take`` says it.
        located: the participants whose process was looked for (each once: a node that
            comes back has a participant of its own).
        hung: the processes found stopped for ``HUNG_SECONDS`` -> their nodes (no longer
            watched, but still there to be stopped).
        participant_of: watched process -> the participant it was confirmed to run.
        prove: listen for the evidence that lets a process be signalled (``--stop-outside``;
            ``provenance``): without it, nothing is ever signalled.
        guid_of: each confirmed process -> its participant, for the proof (kept while the
            process is known, hung ones too).
        theirs: the wanted nodes found running in a process rosreconf did not start, until
            rosreconf starts them itself (``forget``): what started them restarts them.
        ended: the participants of processes found exited or hung, until ``take_ended``:
            what the graph must leave out (DDS announces them until their lease ends). The
            participant, never the node name: a team may have restarted the node already,
            and its new participant must be seen (a restart by hand noticed before its
            predecessor's exit was hidden for ever, when the name was hidden).
    """

    domain: int
    say: Callable[..., None]
    nodes: dict[ProcId, tuple[str, ...]] = field(default_factory=dict)
    lease_only: dict[str, str] = field(default_factory=dict)
    seen_at: dict[bytes, float] = field(default_factory=dict)
    stopped_since: dict[ProcId, float] = field(default_factory=dict)
    gone: dict[str, str] = field(default_factory=dict)
    located: set[bytes] = field(default_factory=set)
    hung: dict[ProcId, tuple[str, ...]] = field(default_factory=dict)
    participant_of: dict[ProcId, bytes] = field(default_factory=dict)
    ended: set[bytes] = field(default_factory=set)
    prove: bool = False
    guid_of: dict[ProcId, bytes] = field(default_factory=dict)
    theirs: set[str] = field(default_factory=set)
    _watch: ProcessWatch = field(default_factory=ProcessWatch)
    _sources: SourcePorts | None = None

    def __post_init__(self) -> None:
        if self.prove:  # only processes the kernel ties to their datagrams are signalled
            self._sources = SourcePorts(self.domain).start()

    @property
    def watched(self) -> set[str]:
        """Return the nodes watched by their process now."""
        return {n for names in self.nodes.values() for n in names}

    def track(self, participants: Mapping[bytes, tuple[str, ...]], wanted: Collection[str]) -> None:
        """Find and watch the processes of ``wanted`` nodes not watched or explained yet.

        ``participants``: each alive participant's GUID -> its nodes (the last read).
        /proc is scanned only when such a node shows up, not on every poll.
        """
        now = boot_seconds()
        for guid in participants:
            self.seen_at.setdefault(guid, now)
        new = {
            g: ns
            for g, ns in participants.items()
            if g not in self.located and any(n in wanted for n in ns)
        }
        if not new:
            return
        host = HostProcesses()
        found_all = {
            g: host.locate(g, self.domain, ns, seen_at=self.seen_at[g]) for g, ns in new.items()
        }
        dead = {g for g, f in found_all.items() if f.found is Found.GONE}
        # a node another participant runs too (restarted, its predecessor's participant still
        # announced until its lease ends) is not gone: only the dead participant is
        running = {n for g, ns in participants.items() if g not in dead for n in ns}
        for guid, names in sorted(new.items()):
            self.located.add(guid)
            found = found_all[guid]
            mine = [n for n in names if n in wanted]
            self.theirs.update(mine)
            if guid in dead:
                self._gone_at_once(guid, [n for n in names if n not in running], found.detail)
                continue
            if found.proc is not None:  # one that exited already: the next poll says so
                self._watch.add(found.proc)
                self.nodes[found.proc] = names
                self.participant_of[found.proc] = guid
                self.guid_of[found.proc] = guid
                self.say(
                    "watched",
                    f"{', '.join(mine)}: watched by its process (pid {found.proc.pid}; "
                    f"{found.detail}): a crash is seen at once, not after the DDS lease",
                    nodes=list(names),
                    pid=found.proc.pid,
                    how="process",
                )
                continue
            for n in mine:
                self.lease_only[n] = found.detail
            self.say(
                "watched",
                f"{', '.join(mine)}: watched by the DDS lease only ({found.detail})",
                nodes=mine,
                how="lease",
                why=found.detail,
            )

    def _gone_at_once(self, guid: bytes, names: list[str], detail: str) -> None:
        """Take a participant whose process is proven gone as one that exited just now."""
        self.ended.add(guid)
        for n in names:
            self.gone[n] = "exited"
        if names:
            self.say(
                "watched",
                f"{', '.join(names)}: its process is gone already ({detail}): failed now, "
                "not after the DDS lease",
                nodes=names,
                how="gone",
                why=detail,
            )

    def poll(self) -> bool:
        """Read the watched processes' exits and stops now; tell whether a node is gone."""
        events = self._watch.poll(0.0)
        for proc in events.exited:
            self.stopped_since.pop(proc, None)
            self._ended(proc)
            for n in self.nodes.pop(proc, ()):
                self.gone[n] = "exited"
        for proc in events.stopped:
            self.stopped_since.setdefault(proc, time.monotonic())
        for proc in events.resumed:
            self.stopped_since.pop(proc, None)
        for proc, since in list(self.stopped_since.items()):
            if time.monotonic() - since >= HUNG_SECONDS:
                del self.stopped_since[proc]
                self._watch.remove(proc)
                self.hung[proc] = self.nodes.pop(proc, ())
                self._ended(proc)
                for n in self.hung[proc]:
                    self.gone[n] = "hung"
        return bool(self.gone)

    def take(self) -> dict[str, str]:
        """Return node -> ``exited`` or ``hung`` for the nodes found gone, and forget them.

        A node that comes back (restarted by its team) is tracked afresh by ``track``: its
        new process is a new participant.
        """
        self.poll()
        gone, self.gone = self.gone, {}
        return gone

    def _ended(self, proc: ProcId) -> None:
        if (guid := self.participant_of.pop(proc, None)) is not None:
            self.ended.add(guid)

    def take_ended(self) -> set[bytes]:
        """Return the participants whose process ended or hung since last asked, and forget."""
        ended, self.ended = self.ended, set()
        return ended

    def forget(self, nodes: Collection[str]) -> None:
        """Stop watching these nodes' processes (replaced, or started by rosreconf now)."""
        for proc, names in list(self.nodes.items()):
            if set(names) & set(nodes):
                del self.nodes[proc]
                self.participant_of.pop(proc, None)
                self.guid_of.pop(proc, None)
                self._watch.remove(proc)
        for n in nodes:
            self.lease_only.pop(n, None)
            self.theirs.discard(n)

    def drop(self, proc: ProcId) -> None:
        """Stop watching ``proc``: it runs no component (a squatter on a component's name)."""
        self.nodes.pop(proc, None)
        self.hung.pop(proc, None)
        self.stopped_since.pop(proc, None)
        self.participant_of.pop(proc, None)
        self._watch.remove(proc)

    def process_of(self, node: str) -> tuple[ProcId, tuple[str, ...]] | None:
        """Return the confirmed process of ``node`` (watched, or hung) and every node it runs."""
        for proc, names in (*self.nodes.items(), *self.hung.items()):
            if node in names:
                return proc, names
        return None

    def stop(self, nodes: Collection[str]) -> dict[str, StopResult | None]:
        """Stop the confirmed process of each of ``nodes`` unless it runs other nodes
        (``stopproc``); the stops run at once, so their grace periods overlap.

        node -> its result; None when no process of it is known. A process stopped, or gone
        already, is forgotten. Two nodes of one process are never signalled: ``stopproc``
        refuses a process that runs more than the node it is asked to stop.
        """
        known = {n: k for n in nodes if (k := self.process_of(n)) is not None}
        results: dict[str, StopResult | None] = dict.fromkeys(nodes)
        if not known:
            return results
        with ThreadPoolExecutor(max_workers=len(known)) as pool:
            futures = {
                n: pool.submit(self._stop_proven, proc, n, names)
                for n, (proc, names) in known.items()
            }
        for node, future in futures.items():
            proc, result = known[node][0], future.result()
            if result.outcome in (Stopped.STOPPED, Stopped.GONE):
                self.nodes.pop(proc, None)
                self.hung.pop(proc, None)
                self.guid_of.pop(proc, None)
                self.stopped_since.pop(proc, None)
                self._watch.remove(proc)
            results[node] = result
        return results

    def _stop_proven(self, proc: ProcId, node: str, names: tuple[str, ...]) -> StopResult:
        """Stop ``proc`` for ``node`` only once the kernel proved it sends its datagrams."""
        return self.stop_proven(proc, self.guid_of.get(proc), node, names)

    def stop_proven(
        self, proc: ProcId, guid: bytes | None, node: str, names: tuple[str, ...]
    ) -> StopResult:
        """Stop ``proc``, said to run participant ``guid`` and ``node`` (and ``names``), only
        once the kernel proved it sends that participant's datagrams (``provenance``).
        """
        if self._sources is None or guid is None:
            why = "no evidence was gathered"
        elif (unproven := self._sources.unproven(guid, proc)) is not None:
            why = unproven
        else:
            return stop_node_process(proc, node, names)
        return StopResult(Stopped.UNPROVEN, node, proc, why=why)

    def close(self) -> None:
        """Release the pidfds and stop listening for evidence."""
        self._watch.close()
        if self._sources is not None:
            self._sources.close()
