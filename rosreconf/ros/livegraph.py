"""The graph of a running ROS 1 system as its master reports it, and its JSON snapshot.

A ``LiveGraph`` is what ``rosreconf.ros.rosmaster.read_live_graph`` saw at one moment; keeping it
free of I/O lets a saved snapshot be reviewed, diffed and tested without any master.

How the master's answers map onto this module::

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
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from datetime import datetime
from types import MappingProxyType
from typing import Any

import jsonschema

from rosreconf import jsonout
from rosreconf.errors import InvalidInputError, Problem
from rosreconf.model import Span
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
    """

    name: str
    uri: str | None = None
    pid: int | None = None
    publishes: tuple[str, ...] = ()
    subscribes: tuple[str, ...] = ()
    serves: tuple[str, ...] = ()

    @property
    def answered(self) -> bool:
        """Tell whether the node's own API answered ``getPid`` when the graph was read."""
        return self.pid is not None


@dataclass(frozen=True)
class LiveGraph:
    """A running system's nodes, topics and services at one moment, as its master said.

    Attributes:
        master_uri: the master it was read from.
        taken_at: when it was read (timezone-aware).
        nodes: the nodes, sorted by name.
        topic_types: topic -> message type. The master never forgets a type, so this may
            name topics no node uses any more; ``topics`` gives the ones in use.
    """

    master_uri: str
    taken_at: datetime
    nodes: tuple[LiveNode, ...]
    topic_types: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))

    def __post_init__(self) -> None:
        object.__setattr__(self, "nodes", tuple(sorted(self.nodes, key=lambda n: n.name)))
        object.__setattr__(
            self, "topic_types", MappingProxyType(dict(sorted(self.topic_types.items())))
        )

    @property
    def names(self) -> tuple[str, ...]:
        """Return the node names, sorted."""
        return tuple(n.name for n in self.nodes)

    def node(self, name: str) -> LiveNode:
        """Return the node called ``name`` (KeyError if there is none)."""
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


def without_plumbing(graph: LiveGraph) -> LiveGraph:
    """Return ``graph`` without roscore's logging node, topics and per-node logger services."""
    nodes = tuple(
        replace(
            n,
            publishes=tuple(t for t in n.publishes if t not in PLUMBING_TOPICS),
            subscribes=tuple(t for t in n.subscribes if t not in PLUMBING_TOPICS),
            serves=tuple(s for s in n.serves if not is_plumbing_service(n.name, s)),
        )
        for n in graph.nodes
        if n.name not in PLUMBING_NODES
    )
    types = {t: ty for t, ty in graph.topic_types.items() if t not in PLUMBING_TOPICS}
    return replace(graph, nodes=nodes, topic_types=types)


def to_json(graph: LiveGraph) -> str:
    """Return the snapshot of ``graph`` (format above), ending in a newline."""
    doc = {
        "format": SNAPSHOT_FORMAT,
        "version": SNAPSHOT_VERSION,
        "master_uri": graph.master_uri,
        "taken_at": graph.taken_at.isoformat(),
        "nodes": [
            {
                "name": n.name,
                "uri": n.uri,
                "pid": n.pid,
                "publishes": sorted(n.publishes),
                "subscribes": sorted(n.subscribes),
                "serves": sorted(n.serves),
            }
            for n in graph.nodes
        ],
        "topic_types": dict(graph.topic_types),
    }
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
    if dups:
        msg = f"node(s) listed twice: {', '.join(dups)}"
        raise InvalidInputError([Problem(start, msg, code="duplicate-node")])
    nodes = tuple(
        LiveNode(
            name=n["name"],
            uri=n["uri"],
            pid=n["pid"],
            publishes=tuple(sorted(n["publishes"])),
            subscribes=tuple(sorted(n["subscribes"])),
            serves=tuple(sorted(n["serves"])),
        )
        for n in doc["nodes"]
    )
    return LiveGraph(doc["master_uri"], taken_at, nodes, dict(doc["topic_types"]))


def _schema_problems(doc: Any, source: str) -> list[Problem]:
    """Return every way ``doc`` breaks the snapshot schema, each naming its JSON path."""
    schema = json.loads(bundled(Bundle.DATA, "live_graph.schema.json").read_text("utf-8"))
    validator = jsonschema.Draft202012Validator(schema)
    problems = []
    for err in validator.iter_errors(doc):
        path = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in err.absolute_path)
        where = path.lstrip(".") or "snapshot"
        hint = f"this reader understands {SNAPSHOT_FORMAT} version {SNAPSHOT_VERSION}"
        problems.append(Problem(Span(source, 1, 1), f"{where}: {err.message}", hint, "schema"))
    return problems
