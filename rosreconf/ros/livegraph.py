"""The graph of a running ROS system at one moment, and its JSON snapshot.

A ``LiveGraph`` is what one read saw: a ROS 1 master's answers
(``rosreconf.ros.ros1.rosmaster.read_live_graph``) or a ROS 2 domain's DDS discovery
(``rosreconf.ros.ros2.discovery``: nodes from each participant's ``ros_discovery_info``, their
endpoints, types and QoS, actions and lifecycle states; ``ros_version`` says which). Keeping
it free of I/O lets a saved snapshot be reviewed, diffed and tested without any middleware.

How a ROS 1 master's answers map onto this module (ROS 2's discovery: docs/ros2.md)::

    master / node API                      here
    -------------------------------------  ------------------------------------------
    getSystemState publishers [t, [n..]]   LiveNode.publishes (of each n)
    getSystemState subscribers             LiveNode.subscribes
    getSystemState services [s, [n]]       LiveNode.serves
    getTopicTypes [[t, type]..]            LiveGraph.topic_types
    lookupNode(n)                          LiveNode.uri
    getPid() on the node's own API         LiveNode.pid (None: it did not answer)

The snapshot (``to_json``/``from_json``) is one JSON object, described by the JSON Schema
``rosreconf/data/live_graph.schema.json``; lists are sorted so that two snapshots of the same
system are byte-identical apart from ``taken_at`` and pids::

    {"format": "rosreconf-live-graph", "version": 1,
     "master_uri": "http://127.0.0.1:11311/", "taken_at": "2026-01-01T12:00:00+00:00",
     "nodes": [{"name": "/talker", "uri": "http://127.0.0.1:40000/", "pid": 4242,
                "publishes": ["/a", "/rosout"], "subscribes": [], "serves": ["/s"]}],
     "topic_types": {"/a": "std_msgs/String", "/rosout": "rosgraph_msgs/Log"}}

ROS plumbing: roscore starts the node ``/rosout`` (topics ``/rosout`` and ``/rosout_agg``),
every rospy/roscpp node publishes ``/rosout`` and serves ``<node>/get_loggers`` and
``<node>/set_logger_level``. A snapshot keeps all of it; ``without_plumbing`` hides it,
which is what a comparison with a configuration's ROS-graph wants.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from datetime import datetime
from types import MappingProxyType
from typing import Any

import jsonschema_rs

from rosreconf import jsonout
from rosreconf.errors import InvalidInputError, Problem
from rosreconf.model import Span
from rosreconf.model.qos import QosProfile
from rosreconf.resources import Bundle, bundled

SNAPSHOT_FORMAT = "rosreconf-live-graph"
"""The ``format`` member every snapshot carries."""
SNAPSHOT_VERSION = 1
"""The snapshot version this module writes and reads."""

PLUMBING_NODES = frozenset({"/rosout"})
"""Nodes roscore starts for its own logging."""
PLUMBING_TOPICS = frozenset({"/rosout", "/rosout_agg"})
"""Topics every client library uses for logging."""
PLUMBING_SERVICE_SUFFIXES = ("/get_loggers", "/set_logger_level")
"""Services every rospy/roscpp node serves under its own name."""

ROS2_PLUMBING_TOPICS = frozenset({"/rosout", "/parameter_events"})
"""Topics every rclcpp/rclpy node publishes (and subscribes) for logging and parameters."""
ROS2_PLUMBING_SERVICE_SUFFIXES = (
    "/describe_parameters",
    "/get_parameter_types",
    "/get_parameters",
    "/list_parameters",
    "/set_parameters",
    "/set_parameters_atomically",
    "/get_type_description",
)
"""Services every node serves under its own name (parameters; type descriptions, Jazzy on)."""
LIFECYCLE_SERVICE_SUFFIXES = (
    "/change_state",
    "/get_state",
    "/get_available_states",
    "/get_available_transitions",
    "/get_transition_graph",
)
"""Services a lifecycle (managed) node serves under its own name (rclcpp_lifecycle)."""
LIFECYCLE_TOPIC_SUFFIX = "/transition_event"
"""The topic a lifecycle node publishes its transitions on, under its own name."""


@dataclass(frozen=True)
class LiveNode:
    """One node the master lists, with what it registered and what its own API answered.

    Attributes:
        name: the node's global name (``/talker``).
        uri: its XML-RPC API (``lookupNode``), None if the master no longer knew it.
        pid: its process id from ``getPid`` on its API; None when it did not answer, which
            means it is dead or hung (the master keeps registrations of killed nodes).
        publishes: topics it publishes, sorted.
        subscribes: topics it subscribes to, sorted.
        serves: services it serves, sorted.
        clients: services it calls, sorted (ROS 2 only: a ROS 1 master does not know them).
        alive: ROS 2: whether its DDS participant was alive (None for ROS 1, where the pid
            tells).
        publish_qos: ROS 2: topic -> the QoS its publisher offers.
        subscribe_qos: ROS 2: topic -> the QoS its subscription requests.
        topic_types: ROS 2: topic -> the type of this node's own endpoint on it (nodes may
            disagree; the graph's ``topic_types`` keeps one per topic).
        service_types: ROS 2: service -> the type of this node's server or client.
        lifecycle_state: ROS 2: a managed node's state (``unconfigured``, ``inactive``,
            ``active``, ``finalized``, or ``unknown`` when it did not answer); None for a
            node that is not managed, or when states were not read.
        participant: ROS 2: its DDS participant's 16-byte GUID in hex (one per process: two
            nodes of one name are told apart by it); empty for ROS 1.
    """

    name: str
    uri: str | None = None
    pid: int | None = None
    publishes: tuple[str, ...] = ()
    subscribes: tuple[str, ...] = ()
    serves: tuple[str, ...] = ()
    clients: tuple[str, ...] = ()
    alive: bool | None = None
    publish_qos: Mapping[str, QosProfile] = field(default_factory=lambda: MappingProxyType({}))
    subscribe_qos: Mapping[str, QosProfile] = field(default_factory=lambda: MappingProxyType({}))
    topic_types: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    service_types: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    lifecycle_state: str | None = None
    participant: str = ""

    @property
    def answered(self) -> bool:
        """Tell whether the node was alive when read (ROS 1: its API answered ``getPid``)."""
        return self.alive if self.alive is not None else self.pid is not None


@dataclass(frozen=True)
class LiveGraph:
    """A running system's nodes, topics and services at one moment, as its master said.

    Attributes:
        master_uri: the master it was read from.
        taken_at: when it was read (timezone-aware).
        nodes: the nodes, sorted by name.
        topic_types: topic -> message type. The master never forgets a type, so this may
            name topics no node uses any more; ``topics`` gives the ones in use.
        ros_version: 1 (a master) or 2 (DDS discovery; ``master_uri`` is then
            ``ros2://domain/<id>``).
        service_types: ROS 2: service -> service type (a ROS 1 master does not know them).
    """

    master_uri: str
    taken_at: datetime
    nodes: tuple[LiveNode, ...]
    topic_types: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    ros_version: int = 1
    service_types: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))

    def __post_init__(self) -> None:
        object.__setattr__(self, "nodes", tuple(sorted(self.nodes, key=lambda n: n.name)))
        object.__setattr__(
            self, "topic_types", MappingProxyType(dict(sorted(self.topic_types.items())))
        )
        object.__setattr__(
            self, "service_types", MappingProxyType(dict(sorted(self.service_types.items())))
        )

    @property
    def names(self) -> tuple[str, ...]:
        """Return the node names, sorted."""
        return tuple(n.name for n in self.nodes)

    @property
    def duplicates(self) -> tuple[str, ...]:
        """Return the names more than one node has (ROS 2 allows it; calls reach either)."""
        names = [n.name for n in self.nodes]
        return tuple(sorted({n for n in names if names.count(n) > 1}))

    def node(self, name: str) -> LiveNode:
        """Return the node called ``name`` (the first, if several; KeyError if none)."""
        for n in self.nodes:
            if n.name == name:
                return n
        raise KeyError(name)

    @property
    def topics(self) -> frozenset[str]:
        """Return the topics some node publishes or subscribes to now."""
        return frozenset(t for n in self.nodes for t in (*n.publishes, *n.subscribes))

    @property
    def services(self) -> frozenset[str]:
        """Return the services some node serves."""
        return frozenset(s for n in self.nodes for s in n.serves)


def is_plumbing_service(node: str, service: str) -> bool:
    """Tell whether ``service`` is one of the logger services a client library adds to ``node``."""
    return any(service == node + suffix for suffix in PLUMBING_SERVICE_SUFFIXES)


def is_ros2_plumbing_service(node: str, service: str) -> bool:
    """Tell whether ``service`` is a parameter/type service every node ``node`` serves."""
    return any(service == node + suffix for suffix in ROS2_PLUMBING_SERVICE_SUFFIXES)


def is_lifecycle_service(node: str, service: str) -> bool:
    """Tell whether ``service`` is one of the lifecycle services of the managed node ``node``."""
    return any(service == node + suffix for suffix in LIFECYCLE_SERVICE_SUFFIXES)


FACE_NAME = "/rosreconf"
"""The default name of rosreconf's own ROS 2 node, its face (``ros2.face``)."""


def is_own_face(name: str) -> bool:
    """Tell whether ``name`` is one a face of rosreconf may have: an absolute ROS name whose
    base name is ``rosreconf`` or starts with ``rosreconf_``. Such a node is plumbing: never
    an extra node of a configuration."""
    if not re.fullmatch(r"(/[A-Za-z_][A-Za-z0-9_]*)+", name):
        return False
    base = name.rsplit("/", 1)[-1]
    return base == "rosreconf" or base.startswith("rosreconf_")


def is_hidden_node(name: str) -> bool:
    """Tell whether a node is hidden in ROS 2 (a base name starting with ``_``, e.g. the CLI's).

    An empty base name (``/ns/``: rcl refuses it, only a forged participant announces it) is
    hidden too, as ``ros2 node list`` hides it: no launch file can name such a node.
    """
    base = name.rsplit("/", 1)[-1]
    return not base or base.startswith("_")


def _ros2_plumbing_service(node: str, service: str) -> bool:
    """Tell whether ``service`` is a parameter or lifecycle service every such node has."""
    return is_ros2_plumbing_service(node, service) or is_lifecycle_service(node, service)


def without_plumbing(graph: LiveGraph) -> LiveGraph:
    """Return ``graph`` without the client libraries' own nodes, topics and services.

    ROS 1: roscore's ``/rosout`` node, ``/rosout``/``/rosout_agg`` and the logger services.
    ROS 2: hidden nodes (``_ros2cli_...``), rosreconf's face (``is_own_face``), ``/rosout``,
    ``/parameter_events``, every node's parameter services and a lifecycle node's state
    services and ``transition_event`` topic.
    """
    if graph.ros_version == 2:
        topics = ROS2_PLUMBING_TOPICS
        plumbing_service = _ros2_plumbing_service
    else:
        topics, plumbing_service = PLUMBING_TOPICS, is_plumbing_service

    def keep_topic(node: str, topic: str) -> bool:
        lifecycle = graph.ros_version == 2 and topic == node + LIFECYCLE_TOPIC_SUFFIX
        return topic not in topics and not lifecycle

    nodes = tuple(
        replace(
            n,
            publishes=tuple(t for t in n.publishes if keep_topic(n.name, t)),
            subscribes=tuple(t for t in n.subscribes if keep_topic(n.name, t)),
            serves=tuple(s for s in n.serves if not plumbing_service(n.name, s)),
            clients=tuple(s for s in n.clients if not plumbing_service(n.name, s)),
            publish_qos={t: q for t, q in n.publish_qos.items() if keep_topic(n.name, t)},
            subscribe_qos={t: q for t, q in n.subscribe_qos.items() if keep_topic(n.name, t)},
            topic_types={t: y for t, y in n.topic_types.items() if keep_topic(n.name, t)},
            service_types={
                s: y for s, y in n.service_types.items() if not plumbing_service(n.name, s)
            },
        )
        for n in graph.nodes
        if n.name not in PLUMBING_NODES
        and not is_hidden_node(n.name)
        and not (graph.ros_version == 2 and is_own_face(n.name))
    )
    types = {t: ty for t, ty in graph.topic_types.items() if t not in topics}
    services = dict(graph.service_types)
    if graph.ros_version == 2:
        in_use = {t for n in nodes for t in (*n.publishes, *n.subscribes)}
        called = {s for n in nodes for s in (*n.serves, *n.clients)}
        types = {t: ty for t, ty in types.items() if t in in_use}
        services = {s: ty for s, ty in services.items() if s in called}
    return replace(graph, nodes=nodes, topic_types=types, service_types=services)


def _node_json(n: LiveNode, ros_version: int) -> dict[str, Any]:
    """Return one node's snapshot entry (ROS 2 adds clients, alive and QoS)."""
    doc: dict[str, Any] = {
        "name": n.name,
        "uri": n.uri,
        "pid": n.pid,
        "publishes": sorted(n.publishes),
        "subscribes": sorted(n.subscribes),
        "serves": sorted(n.serves),
    }
    if ros_version == 2:
        doc["clients"] = sorted(n.clients)
        doc["alive"] = n.alive
        doc["qos"] = {
            "publishes": {t: q.to_dict() for t, q in sorted(n.publish_qos.items())},
            "subscribes": {t: q.to_dict() for t, q in sorted(n.subscribe_qos.items())},
        }
        doc["lifecycle_state"] = n.lifecycle_state
        if n.participant:  # a graph built by hand, or an older snapshot, has none
            doc["participant"] = n.participant
        doc["types"] = {
            "topics": dict(sorted(n.topic_types.items())),
            "services": dict(sorted(n.service_types.items())),
        }
    return doc


def to_json(graph: LiveGraph) -> str:
    """Return the snapshot of ``graph`` (format above), ending in a newline."""
    doc: dict[str, Any] = {
        "format": SNAPSHOT_FORMAT,
        "version": SNAPSHOT_VERSION,
        "master_uri": graph.master_uri,
        "taken_at": graph.taken_at.isoformat(),
        "nodes": [_node_json(n, graph.ros_version) for n in graph.nodes],
        "topic_types": dict(graph.topic_types),
    }
    if graph.ros_version == 2:
        doc["ros_version"] = 2
        doc["service_types"] = dict(graph.service_types)
    return jsonout.dumps(doc, indent=2) + "\n"


def from_json(text: str, source: str = "<snapshot>") -> LiveGraph:
    """Read a snapshot written by ``to_json``, reporting every problem with ``source``."""
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        where = Span(source, e.lineno, e.colno)
        raise InvalidInputError([Problem(where, f"not JSON: {e.msg}", code="not-json")]) from None
    problems = _schema_problems(doc, source)
    if problems:
        raise InvalidInputError(problems)
    start = Span(source, 1, 1)
    try:
        taken_at = datetime.fromisoformat(doc["taken_at"])
        if taken_at.tzinfo is None:
            raise ValueError("no UTC offset")
    except ValueError:
        hint = "write it as ISO 8601 with a UTC offset"
        bad = Problem(start, f"taken_at {doc['taken_at']!r} is not a time", hint, "bad-time")
        raise InvalidInputError([bad]) from None
    names = [n["name"] for n in doc["nodes"]]
    dups = sorted({n for n in names if names.count(n) > 1})
    if dups and doc.get("ros_version", 1) == 1:  # ROS 2 allows two nodes of one name
        msg = f"node(s) listed twice: {', '.join(dups)}"
        raise InvalidInputError([Problem(start, msg, code="duplicate-node")])
    nodes = tuple(_node_from_json(n) for n in doc["nodes"])
    return LiveGraph(
        doc["master_uri"],
        taken_at,
        nodes,
        dict(doc["topic_types"]),
        ros_version=doc.get("ros_version", 1),
        service_types=dict(doc.get("service_types", {})),
    )


def _node_from_json(n: dict[str, Any]) -> LiveNode:
    """Build one node from its (schema-checked) snapshot entry."""
    qos = n.get("qos", {})
    types = n.get("types", {})
    return LiveNode(
        name=n["name"],
        uri=n["uri"],
        pid=n["pid"],
        publishes=tuple(sorted(n["publishes"])),
        subscribes=tuple(sorted(n["subscribes"])),
        serves=tuple(sorted(n["serves"])),
        clients=tuple(sorted(n.get("clients", ()))),
        alive=n.get("alive"),
        publish_qos={t: QosProfile.from_dict(q) for t, q in qos.get("publishes", {}).items()},
        subscribe_qos={t: QosProfile.from_dict(q) for t, q in qos.get("subscribes", {}).items()},
        topic_types=dict(types.get("topics", {})),
        service_types=dict(types.get("services", {})),
        lifecycle_state=n.get("lifecycle_state"),
        participant=n.get("participant", ""),
    )


def _schema_problems(doc: Any, source: str) -> list[Problem]:
    """Return every way ``doc`` breaks the snapshot schema, each naming its JSON path."""
    schema = json.loads(bundled(Bundle.DATA, "live_graph.schema.json").read_text("utf-8"))
    validator = jsonschema_rs.Draft202012Validator(schema)
    problems = []
    for err in validator.iter_errors(doc):
        path = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in err.instance_path)
        where = path.lstrip(".") or "snapshot"
        hint = f"this reader understands {SNAPSHOT_FORMAT} version {SNAPSHOT_VERSION}"
        problems.append(Problem(Span(source, 1, 1), f"{where}: {err.message}", hint, "schema"))
    return problems
