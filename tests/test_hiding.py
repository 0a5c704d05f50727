"""Tests of the hiding of dead processes' participants, and of per-participant state pairing.

Pure: no DDS. The source only reads, and every ROS 2 node carries its participant
(``LiveNode.participant``); the actuator's ``exits.OwnExits`` leaves the participants of
processes known dead out of the graph and of the participant lists its parts find processes
from. A node restarted under its name is another participant: its lifecycle state is read
from its own ``get_state`` server only (``lifecycle_state``), never the dead process's.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import cast

import pytest

from rosreconf.errors import InvalidInputError
from rosreconf.model.qos import QosProfile
from rosreconf.ros.livegraph import LiveGraph, LiveNode, from_json, to_json
from rosreconf.ros.ros2.discovery import Ros2Discovery
from rosreconf.ros.ros2.exits import OwnExits
from rosreconf.ros.ros2.graph import Endpoint
from rosreconf.ros.ros2.lifecycle_state import UNKNOWN, StateReader, managed_servers, with_states
from rosreconf.ros.ros2.nodes import NodeProcesses

# Cyclone-like GUIDs (not eProsima's 01 0f): the state reader never asks them over DDS.
DEAD = bytes.fromhex("01100000000000000000000a000001c1")
NEW = bytes.fromhex("01100000000000000000000b000001c1")
OTHER = bytes.fromhex("01100000000000000000000c000001c1")
AT = datetime(2026, 1, 1, tzinfo=UTC)


def _graph(*nodes: tuple[str, bytes]) -> LiveGraph:
    live = tuple(
        LiveNode(name, alive=True, serves=(f"{name}/get_state",), participant=p.hex())
        for name, p in nodes
    )
    return LiveGraph("ros2://domain/0", AT, live, ros_version=2)


def _exits(participants: dict[bytes, tuple[str, ...]]) -> OwnExits:
    return OwnExits(
        cast(NodeProcesses, None), lambda: participants, lambda _: None, lambda *a, **k: None
    )


def _shown(graph: LiveGraph) -> list[tuple[str, bytes]]:
    return [(n.name, bytes.fromhex(n.participant)) for n in graph.nodes]


# hidden participants, dead names, graph -> what the actuator shows, hidden afterwards
FILTER_CASES = {
    "nothing hidden": (set(), set(), [("/a", DEAD)], [("/a", DEAD)], set()),
    "dead process left out, its restart kept": (
        {DEAD},
        set(),
        [("/a", DEAD), ("/a", NEW)],
        [("/a", NEW)],
        {DEAD},
    ),
    "every node of a hidden participant": (
        {DEAD},
        set(),
        [("/a", DEAD), ("/b", DEAD), ("/c", OTHER)],
        [("/c", OTHER)],
        {DEAD},
    ),
    "gone from the graph: no longer hidden": ({DEAD}, set(), [("/a", NEW)], [("/a", NEW)], set()),
    "an own process seen to end: its name": (
        set(),
        {"/a"},
        [("/a", DEAD), ("/b", OTHER)],
        [("/b", OTHER)],
        set(),
    ),
}


@pytest.mark.parametrize(
    ("hidden", "dead", "nodes", "shown", "after"),
    FILTER_CASES.values(),
    ids=list(FILTER_CASES),
)
def test_own_exits_filter(
    hidden: set[bytes],
    dead: set[str],
    nodes: list[tuple[str, bytes]],
    shown: list[tuple[str, bytes]],
    after: set[bytes],
) -> None:
    exits = _exits({})
    exits.hide(hidden)
    exits.dead |= dead
    graph = _graph(*nodes)
    assert _shown(exits.visible(exits.unhidden(graph))) == shown
    assert exits.hidden == after


def test_filter_returns_the_same_graph_when_nothing_is_hidden() -> None:
    graph = _graph(("/a", NEW))
    exits = _exits({})
    assert exits.visible(exits.unhidden(graph)) is graph


def test_alive_participants_leave_the_hidden_out() -> None:
    exits = _exits({DEAD: ("/a",), NEW: ("/a",), OTHER: ("/b",)})
    exits.hide({DEAD})
    assert exits.alive() == {NEW: ("/a",), OTHER: ("/b",)}


@dataclass
class FakeSession:
    """What the state reader reads of a discovery session: the endpoints last seen."""

    endpoints: list[tuple[str, bytes]] = field(default_factory=list)

    @property
    def last_endpoints(self) -> dict[bytes, Endpoint]:
        found = {}
        for i, (node, participant) in enumerate(self.endpoints):
            guid = participant[:12] + bytes([0, 0, i, 4])
            topic = f"rq{node}/get_stateRequest"
            found[guid] = Endpoint(guid, participant, topic, "t", False, QosProfile(), b"")
        return found


# get_state servers (node, participant), graph -> the (node, participant) keys managed
PAIRING_CASES = {
    "own server": ([("/a", NEW)], [("/a", NEW)], {("/a", NEW)}),
    "a dead process's server never pairs with its restart": (
        [("/a", DEAD)],
        [("/a", DEAD), ("/a", NEW)],
        {("/a", DEAD)},
    ),
    "each of two processes with its own": (
        [("/a", DEAD), ("/a", NEW)],
        [("/a", DEAD), ("/a", NEW)],
        {("/a", DEAD), ("/a", NEW)},
    ),
    "a server of a node not in the graph": ([("/a", DEAD)], [("/a", NEW)], set()),
    "another node's participant": ([("/b", OTHER)], [("/a", OTHER)], set()),
}


@pytest.mark.parametrize(
    ("servers", "nodes", "managed"), PAIRING_CASES.values(), ids=list(PAIRING_CASES)
)
def test_state_servers_pair_per_participant(
    servers: list[tuple[str, bytes]],
    nodes: list[tuple[str, bytes]],
    managed: set[tuple[str, bytes]],
) -> None:
    session = cast(Ros2Discovery, FakeSession(servers))
    keys = {(n, p.hex()) for n, p in managed}
    assert managed_servers(session, _graph(*nodes)) == keys
    assert StateReader().servers(session, _graph(*nodes)) == keys


def test_a_restarted_node_never_gets_the_dead_process_state() -> None:
    """The dead process answered ``active``; its restart under the name has not answered."""
    session = cast(Ros2Discovery, FakeSession([("/a", DEAD), ("/a", NEW)]))
    reader = StateReader()
    reader._known[("/a", DEAD.hex())] = "active"
    graph = with_states(session, _graph(("/a", DEAD), ("/a", NEW)), reader=reader, timeout=0)
    assert {(n.participant, n.lifecycle_state) for n in graph.nodes} == {
        (DEAD.hex(), "active"),
        (NEW.hex(), UNKNOWN),
    }


def test_a_state_is_forgotten_with_its_process() -> None:
    session = cast(Ros2Discovery, FakeSession([("/a", NEW)]))
    reader = StateReader()
    reader._known[("/a", DEAD.hex())] = "active"
    with_states(session, _graph(("/a", NEW)), reader=reader, timeout=0)
    assert ("/a", DEAD.hex()) not in reader._known


def test_snapshot_round_trips_the_participant() -> None:
    graph = _graph(("/a", DEAD), ("/a", NEW))
    text = to_json(graph)
    assert f'"participant": "{NEW.hex()}"' in text
    assert from_json(text) == graph


def test_snapshot_refuses_a_participant_that_is_no_guid() -> None:
    text = to_json(_graph(("/a", NEW))).replace(NEW.hex(), "not-a-guid")
    with pytest.raises(InvalidInputError, match="participant"):
        from_json(text)
