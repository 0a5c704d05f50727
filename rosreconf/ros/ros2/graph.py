"""Join what DDS discovery announced into a ROS 2 live graph: nodes, their topics and services.

A ROS participant's ``ros_discovery_info`` sample names its nodes and, for each, the GIDs of
its readers and writers; the endpoints discovery announced carry each GID's DDS topic, type
and QoS. ``build_graph`` joins the two (``rosreconf.ros.ros2.names`` turns DDS names into ROS
names) into the ``LiveGraph`` every live command reads. Pure data: no DDS here.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from datetime import datetime

from rosreconf.model.qos import QosProfile
from rosreconf.printable import printable
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.ros2.names import DISCOVERY_TOPIC, Channel, ros_name, ros_type

_NAME_CHARS = 2048
"""Longest name kept whole (a Gid's namespace and name are 256 bytes each; DDS topics more)."""


def graph_uri(domain: int) -> str:
    """Return the ``master_uri`` a ROS 2 live graph of ``domain`` carries."""
    return f"ros2://domain/{domain}"


@dataclass(frozen=True)
class Endpoint:
    """One DDS reader or writer as discovery announced it.

    Attributes:
        guid: its 16-byte GUID (its GID, unpadded).
        participant: its participant's GUID.
        topic: the DDS topic name (``rt/chatter``).
        type_name: the DDS type name.
        writer: True for a writer (publication), False for a reader.
        qos: its QoS in rmw terms.
        user_data: its USER_DATA (``typehash=...;`` from Iron on).
    """

    guid: bytes
    participant: bytes
    topic: str
    type_name: str
    writer: bool
    qos: QosProfile
    user_data: bytes


@dataclass(frozen=True)
class NodeInfo:
    """One node of a participant's ``ros_discovery_info`` sample."""

    namespace: str
    name: str
    readers: tuple[bytes, ...]
    writers: tuple[bytes, ...]

    @property
    def gids(self) -> tuple[bytes, ...]:
        """Return the GIDs of the node's readers and writers."""
        return (*self.readers, *self.writers)

    @property
    def full_name(self) -> str:
        """Return the node's global name (``/ns`` + ``name``).

        A base name cannot hold ``/`` (rcl refuses it), so one that came over the network with
        it is escaped as ``\\x2f``, like other characters no ROS name holds: ``/`` would read as
        ``//`` and ``a/b`` as node ``b`` of namespace ``/a``. An empty base name gives
        ``/ns/``, which ``is_hidden_node`` hides, as ``ros2 node list`` does.
        """
        ns = self.namespace.rstrip("/")
        return ns + "/" + self.name.replace("/", "\\x2f")


def stale_participants(
    named: AbstractSet[bytes],
    infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]],
    endpoints: dict[bytes, Endpoint],
) -> frozenset[bytes]:
    """Return participants with a ROS endpoint that no node of their ``ros_discovery_info`` names.

    ``named`` holds every GID the held node lists name (the caller needs it too). rmw
    announces a node's endpoints in the participant's next sample; one still unnamed once the
    graph is still means that sample was lost or did not decode: the node list held for that
    participant is out of date.
    """
    return frozenset(
        e.participant
        for e in endpoints.values()
        if e.participant in infos and e.guid not in named and ros_name(e.topic) is not None
    )


def writing_since(
    since: dict[bytes, float], endpoints: dict[bytes, Endpoint], now: float
) -> dict[bytes, float]:
    """Note in ``since`` when each participant's ``ros_discovery_info`` writer was first seen
    (``now`` for a new one); return that of each writer there now (``silent_participants``)."""
    writing = {e.participant for e in endpoints.values() if e.writer and e.topic == DISCOVERY_TOPIC}
    return {k: since.setdefault(k, now) for k in writing}


def silent_participants(
    ros: AbstractSet[bytes],
    infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]],
    writing: dict[bytes, float],
    after: float,
    now: float | None = None,
) -> set[bytes]:
    """Return ROS participants whose discovery writer has sent nothing decodable for ``after`` s.

    A real participant's ``ros_discovery_info`` (transient local) arrives as soon as its
    writer is matched; one that never decodes (another Gid layout: a wrong ``--distro``; a
    broken writer) would otherwise hold every read for the full timeout. ``writing`` holds
    when each writer was first seen (``writing_since``) and ``now`` defaults to the time now.
    """
    now = time.monotonic() if now is None else now
    return {k for k in ros if k not in infos and k in writing and now - writing[k] >= after}


def build_graph(
    domain: int,
    taken_at: datetime,
    ros_participants: Iterable[bytes],
    infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]],
    endpoints: dict[bytes, Endpoint],
) -> LiveGraph:
    """Join the nodes of alive ROS participants with their endpoints into a live graph.

    Every node keeps the types of its own endpoints, so two nodes that disagree on a topic's
    type are both seen, in whatever order they started; the graph-wide ``topic_types`` keeps
    the first type by sorted node name (a summary). Two nodes announcing one name (ROS 2 does
    not forbid it) stay two entries. Names and types come from the network: anything
    unprintable in them is escaped (``printable``), as no ROS name can hold it.
    """
    topic_types: dict[str, str] = {}
    service_types: dict[str, str] = {}
    nodes: list[LiveNode] = []
    for participant in sorted(ros_participants):
        if participant not in infos:
            continue
        nodes += (_node(info, endpoints, participant) for info in infos[participant][1])
    for node in sorted(nodes, key=lambda n: n.name):
        for name, typ in node.topic_types.items():
            topic_types.setdefault(name, typ)
        for name, typ in node.service_types.items():
            service_types.setdefault(name, typ)
    return LiveGraph(
        graph_uri(domain),
        taken_at,
        tuple(nodes),
        topic_types,
        ros_version=2,
        service_types=service_types,
    )


def _node(info: NodeInfo, endpoints: dict[bytes, Endpoint], participant: bytes) -> LiveNode:
    """Build one live node of ``participant`` from its discovery entry and its endpoints."""
    pubs: dict[str, QosProfile] = {}
    subs: dict[str, QosProfile] = {}
    serves: set[str] = set()
    clients: set[str] = set()
    topic_types: dict[str, str] = {}
    service_types: dict[str, str] = {}
    for gid in (*info.readers, *info.writers):
        e = endpoints.get(gid)
        if e is None:
            continue  # not discovered (yet), or gone
        named = ros_name(e.topic)
        typ = ros_type(e.type_name)
        if named is None or typ is None:
            continue
        channel, name = named
        name, typ = printable(name, _NAME_CHARS), printable(typ, _NAME_CHARS)
        if channel is Channel.TOPIC:
            (pubs if e.writer else subs).setdefault(name, e.qos)
            topic_types.setdefault(name, typ)
        else:
            service_types.setdefault(name, typ)
            server = (channel is Channel.REQUEST) != e.writer
            (serves if server else clients).add(name)
    return LiveNode(
        name=printable(info.full_name, _NAME_CHARS),
        publishes=tuple(sorted(pubs)),
        subscribes=tuple(sorted(subs)),
        serves=tuple(sorted(serves)),
        clients=tuple(sorted(clients)),
        alive=True,
        publish_qos=pubs,
        subscribe_qos=subs,
        topic_types=topic_types,
        service_types=service_types,
        participant=participant.hex(),
    )
