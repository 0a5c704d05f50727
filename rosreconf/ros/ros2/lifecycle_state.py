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
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.dds import load_dds
from rosreconf.ros.ros2.discovery import Ros2Discovery
from rosreconf.ros.ros2.names import Channel, ros_name

_GET_STATE = "/get_state"

EPROSIMA = b"\x01\x0f"
"""The vendor id Fast DDS puts at the start of every GUID prefix."""
STATES = {1: "unconfigured", 2: "inactive", 3: "active", 4: "finalized"}
"""lifecycle_msgs/msg/State's primary state ids."""
RESEND = 0.25
"""Seconds before an unanswered request is written again (get_state changes nothing)."""
UNKNOWN = "unknown"
"""The state of a managed node that was not asked or did not answer."""


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


def read_states(
    session: Ros2Discovery, nodes: dict[str, bytes], *, timeout: float = 3.0
) -> dict[str, str]:
    """Ask each managed node its lifecycle state; return node -> state label.

    ``nodes`` maps a node's global name to the participant GUID of its ``get_state`` server.
    A node whose server is not Fast DDS's, or that does not answer within ``timeout`` s,
    is ``unknown``.
    """
    states = {n: UNKNOWN for n in nodes}
    asked = {n: p for n, p in nodes.items() if p.startswith(EPROSIMA)}
    if not asked:
        return states
    dds = load_dds()
    policy, dp = dds.qos.Policy, session.participant
    request, response = _types(dds)
    qos = dds.qos.Qos(
        policy.Reliability.Reliable(max_blocking_time=dds.util.duration(seconds=1)),
        policy.Durability.Volatile,
        policy.History.KeepLast(1),
        policy.DataRepresentation(use_cdrv0_representation=True),
    )
    pending: dict[str, tuple[Any, Any]] = {}
    for node in asked:
        writer = dds.pub.DataWriter(
            dp, dds.topic.Topic(dp, f"rq{node}/get_stateRequest", request), qos=qos
        )
        reader = dds.sub.DataReader(
            dp, dds.topic.Topic(dp, f"rr{node}/get_stateReply", response), qos=qos
        )
        pending[node] = (writer, reader)
    sent: dict[str, float] = {}
    deadline = time.monotonic() + timeout
    while pending and time.monotonic() < deadline:
        now = time.monotonic()
        for node, (writer, reader) in list(pending.items()):
            for sample in reader.take(N=16):
                if hasattr(sample, "current_state"):
                    state = sample.current_state
                    states[node] = STATES.get(int(state.id), str(state.label) or UNKNOWN)
                    del pending[node]
                    break
            else:
                if now - sent.get(node, -RESEND) < RESEND or not (
                    writer.get_publication_matched_status().current_count
                    and reader.get_subscription_matched_status().current_count
                ):
                    continue  # asked just now, or the server's endpoints are not matched yet
                # Ask (again): the server may not have matched our reply reader yet when we
                # matched its endpoints, and then its answer reaches no one.
                writer.write(request(structure_needs_at_least_one_member=0))
                sent[node] = now
        time.sleep(0.01)
    return states


def with_states(session: Ros2Discovery, graph: LiveGraph, *, timeout: float = 3.0) -> LiveGraph:
    """Return ``graph`` with every managed node's lifecycle state read (others: None).

    A managed node is one serving ``<node>/get_state`` (its request reader on
    ``rq<node>/get_stateRequest``, as the session's last read saw it).
    """
    servers: dict[str, bytes] = {}
    for e in session.last_endpoints.values():
        named = ros_name(e.topic)
        if e.writer or named is None or named[0] is not Channel.REQUEST:
            continue
        if named[1].endswith(_GET_STATE):
            servers[named[1][: -len(_GET_STATE)]] = e.participant
    names = {n.name for n in graph.nodes}
    states = read_states(session, {n: p for n, p in servers.items() if n in names}, timeout=timeout)
    nodes = tuple(replace(n, lifecycle_state=states.get(n.name)) for n in graph.nodes)
    return replace(graph, nodes=nodes)
