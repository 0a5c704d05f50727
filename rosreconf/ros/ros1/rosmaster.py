"""Ask a running ROS 1 master what is running, with the standard library's XML-RPC only.

rosreconf's own environment has no rospy, and needs none: the master API
(http://wiki.ros.org/ROS/Master_API) and every node's own API
(http://wiki.ros.org/ROS/Slave_API) are plain XML-RPC, each call answering
``[code, status, value]`` with code 1 for success. Each call goes through
``rosreconf.ros.ros1.rpc`` (one total deadline and a byte cap per call). Every failure (nothing
listening, no answer within ``timeout``, an answer that is not that shape) becomes
``ExternalToolError`` naming the URI; nothing here prints.

What the master does not do: it never checks that a registered node is alive. A node that
shuts down cleanly (SIGINT/SIGTERM) unregisters itself; a node killed with SIGKILL stays
listed, with its topics and services, until someone unregisters it. ``alive`` asks a node
for its pid to tell the difference, and ``purge_dead`` unregisters the dead ones, the way
``rosnode cleanup`` does.
"""

from __future__ import annotations

from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from datetime import UTC, datetime
from typing import Any

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.printable import printable
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.ros1 import rpc
from rosreconf.ros.ros1.rpc import DEFAULT_MAX_BYTES, DEFAULT_TIMEOUT

__all__ = [
    "DEFAULT_MAX_BYTES",
    "DEFAULT_TIMEOUT",
    "LiveGraph",
    "LiveNode",
    "alive",
    "master_identity",
    "node_pid",
    "printable",
    "purge_dead",
    "read_live_graph",
    "shutdown_node",
]

_PID_WORKERS = 8
"""How many nodes are asked for their pid at once, so hung nodes cost one timeout, not many."""

_NODE_MAX_BYTES = 64 << 10
"""The cap for a node's answers (getPid, shutdown), which are a few hundred bytes."""


def _bad(uri: str, method: str, value: object) -> ExternalToolError:
    """Build the error for a code-1 answer whose value has the wrong shape."""
    msg = f"ROS master at {uri}: {method} gave an unexpected {value!r:.200}"
    return ExternalToolError(printable(msg, 400))


def _name(value: object) -> bool:
    """Tell whether ``value`` can be a ROS name or type: a string with nothing unprintable."""
    return isinstance(value, str) and value.isprintable()


def _registrations(uri: str, value: object) -> tuple[dict[str, set[str]], ...]:
    """Turn getSystemState's ``[pubs, subs, srvs]`` into three maps node -> names."""
    if not (isinstance(value, list) and len(value) == 3):
        raise _bad(uri, "getSystemState", value)
    maps: list[dict[str, set[str]]] = []
    for section in value:
        by_node: dict[str, set[str]] = {}
        if not isinstance(section, list):
            raise _bad(uri, "getSystemState", value)
        for entry in section:
            ok = isinstance(entry, list) and len(entry) == 2 and _name(entry[0])
            if not (ok and isinstance(entry[1], list)):
                raise _bad(uri, "getSystemState", entry)
            for node in entry[1]:
                if not _name(node):
                    raise _bad(uri, "getSystemState", entry)
                by_node.setdefault(node, set()).add(entry[0])
        maps.append(by_node)
    return maps[0], maps[1], maps[2]


def _topic_types(uri: str, value: object) -> dict[str, str]:
    """Turn getTopicTypes' ``[[topic, type], ...]`` into a dict."""
    if not isinstance(value, list):
        raise _bad(uri, "getTopicTypes", value)
    types: dict[str, str] = {}
    for entry in value:
        if not (isinstance(entry, list) and len(entry) == 2 and all(map(_name, entry))):
            raise _bad(uri, "getTopicTypes", entry)
        types[entry[0]] = entry[1]
    return types


def _lookup_node(
    master_uri: str, name: str, timeout: float, max_bytes: int, caller_id: str
) -> str | None:
    """Return the API URI of node ``name``, or None if the master does not know it now."""
    answer = rpc.ask(master_uri, "ROS master", timeout, max_bytes, "lookupNode", caller_id, name)
    if isinstance(answer, list) and len(answer) == 3 and answer[0] == 1:
        uri = answer[2]
        return uri if isinstance(uri, str) and uri.isprintable() else None
    return None


def node_pid(node_uri: str, *, timeout: float = 1.0, caller_id: str = "/rosreconf") -> int | None:
    """Return the pid a node's own API reports, or None when it does not answer properly."""
    try:
        rpc.check_uri(node_uri, "node")
        pid = rpc.call(node_uri, "node", timeout, "getPid", caller_id, max_bytes=_NODE_MAX_BYTES)
    except (ExternalToolError, UsageError):
        return None
    return pid if isinstance(pid, int) and not isinstance(pid, bool) else None


def alive(node: LiveNode | str, *, timeout: float = 1.0, caller_id: str = "/rosreconf") -> bool:
    """Tell whether a node (a ``LiveNode`` or its API URI) answers ``getPid`` right now.

    For a ``LiveNode`` read with a pid, the answer must also be that pid: a new process
    that happens to listen on a dead node's port is not that node.
    """
    if isinstance(node, str):
        return node_pid(node, timeout=timeout, caller_id=caller_id) is not None
    if node.uri is None:
        return False
    pid = node_pid(node.uri, timeout=timeout, caller_id=caller_id)
    return pid is not None and (node.pid is None or pid == node.pid)


def read_live_graph(
    master_uri: str,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    caller_id: str = "/rosreconf",
) -> LiveGraph:
    """Return what the master at ``master_uri`` lists, with each node's API URI and pid.

    ``timeout`` is each XML-RPC call's total deadline and ``max_bytes`` the cap on each
    answer (two calls to the master, one ``lookupNode`` per node, then ``getPid`` to every
    node, eight at a time so hung nodes do not add up). A node that does not answer
    ``getPid`` gets ``pid=None``; only master failures raise. Names and types with
    unprintable characters are refused: no ROS client library makes them, and they would
    reach the terminal.
    """
    rpc.check_uri(master_uri, "ROS master")
    who = "ROS master"
    taken_at = datetime.now(UTC)

    def ask(method: str) -> Any:
        return rpc.call(master_uri, who, timeout, method, caller_id, max_bytes=max_bytes)

    pubs, subs, srvs = _registrations(master_uri, ask("getSystemState"))
    types = _topic_types(master_uri, ask("getTopicTypes"))
    names = sorted({*pubs, *subs, *srvs})
    uris = [_lookup_node(master_uri, n, timeout, max_bytes, caller_id) for n in names]

    def pid_of(uri: str | None) -> int | None:
        return None if uri is None else node_pid(uri, timeout=timeout, caller_id=caller_id)

    with ThreadPoolExecutor(max_workers=_PID_WORKERS) as pool:
        pids = list(pool.map(pid_of, uris))
    nodes = tuple(
        LiveNode(
            name=name,
            uri=uri,
            pid=pid,
            publishes=tuple(sorted(pubs.get(name, ()))),
            subscribes=tuple(sorted(subs.get(name, ()))),
            serves=tuple(sorted(srvs.get(name, ()))),
        )
        for name, uri, pid in zip(names, uris, pids, strict=True)
    )
    return LiveGraph(master_uri, taken_at, nodes, types)


def purge_dead(
    master_uri: str,
    graph: LiveGraph,
    *,
    only: Iterable[str] | None = None,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    caller_id: str = "/rosreconf",
) -> tuple[str, ...]:
    """Unregister, like ``rosnode cleanup``, every node of ``graph`` that no longer answers.

    Each registration is withdrawn in the dead node's name (the master checks the caller's
    API URI). ``only`` restricts the purge to those node names. Returns the purged names.
    """
    rpc.check_uri(master_uri, "ROS master")
    wanted = None if only is None else frozenset(only)
    purged: list[str] = []

    def ask(method: str, *args: object) -> Any:
        return rpc.call(master_uri, "ROS master", timeout, method, *args, max_bytes=max_bytes)

    for node in graph.nodes:
        if (wanted is not None and node.name not in wanted) or node.uri is None:
            continue
        if alive(node.uri, timeout=timeout, caller_id=caller_id):
            continue
        for topic in node.publishes:
            ask("unregisterPublisher", node.name, topic, node.uri)
        for topic in node.subscribes:
            ask("unregisterSubscriber", node.name, topic, node.uri)
        for service in node.serves:
            try:
                service_uri = ask("lookupService", caller_id, service)
            except ExternalToolError:
                continue  # the master no longer lists it
            ask("unregisterService", node.name, service, service_uri)
        purged.append(node.name)
    return tuple(purged)


def shutdown_node(
    node_uri: str, reason: str, *, timeout: float = 2.0, caller_id: str = "/rosreconf"
) -> bool:
    """Ask a node, through its own API, to shut down (what ``rosnode kill`` does).

    Works for any rospy/roscpp node, whoever started it. Returns whether the node accepted;
    a node that is already gone is not an error.
    """
    try:
        rpc.check_uri(node_uri, "node")
        rpc.call(
            node_uri, "node", timeout, "shutdown", caller_id, reason, max_bytes=_NODE_MAX_BYTES
        )
    except (ExternalToolError, UsageError):
        return False
    return True


def master_identity(
    master_uri: str,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    caller_id: str = "/rosreconf",
) -> tuple[int | None, str | None]:
    """Return what tells one run of the master from the next: its pid and ``/run_id``.

    A restarted master lists none of the nodes registered with the one before (ROS 1 nodes
    do not register again), so a watcher must know that it restarted rather than conclude
    that every node failed. roscore sets the parameter ``/run_id`` to a fresh UUID; a bare
    ``rosmaster`` does not (``None``), and then the pid alone tells.
    """
    rpc.check_uri(master_uri, "ROS master")
    who = "ROS master"
    pid = rpc.call(master_uri, who, timeout, "getPid", caller_id, max_bytes=max_bytes)
    answer = rpc.ask(master_uri, who, timeout, max_bytes, "getParam", caller_id, "/run_id")
    found = isinstance(answer, list) and len(answer) == 3 and answer[0] == 1
    run_id = answer[2] if found else None  # -1: no such parameter (a bare rosmaster)
    pid_ok = isinstance(pid, int) and not isinstance(pid, bool)
    return (pid if pid_ok else None), (printable(run_id, 80) if isinstance(run_id, str) else None)


def restarted(before: tuple[int | None, str | None], now: tuple[int | None, str | None]) -> bool:
    """Tell a new master from the same one seen more fully.

    roscore's master answers before roslaunch sets ``/run_id``, so one master can be read first
    without a ``/run_id`` and then with one; only a value that differs from a known value (a
    new pid, or a new ``/run_id``) means the master restarted.
    """
    (pid0, run0), (pid1, run1) = before, now
    if pid0 is not None and pid1 is not None and pid0 != pid1:
        return True
    return run0 is not None and run1 is not None and run0 != run1


def restart_event(
    before: tuple[int | None, str | None] | None, now: tuple[int | None, str | None] | None
) -> tuple[str, dict[str, int | str | None]] | None:
    """Return what to say when the master restarted between two reads (None: it did not)."""
    if before is None or now is None or not restarted(before, now):
        return None
    what = f"pid {before[0]} -> {now[0]}" if before[0] != now[0] else "new /run_id"
    message = (
        f"the ROS master restarted ({what}): it lists none of the nodes registered with "
        "the old one (ROS 1 nodes do not register again), so nothing is counted as "
        "failed; checking the graph against the configuration again"
    )
    data = {"old_pid": before[0], "new_pid": now[0], "old_run_id": before[1], "new_run_id": now[1]}
    return message, data


def known_identity(
    before: tuple[int | None, str | None] | None, now: tuple[int | None, str | None] | None
) -> tuple[int | None, str | None] | None:
    """Return ``now``, keeping what ``before`` knew that ``now`` did not read (same master)."""
    if before is None or now is None or restarted(before, now):
        return now
    return (
        now[0] if now[0] is not None else before[0],
        now[1] if now[1] is not None else before[1],
    )
