"""Which ROS 2 participants a read waits for, and which it asks again: a table of cases.

A participant whose ``ros_discovery_info`` never decoded is "silent" once its discovery
writer has been known for the grace period: its nodes are left out (a wrong ``--distro``),
and the watch makes fresh readers for it, as for a stale one (its single sample may have
been lost to the old reader, and nothing else sends it again).
"""

from __future__ import annotations

import pytest

from rosreconf.model.qos import QosProfile
from rosreconf.ros.ros2.graph import Endpoint, silent_participants, writing_since
from rosreconf.ros.ros2.names import DISCOVERY_TOPIC

A, B, C = b"A" * 16, b"B" * 16, b"C" * 16


def _writer(participant: bytes, topic: str = DISCOVERY_TOPIC) -> Endpoint:
    return Endpoint(participant + b"w", participant, topic, "T", True, QosProfile(), b"")


@pytest.mark.parametrize(
    ("infos", "first_seen", "now", "silent"),
    [
        ({}, 0.0, 4.4, set()),  # a writer just found: its sample may be on its way
        ({}, 0.0, 4.5, {A}),  # nothing decodable for the grace period
        ({A: (16, ())}, 0.0, 60.0, set()),  # it decoded once: not silent (stale, maybe)
    ],
)
def test_a_participant_is_silent_only_after_the_grace_period_with_nothing_decoded(
    infos: dict[bytes, tuple[int, tuple[()]]], first_seen: float, now: float, silent: set[bytes]
) -> None:
    since = writing_since({}, {A + b"w": _writer(A)}, first_seen)
    assert silent_participants({A}, infos, since, 4.5, now) == silent


def test_only_participants_writing_discovery_info_now_can_be_silent() -> None:
    since: dict[bytes, float] = {}
    endpoints = {B + b"w": _writer(B, "rt/chatter"), A + b"w": _writer(A)}
    writing = writing_since(since, endpoints, 0.0)
    assert writing == {A: 0.0}  # B writes no discovery info: a reader cannot wait on it
    assert silent_participants({A, B, C}, {}, writing, 1.0, 5.0) == {A}
    again = writing_since(since, {A + b"w": _writer(A)}, 3.0)
    assert again == {A: 0.0}  # first seen is kept: the grace period does not start anew
