"""Turn the DDS names a ROS 2 rmw announces back into ROS names and types.

ROS 2 maps every topic and service onto DDS topics with a prefix, and every message type onto
a DDS type name in a ``dds_`` namespace (rmw_cyclonedds_cpp ``make_fqtopic`` and
``MessageTypeSupport``/``ServiceTypeSupport``; rmw_fastrtps ``namespace_prefix.cpp`` uses the
same names). The inverse, as rmw_cyclonedds_cpp ``demangle.cpp`` does it::

    DDS                                              ROS
    -----------------------------------------------  ----------------------------------------
    topic  rt/chatter                                topic /chatter
    topic  rq/add_two_intsRequest (reader: server)   service /add_two_ints
    topic  rr/add_two_intsReply   (writer: server)   service /add_two_ints
    type   std_msgs::msg::dds_::String_              std_msgs/msg/String
    type   example_interfaces::srv::dds_::AddTwoInts_Request_  example_interfaces/srv/AddTwoInts
    type   nav2_msgs::action::dds_::NavigateToPose_SendGoal_Request_
                                                     nav2_msgs/action/NavigateToPose_SendGoal

An action's services and topics (``<a>/_action/send_goal`` ...) are ordinary ones here;
``rosreconf.ros.liveactions`` reads the actions back from them. The library's ``pkg/Name``
equals ``pkg/msg/Name`` by ``rosreconf.model.type_key``, the one place types are compared.

A DDS name without these prefixes is not a ROS one (plain DDS applications, or ROS endpoints
created with ``avoid_ros_namespace_conventions``) and is left out of the ROS graph.
"""

from __future__ import annotations

import enum

from rosreconf.errors import UsageError

TOPIC_PREFIX = "rt"
REQUEST_PREFIX = "rq"
REPLY_PREFIX = "rr"
DISCOVERY_TOPIC = "ros_discovery_info"
"""rmw_dds_common's graph topic: its DDS name has no prefix."""


class Channel(enum.StrEnum):
    """What a DDS topic carries for ROS 2."""

    TOPIC = "topic"
    REQUEST = "request"
    REPLY = "reply"


def ros_name(dds_topic: str) -> tuple[Channel, str] | None:
    """Return what ``dds_topic`` carries and its ROS name, or None if it is not a ROS name."""
    for prefix, channel, suffix in (
        (TOPIC_PREFIX, Channel.TOPIC, ""),
        (REQUEST_PREFIX, Channel.REQUEST, "Request"),
        (REPLY_PREFIX, Channel.REPLY, "Reply"),
    ):
        if not dds_topic.startswith(prefix + "/"):
            continue
        name = dds_topic[len(prefix) :]
        if suffix:
            if not name.endswith(suffix) or len(name) == len(suffix) + 1:
                return None
            name = name[: -len(suffix)]
        return (channel, name) if len(name) > 1 else None
    return None


def ros_type(dds_type: str) -> str | None:
    """Return the ROS type ``pkg/msg/Name`` or ``pkg/srv/Name`` of a DDS type name, else None.

    An action's services are typed like services: ``pkg/action/Name_SendGoal``.
    """
    head, sep, tail = dds_type.rpartition("::dds_::")
    if not sep or not head or not tail.endswith("_"):
        return None
    name = tail[:-1]
    for suffix in ("_Request", "_Response"):
        if name.endswith(suffix) and head.endswith(("::srv", "::action")):
            name = name[: -len(suffix)]
            break
    if not name:
        return None
    return head.replace("::", "/") + "/" + name


GID_SIZES = {"humble": 24, "iron": 16, "jazzy": 16, "kilted": 16, "rolling": 16}
"""The Gid message's size in each ROS 2 distribution (Humble's is 24 bytes)."""
DISTROS = tuple(GID_SIZES)


def check_domain(domain: int) -> None:
    """Refuse a domain id DDS cannot use (0-232 with the default port mapping)."""
    if not 0 <= domain <= 232:
        raise UsageError(f"--domain {domain}: a ROS 2 domain id is 0 to 232 (ROS_DOMAIN_ID)")


def gid_sizes(distro: str | None) -> tuple[int, ...]:
    """Return the Gid layouts to read for ``distro`` (both when it is not given)."""
    if distro is None:
        return (16, 24)
    try:
        return (GID_SIZES[distro.lower()],)
    except KeyError:
        raise UsageError(
            f"--distro {distro}: not a ROS 2 distribution rosreconf knows "
            f"(one of {', '.join(DISTROS)})"
        ) from None
