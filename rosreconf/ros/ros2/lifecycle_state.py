"""Read managed (lifecycle) nodes' states by calling their ``get_state`` service over plain DDS.

Discovery shows that a node is managed (it serves ``<node>/get_state`` and publishes
``<node>/transition_event``) but not which state it is in; ``transition_event`` only carries
changes, and a node left unconfigured never sends one. So the state is asked, as
``ros2 lifecycle get`` does, from the discovery session's own participant, without ROS 2
installed: a request ``lifecycle_msgs/srv/GetState`` written on
``rq<node>/get_stateRequest`` and the answer read on ``rr<node>/get_stateReply``::

    lifecycle_msgs::srv::dds_::GetState_Request_   {uint8 structure_needs_at_least_one_member}
    lifecycle_msgs::srv::dds_::GetState_Response_  {lifecycle_msgs::msg::dds_::State_
                                                     current_state {uint8 id; string label}}

rmw_fastrtps (ROS 2's default) keeps the request identity out of the payload: the server
answers the writer's RTPS sample identity, so a plain DDS writer is answered (measured:
Jazzy and Kilted, about 10 ms once matched). rmw_cyclonedds puts a header (client GUID,
sequence number) in the payload and answers only readers it paired with the client: those
servers (and any non-eProsima participant) are not asked, and their state stays unknown.
Any reply on the topic tells the state, whoever asked. Nothing here prints.

This is the fast path, kept beside the rclpy lifecycle agent (``rosreconf.ros.ros2.lifecycle``,
which performs transitions and whose ``get_state`` calls confirm them): ``watch`` reads every
managed node's state on every poll, with at most ``STATES_TIMEOUT`` (0.1 s) to wait, and a
``StateReader`` kept across polls keeps its request/reply pairs matched. Measured: a full
graph read with states takes 18 ms median with the kept pairs, 45 ms when
each read makes new request/reply pairs; an rclpy call goes through the agent's JSON-lines
pipe on top of that. So states are read here and changed there.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Any

from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.dds import load_dds
from rosreconf.ros.ros2.discovery import Ros2Discovery
from rosreconf.ros.ros2.names import Channel, ros_name

_GET_STATE = "/get_state"

EPROSIMA = "010f"
"""The vendor id Fast DDS puts at the start of every GUID prefix (in hex, as nodes carry it)."""
STATES = {1: "unconfigured", 2: "inactive", 3: "active", 4: "finalized"}
"""lifecycle_msgs/msg/State's primary state ids."""
RESEND = 0.25
"""Seconds before an unanswered request is written again (get_state changes nothing)."""
UNKNOWN = "unknown"
"""The state of a managed node that was not asked or did not answer."""
UNANSWERED = "unanswered"
"""The state of a managed node that answered before and then left a request unanswered for
``UNANSWERED_AFTER`` s while its endpoints stayed matched: its executor runs no more (hung)."""
UNANSWERED_AFTER = 1.5
"""Seconds a node that answered before may leave a ``get_state`` unanswered before it is
``UNANSWERED``. A healthy rclpy node answers in about 10 ms; the margin is for a loaded
2-core machine running 25 nodes, where a false "hung" would fail a working component."""
UNSEEN_AFTER = 5.0
"""Seconds a node seen managed keeps being managed while discovery shows no ``get_state``
server of its, on the participant that still runs it: more than Fast DDS's 3 s heartbeat,
after which an endpoint announcement lost on the way is sent again."""

Key = tuple[str, str]
"""A node as states are read for it: its name and its participant (``LiveNode.participant``).
A node restarted under its name is another process, so another key: it is never paired with
the dead one's ``get_state`` server, nor given the state that one answered."""


def _types(dds: Any) -> tuple[Any, Any]:
    """Build the GetState request and response types (rosidl's DDS names)."""
    t, make = dds.types, dds.idl.make_idl_struct
    request = make(
        "GetState_Request_",
        "lifecycle_msgs::srv::dds_::GetState_Request_",
        {"structure_needs_at_least_one_member": t.uint8},
    )
    state = make("State_", "lifecycle_msgs::msg::dds_::State_", {"id": t.uint8, "label": str})
    name = "lifecycle_msgs::srv::dds_::GetState_Response_"
    response = make("GetState_Response_", name, {"current_state": state})
    return request, response


@dataclass
class StateReader:
    """Ask managed nodes their state, poll after poll, with one request/reply pair per node.

    Everything is kept per node and participant (``Key``). A pair (a request writer, a reply
    reader) is made once per key and kept while the node stays on that participant: making
    them on every poll would wait for DDS to match them again (hundreds of ms). Each read
    drains replies, asks once more, and waits at most ``timeout`` s for the answers; a node
    that does not answer in time keeps the state it last answered, else it is ``unknown``;
    one that answered before and has left a request unanswered for ``UNANSWERED_AFTER`` s
    is ``unanswered`` (hung), whatever it answered last.
    """

    _pairs: dict[Key, tuple[Any, Any]] = field(default_factory=dict)
    _known: dict[Key, str] = field(default_factory=dict)
    _waiting: dict[Key, float] = field(default_factory=dict)
    """node -> when its oldest request still unanswered was written (answered nodes only)."""
    _managed: dict[Key, float | None] = field(default_factory=dict)
    """node -> since when its ``get_state`` server, once seen on its participant, is unseen
    (None: seen in the last read)."""
    _types: tuple[Any, Any] | None = None

    def servers(self, session: Ros2Discovery, graph: LiveGraph) -> set[Key]:
        """Return the managed nodes of ``graph``, as ``read`` takes them.

        The nodes whose own participant serves ``<node>/get_state`` now (``managed_servers``),
        and each node seen so before that the graph still shows on that participant, until
        its ``get_state`` server has been gone from discovery for ``UNSEEN_AFTER`` s. A
        process cannot make its managed node plain (rclpy and rclcpp make the state services
        with the node and drop them with it), but a loaded host can leave an endpoint's
        announcement out of a read, or a read out of the node's endpoints: one such read
        must not call the node plain.
        Its state is then what ``read`` says of a node that did not answer (the state last
        answered there, ``unknown``, or ``unanswered``: hung), never "not managed". A node
        started anew (another participant) is judged afresh.
        """
        now, serving = time.monotonic(), managed_servers(session, graph)
        shown = {(n.name, n.participant) for n in graph.nodes}
        for node, unseen in list(self._managed.items()):
            if node in serving or node not in shown:
                del self._managed[node]  # seen again (below), or no longer run there
            elif unseen is not None and now - unseen >= UNSEEN_AFTER:
                del self._managed[node]  # its get_state server is gone: plain now
            else:
                self._managed[node] = now if unseen is None else unseen
        self._managed.update(dict.fromkeys(serving))
        self._known = {n: s for n, s in self._known.items() if n in shown}  # its process gone
        return set(self._managed)

    def read(self, session: Ros2Discovery, nodes: set[Key], *, timeout: float) -> dict[Key, str]:
        """Return (node, participant) -> state label for ``nodes`` (``servers``)."""
        for node in [n for n in self._pairs if n not in nodes]:
            del self._pairs[node]  # gone, or restarted in another process (another key)
            self._waiting.pop(node, None)
        asked = {n for n in nodes if n[1].startswith(EPROSIMA)}
        if asked:
            self._ask(session, asked, timeout)
        states, now = {}, time.monotonic()
        for node in nodes:
            states[node] = self._known.get(node, UNKNOWN)
            if now - self._waiting.get(node, now) >= UNANSWERED_AFTER:
                states[node] = UNANSWERED
        return states

    def _ask(self, session: Ros2Discovery, asked: set[Key], timeout: float) -> None:
        """Ask each node once more; record the answers that come within ``timeout`` s."""
        dds = load_dds()
        if self._types is None:
            self._types = _types(dds)
        request, response = self._types
        dp = session.participant
        for node in asked:
            if node not in self._pairs:
                topics = (f"rq{node[0]}/get_stateRequest", f"rr{node[0]}/get_stateReply")
                writer = dds.pub.DataWriter(
                    dp, dds.topic.Topic(dp, topics[0], request), qos=_qos(dds, reliable=True)
                )
                reader = dds.sub.DataReader(
                    dp, dds.topic.Topic(dp, topics[1], response), qos=_qos(dds, reliable=False)
                )
                self._pairs[node] = (writer, reader)
        pending = dict.fromkeys(asked, -RESEND)
        for node in asked:
            self._answer(node, drain=True)  # a late answer to an older request: not now's
        deadline = time.monotonic() + timeout
        while pending and time.monotonic() < deadline:
            now = time.monotonic()
            for node, sent in list(pending.items()):
                if sent >= 0 and self._answer(node):
                    del pending[node]
                    continue
                writer, reader = self._pairs[node]
                if not (
                    writer.get_publication_matched_status().current_count
                    and reader.get_subscription_matched_status().current_count
                ):
                    # not matched (yet, or its server left discovery): it cannot hear an ask
                    # or answer one, so an ask it left unanswered is no sign of a hang
                    self._waiting.pop(node, None)
                    continue
                if now - sent < RESEND:
                    continue  # asked just now
                # Ask (again): the server may not have matched our reply reader yet when we
                # matched its endpoints, and then its answer reaches no one.
                writer.write(request(structure_needs_at_least_one_member=0))
                pending[node] = now
                if node in self._known:
                    self._waiting.setdefault(node, now)  # it answered before
            time.sleep(0.005)

    def _answer(self, node: Key, *, drain: bool = False) -> bool:
        """Take ``node``'s replies; record the newest state; tell whether one came."""
        _, reader = self._pairs[node]
        got = False
        for sample in reader.take(N=16):
            if hasattr(sample, "current_state"):
                state = sample.current_state
                label = STATES.get(int(state.id), str(state.label) or UNKNOWN)
                self._known[node] = label
                got = True
        if got:
            self._waiting.pop(node, None)  # alive: a late answer counts
        return got and not drain


def _qos(dds: Any, *, reliable: bool) -> Any:
    """Return the QoS of a request writer (reliable, as rmw's service readers require) or of
    a reply reader (best effort).

    A reliable reader hands replies over in order: one reply lost on the way (a loaded host's
    UDP receive buffers overflow: this 2-core machine counts millions of such drops, in
    bursts, while tests start their nodes) holds every later reply of that node behind it
    until the server's writer says what it sent, and Fast DDS says so every 3 s (its default
    heartbeat period). The node then looks silent for up to 3 s, and ``unanswered`` (hung)
    after 1.5 s: the likely cause of twelve healthy nodes once failed at once
    as hung just after twelve standbys started. Measured with every fifth answer the
    reader's process receives lost (``tests/faults/drop_received.c``, 40 reads 0.3 s apart,
    Jazzy and Kilted alike): 11 of 40 reads said a healthy node ``unanswered`` with a
    reliable reader, none with a best-effort one. Best effort takes each reply as it comes;
    a lost one is made up by the next ask. A best-effort reader matches a reliable writer.
    """
    policy = dds.qos.Policy
    reliability = (
        policy.Reliability.Reliable(max_blocking_time=dds.util.duration(seconds=1))
        if reliable
        else policy.Reliability.BestEffort
    )
    return dds.qos.Qos(
        reliability,
        policy.Durability.Volatile,
        policy.History.KeepLast(1),
        policy.DataRepresentation(use_cdrv0_representation=True),
    )


def managed_servers(session: Ros2Discovery, graph: LiveGraph) -> set[Key]:
    """Return the nodes of ``graph`` whose own participant serves ``<node>/get_state``.

    Read from the request readers the session's last read saw (``rq<node>/get_stateRequest``),
    each paired with the node of that name on the same participant only: a process known dead
    is announced until its lease ends, and its unanswered query must never be read as the
    state of the node started anew under its name (another participant, another process).
    """
    servers: set[Key] = set()
    for e in session.last_endpoints.values():
        named = ros_name(e.topic)
        if e.writer or named is None or named[0] is not Channel.REQUEST:
            continue
        if named[1].endswith(_GET_STATE):
            servers.add((named[1][: -len(_GET_STATE)], e.participant.hex()))
    return servers & {(n.name, n.participant) for n in graph.nodes}


def with_states(
    session: Ros2Discovery,
    graph: LiveGraph,
    *,
    timeout: float = 3.0,
    reader: StateReader | None = None,
) -> LiveGraph:
    """Return ``graph`` with every managed node's lifecycle state read (others: None).

    A managed node is one serving ``<node>/get_state``, or one seen so that still runs on
    the same participant (``StateReader.servers``). ``reader`` keeps what it asked with and
    what it saw from one read to the next (a fresh one: every pair made anew).
    """
    reader = reader or StateReader()
    states = reader.read(session, reader.servers(session, graph), timeout=timeout)
    nodes = (replace(n, lifecycle_state=states.get((n.name, n.participant))) for n in graph.nodes)
    return replace(graph, nodes=tuple(nodes))
