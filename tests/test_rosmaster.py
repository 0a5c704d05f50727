"""Tests of rosreconf.ros.ros1.rosmaster: against a real roscore (marked ros) and against fakes."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import threading
import time
import xmlrpc.client
import xmlrpc.server
from collections.abc import Iterator
from contextlib import suppress
from pathlib import Path
from typing import Any

import pytest
import ros_harness
from conftest import StartStandIn
from misbehaving_masters import DripMaster, EndlessMaster
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.ros.livegraph import LiveNode, from_json, to_json, without_plumbing
from rosreconf.ros.ros1.rosmaster import alive, purge_dead, read_live_graph

TALKER = {
    "name": "talker",
    "publish": [{"topic": "/a", "type": "std_msgs/String"}],
    "serve": [{"service": "/s", "type": "std_srvs/Trigger"}],
}
LISTENER = {"name": "listener", "subscribe": [{"topic": "/a", "type": "std_msgs/String"}]}


@pytest.mark.ros
def test_reads_exactly_the_standins_with_types(ros_master_uri: str, standin: StartStandIn) -> None:
    talker, listener = standin(TALKER), standin(LISTENER)
    graph = without_plumbing(read_live_graph(ros_master_uri))
    assert graph.names == ("/listener", "/talker")
    t, li = graph.node("/talker"), graph.node("/listener")
    assert (t.publishes, t.subscribes, t.serves) == (("/a",), (), ("/s",))
    assert (li.publishes, li.subscribes, li.serves) == ((), ("/a",), ())
    assert dict(graph.topic_types) == {"/a": "std_msgs/String"}
    assert (t.pid, li.pid) == (talker.process.pid, listener.process.pid)
    assert all(n.uri is not None and n.uri.startswith("http://127.0.0.1:") for n in graph.nodes)


@pytest.mark.ros
def test_plumbing_is_kept_in_the_raw_graph(ros_master_uri: str, standin: StartStandIn) -> None:
    standin(TALKER)
    ros_harness.wait_until(
        lambda: "/rosout" in read_live_graph(ros_master_uri).names, 10, "rosout registering"
    )
    graph = read_live_graph(ros_master_uri)
    assert {"/rosout", "/rosout_agg"} <= set(graph.topic_types)
    assert "/talker/get_loggers" in graph.node("/talker").serves
    assert "/rosout" in graph.node("/talker").publishes


@pytest.mark.ros
def test_invented_type_is_what_the_master_reports(
    ros_master_uri: str, standin: StartStandIn
) -> None:
    cmd = [{"topic": "/cmd", "type": "robot_arm_msgs/DcServoCommand"}]
    standin({"name": "arm", "publish": cmd, "serve": [{"service": "/move", "type": "arm/Move"}]})
    ctl = standin({"name": "ctl", "subscribe": cmd})
    graph = read_live_graph(ros_master_uri)
    assert graph.topic_types["/cmd"] == "robot_arm_msgs/DcServoCommand"
    assert graph.node("/arm").serves[-1] == "/move"
    ctl_api = xmlrpc.client.ServerProxy(graph.node("/ctl").uri or "")

    def connected() -> bool:
        bus: Any = ctl_api.getBusInfo("/test")
        return any(c[4] == "/cmd" and c[5] for c in bus[2])

    ros_harness.wait_until(connected, 10, "the invented-type subscriber connecting")
    assert ctl.process.poll() is None


@pytest.mark.ros
def test_snapshot_round_trip_of_a_live_graph(ros_master_uri: str, standin: StartStandIn) -> None:
    standin(TALKER)
    standin(LISTENER)
    graph = read_live_graph(ros_master_uri)
    assert from_json(to_json(graph)) == graph
    assert to_json(from_json(to_json(graph))) == to_json(graph)


@pytest.mark.ros
def test_stopped_node_leaves_at_once(ros_master_uri: str, standin: StartStandIn) -> None:
    node = standin(LISTENER)
    os.killpg(node.process.pid, signal.SIGTERM)
    took = ros_harness.wait_until(
        lambda: "/listener" not in read_live_graph(ros_master_uri).names, 5, "unregistering"
    )
    assert took < 5


@pytest.mark.ros
def test_killed_node_lingers_until_purged(ros_master_uri: str, standin: StartStandIn) -> None:
    victim, survivor = standin(LISTENER), standin(TALKER)
    before = read_live_graph(ros_master_uri).node("/listener")
    assert alive(before)
    os.killpg(victim.process.pid, signal.SIGKILL)
    victim.process.wait(5)
    # The master never drops it by itself (measured: still there after 30 s); wait only
    # until the graph reads it as dead (its XML-RPC server gone), not a fixed 2 s.
    ros_harness.wait_until(
        lambda: not alive(read_live_graph(ros_master_uri).node("/listener")),
        10,
        "the killed listener read as dead",
    )
    graph = read_live_graph(ros_master_uri)
    dead = graph.node("/listener")
    assert dead.subscribes == ("/a",) and dead.pid is None and not alive(dead)
    assert graph.node("/talker").pid == survivor.process.pid
    assert purge_dead(ros_master_uri, graph) == ("/listener",)
    after = read_live_graph(ros_master_uri)
    assert "/listener" not in after.names and "/talker" in after.names
    assert not any(
        "/listener" in nodes for part in after_state(ros_master_uri) for _, nodes in part
    )


def after_state(uri: str) -> list[list[tuple[str, list[str]]]]:
    """Return getSystemState's raw lists, straight from the master."""
    return ros_harness.system_state(uri) or []


@pytest.mark.ros
def test_master_teardown_kills_everything_even_on_failure(tmp_path: Path) -> None:
    pids: set[int] = set()
    failing = pytest.raises(RuntimeError, match="test body failed")
    with failing, ros_harness.running_master(tmp_path / "ros") as master:
        root = master.process.pid
        ros_harness.wait_until(lambda: len(ros_harness.descendants(root)) >= 2, 10, "rosout")
        pids = {root, *ros_harness.descendants(root)}
        raise RuntimeError("test body failed")
    assert len(pids) >= 3 and not any(ros_harness.running(p) for p in pids)


def test_unreachable_master_names_the_uri() -> None:
    uri = f"http://127.0.0.1:{ros_harness.free_port()}/"
    with pytest.raises(ExternalToolError, match=uri):
        read_live_graph(uri, timeout=1.0)


def test_silent_master_times_out_naming_the_uri() -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen(1)
        uri = f"http://127.0.0.1:{s.getsockname()[1]}/"
        start = time.monotonic()
        with pytest.raises(ExternalToolError, match=f"{uri} did not answer getSystemState"):
            read_live_graph(uri, timeout=0.3)
        assert time.monotonic() - start < 2


@pytest.fixture
def fake_master() -> Iterator[xmlrpc.server.SimpleXMLRPCServer]:
    server = xmlrpc.server.SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server
    server.shutdown()
    server.server_close()
    thread.join(5)


@pytest.mark.parametrize(
    ("answer", "message"),
    [
        ("nonsense", "not \\[code, status, value\\]"),
        ([1, "ok", [[["/a", "not-a-list"]], [], []]], "unexpected"),
        ([-1, "master is sad", 0], "master is sad"),
    ],
)
def test_bad_answers_become_external_tool_errors(
    fake_master: xmlrpc.server.SimpleXMLRPCServer, answer: object, message: str
) -> None:
    def get_system_state(_caller: Any) -> Any:
        return answer

    fake_master.register_function(get_system_state, "getSystemState")
    uri = f"http://127.0.0.1:{fake_master.server_address[1]}/"
    with pytest.raises(ExternalToolError, match=message) as err:
        read_live_graph(uri)
    assert uri in str(err.value)


@pytest.mark.parametrize("uri", ["localhost:11311", "ftp://h:1/", "http://h/", "http://h:x/"])
def test_malformed_master_uri_is_a_usage_error(uri: str) -> None:
    with pytest.raises(UsageError, match="http://HOST:PORT/"):
        read_live_graph(uri)


def test_alive_is_false_for_nothing_listening() -> None:
    assert not alive(f"http://127.0.0.1:{ros_harness.free_port()}/", timeout=0.5)


def test_alive_wants_the_same_pid(fake_master: xmlrpc.server.SimpleXMLRPCServer) -> None:
    def get_pid(_caller: Any) -> Any:
        return [1, "", 4242]

    fake_master.register_function(get_pid, "getPid")
    uri = f"http://127.0.0.1:{fake_master.server_address[1]}/"
    assert alive(uri) and alive(LiveNode("/n", uri, 4242)) and alive(LiveNode("/n", uri))
    assert not alive(LiveNode("/n", uri, 17)) and not alive(LiveNode("/n", None, 4242))


def test_a_dripping_master_is_given_up_on_at_the_total_deadline() -> None:
    # Each byte arrives 0.05 s after the last, far within any per-read timeout; the whole
    # answer would take about 30 s. The deadline is for the whole call.
    with DripMaster(interval=0.05, lifetime=20.0) as fake:
        start = time.monotonic()
        with pytest.raises(ExternalToolError, match=f"{fake.uri} did not answer getSystemState"):
            read_live_graph(fake.uri, timeout=0.5)
        took = time.monotonic() - start
    assert 0.4 < took < 15.0, took  # the whole answer needs 30 s; slack for a loaded machine
    assert fake.sent < 300


def test_an_endless_answer_is_cut_at_the_byte_cap() -> None:
    with EndlessMaster(lifetime=20.0) as fake:
        start = time.monotonic()
        with pytest.raises(ExternalToolError, match="more than 1 MiB") as err:
            read_live_graph(fake.uri, timeout=10.0, max_bytes=1 << 20)
        took = time.monotonic() - start
    assert took < 15.0, took  # the fake would stream for 20 s
    assert fake.sent < 64 << 20  # stopped reading soon after the cap, not at the deadline
    assert "xxxx" not in str(err.value)


def _answer_raw(head: bytes, body: bytes) -> Iterator[str]:
    """Serve one connection with ``head`` + ``body`` as the whole HTTP answer; yield the URI."""
    server = socket.create_server(("127.0.0.1", 0))
    server.settimeout(5.0)

    def serve() -> None:
        with suppress(OSError):
            conn, _ = server.accept()
            with conn:
                conn.settimeout(5.0)
                conn.recv(65536)
                conn.sendall(head + body)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.getsockname()[1]}/"
    thread.join(10)
    server.close()


TERMINAL_TRICKS = "\x1b]2;owned\x07\x1b[2J\u009b31m\u202e"


@pytest.mark.parametrize(
    ("head", "body"),
    [
        (f"HTTP/1.0 500 {TERMINAL_TRICKS}\r\n\r\n".encode("latin-1", "replace"), b""),
        (f"{TERMINAL_TRICKS}\r\n\r\n".encode(), b""),
        (
            b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n",
            xmlrpc.client.dumps(
                ([-1, f"sad {TERMINAL_TRICKS[-6:]}", 0],), methodresponse=True
            ).encode(),
        ),
        (
            b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n",
            xmlrpc.client.dumps(
                ([1, "", [[[f"/t{TERMINAL_TRICKS[-6:]}", ["/n"]]], [], []]],), methodresponse=True
            ).encode(),
        ),
        (
            b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n",
            xmlrpc.client.dumps(
                xmlrpc.client.Fault(1, f"boom {TERMINAL_TRICKS[-6:]}"), methodresponse=True
            ).encode(),
        ),
    ],
    ids=["reason-phrase", "status-line", "status-text", "topic-name", "fault"],
)
def test_no_raw_bytes_from_the_wire_reach_the_message(head: bytes, body: bytes) -> None:
    for uri in _answer_raw(head, body):
        with pytest.raises(ExternalToolError) as err:
            read_live_graph(uri, timeout=2.0)
        text = str(err.value)
        assert uri in text
        assert text.isprintable(), repr(text)


def test_inspect_gives_up_on_a_dripping_master_with_exit_3(runner: CliRunner) -> None:
    with DripMaster(interval=0.05, lifetime=20.0) as fake:
        args = ["inspect", "--master", fake.uri, "--only", "object_repositioning"]
        result = runner.invoke(app, [*args, "--master-timeout", "0.5"])
    assert result.exit_code == 3, result.output
    assert f"{fake.uri} did not answer getSystemState within 0.5 s" in result.stderr
    assert "Traceback" not in result.stderr


def test_snapshot_cuts_an_endless_answer_at_the_given_cap(runner: CliRunner) -> None:
    with EndlessMaster(lifetime=20.0) as fake:
        result = runner.invoke(app, ["snapshot", "--master", fake.uri, "--max-answer-mb", "1"])
    assert result.exit_code == 3, result.output
    assert "with more than 1 MiB" in result.stderr and result.stdout == ""


ARGVS = (["/usr/lib/rosout/rosout", "__name:=stray_rosout"], ["sleep", "300"])


def _runs(process: subprocess.Popen[bytes], program: str) -> bool:
    """Tell whether ``process`` runs ``program`` now (its /proc command line names it)."""
    try:
        cmdline = Path(f"/proc/{process.pid}/cmdline").read_bytes()
    except OSError:
        return False
    return Path(cmdline.split(b"\0")[0].decode()).name == Path(program).name


@pytest.mark.ros
def test_the_harness_kills_a_stray_rosout_and_still_reports_any_other_leftover(
    tmp_path: Path,
) -> None:
    """A rosout outside roscore's process tree (as one forked just as roscore was killed) is
    roscore's own and is killed at teardown; any other process left using the master's
    ROS_HOME is still a leftover that fails the test, named by its command line."""
    home = tmp_path / "ros"
    started: list[subprocess.Popen[bytes]] = []
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    with (
        pytest.raises(AssertionError, match="processes left") as left,
        ros_harness.running_master(home) as master,
    ):
        env = ros_harness.ros_env(master.uri, home)
        for argv in ARGVS:
            started.append(subprocess.Popen(argv, env=env, start_new_session=True, **quiet))
        ros_harness.wait_until(  # both running (exec'd), neither a descendant of roscore
            lambda: all(_runs(p, argv[0]) for p, argv in zip(started, ARGVS, strict=True)),
            10,
            "the stray rosout and sleep running",
        )
    codes = [p.wait(10) for p in started]
    assert codes == [-signal.SIGKILL, -signal.SIGKILL]  # both gone after teardown
    assert "sleep 300" in str(left.value)
    assert "rosout" not in str(left.value)
