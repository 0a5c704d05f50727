"""ROS 2 name de-mangling and the QoS compatibility rule, clause by clause (no DDS needed)."""

from __future__ import annotations

import pytest

from rosreconf.model.qos import QosProfile, incompatibilities
from rosreconf.ros.ros2.names import Channel, ros_name, ros_type


@pytest.mark.parametrize(
    ("dds", "expected"),
    [
        ("rt/chatter", (Channel.TOPIC, "/chatter")),
        ("rt/a/b", (Channel.TOPIC, "/a/b")),
        ("rq/add_two_intsRequest", (Channel.REQUEST, "/add_two_ints")),
        ("rr/ns/resetReply", (Channel.REPLY, "/ns/reset")),
        ("rq/addReply", None),  # a request topic must end in Request
        ("rq/Request", None),
        ("ros_discovery_info", None),
        ("DCPSParticipant", None),
        ("rtchatter", None),
    ],
)
def test_ros_name(dds: str, expected: tuple[Channel, str] | None) -> None:
    assert ros_name(dds) == expected


@pytest.mark.parametrize(
    ("dds", "expected"),
    [
        ("std_msgs::msg::dds_::String_", "std_msgs/msg/String"),
        ("example_interfaces::srv::dds_::AddTwoInts_Request_", "example_interfaces/srv/AddTwoInts"),
        (
            "example_interfaces::srv::dds_::AddTwoInts_Response_",
            "example_interfaces/srv/AddTwoInts",
        ),
        ("a::msg::dds_::Has_Request_", "a/msg/Has_Request"),  # a message may end so
        ("HelloWorld", None),
        ("std_msgs::msg::String", None),
    ],
)
def test_ros_type(dds: str, expected: str | None) -> None:
    assert ros_type(dds) == expected


def _policies(offered: dict[str, object], requested: dict[str, object]) -> list[str]:
    pub, sub = QosProfile.from_dict(offered), QosProfile.from_dict(requested)
    return [i.policy for i in incompatibilities(pub, sub)]


@pytest.mark.parametrize(
    ("offered", "requested", "expected"),
    [
        ({}, {}, []),
        ({"reliability": "best_effort"}, {}, ["reliability"]),
        ({}, {"reliability": "best_effort"}, []),
        ({}, {"durability": "transient_local"}, ["durability"]),
        ({"durability": "transient_local"}, {}, []),
        ({}, {"deadline": 1}, ["deadline"]),
        ({"deadline": 1}, {}, []),
        ({"deadline": 1}, {"deadline": 0.5}, ["deadline"]),
        ({"deadline": 0.5}, {"deadline": 1}, []),
        ({}, {"liveliness": "manual_by_topic"}, ["liveliness"]),
        ({"liveliness": "manual_by_topic"}, {}, []),
        ({}, {"lease_duration": 2}, ["lease_duration"]),
        ({"lease_duration": 2}, {"lease_duration": 1}, ["lease_duration"]),
        ({"lease_duration": 1}, {"lease_duration": 2}, []),
        (
            {"reliability": "best_effort"},
            {"durability": "transient_local", "deadline": 1},
            ["reliability", "durability", "deadline"],
        ),
        ({"depth": 1}, {"depth": 0}, []),  # history never makes endpoints incompatible
    ],
)
def test_compatibility_follows_rmw(
    offered: dict[str, object], requested: dict[str, object], expected: list[str]
) -> None:
    assert _policies(offered, requested) == expected


def test_reasons_name_both_sides() -> None:
    (why,) = incompatibilities(
        QosProfile.from_dict({"deadline": 2}), QosProfile.from_dict({"deadline": 0.5})
    )
    assert "0.5 s" in why.message and "2 s" in why.message


@pytest.mark.parametrize(
    "bad",
    [
        {"reliability": "sometimes"},
        {"deadline": -1},
        {"deadline": "1s"},
        {"colour": "red"},
        {"lease_duration": float("inf")},
    ],
)
def test_bad_profiles_are_refused(bad: dict[str, object]) -> None:
    with pytest.raises(ValueError):
        QosProfile.from_dict(bad)
