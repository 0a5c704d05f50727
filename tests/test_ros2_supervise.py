"""Supervising ROS 2 nodes rosreconf did not start: their processes found, watched and stopped.

Real rclpy nodes (tests/ros2_node.py, Fast DDS, Jazzy and Kilted) are started as plain
processes on a private domain, as a robot's own launch files would: three processes of one
node each and one process holding three nodes (one executor). Their command lines name no
node, so a process is known only from its participant's GUID and /proc. The reference is
each ``Popen.pid``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import ros2_harness
import ros2_real

from rosreconf.ros.ros2 import fastdds_ids, hostprocs
from rosreconf.ros.ros2.discovery import Ros2Discovery
from rosreconf.ros.ros2.hostprocs import Found, HostProcesses, ProcId, locate_participants
from rosreconf.ros.ros2.pidwatch import ProcessWatch, WatchEvents
from rosreconf.ros.ros2.stopproc import Stopped, stop_node_process

SOLO = ("/solo1", "/solo2", "/solo3")
MULTI = ("/multi_a", "/multi_b", "/multi_c")
ROOT = Path(__file__).resolve().parent.parent


class Robot:
    """The outside nodes of one distribution and rosreconf's discovery session on them."""

    def __init__(self, system: ros2_real.Ros2System, session: Ros2Discovery) -> None:
        self.system = system
        self.session = session
        self.pid = {
            n["namespace"].rstrip("/") + "/" + n["name"]: p.process.pid
            for p in system.processes
            for n in p.nodes
        }
        self.popen = {p.process.pid: p.process for p in system.processes}

    def locate(self) -> dict[bytes, hostprocs.Located]:
        """Return where every participant's process is, from a fresh read."""
        self.session.read()
        return locate_participants(self.session.participant_nodes, self.system.domain)

    def by_node(self) -> dict[str, hostprocs.Located]:
        """Return each node's located participant."""
        return {n: where for where in self.locate().values() for n in where.nodes}


@pytest.fixture(scope="module", params=ros2_real.DISTROS)
def robot(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Robot]:
    """Start the outside nodes of one distribution and read their graph."""
    distro = str(request.param)
    ros2_real.python_of(distro)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CYCLONEDDS_URI", ros2_harness.loopback_config())
        tmp = tmp_path_factory.mktemp(f"supervise-{distro}")
        system = ros2_real.Ros2System.on_a_free_domain(distro, tmp)
        try:
            for name in SOLO:
                system.start({"name": name[1:], "namespace": "/"})
            system.start(*({"name": n[1:], "namespace": "/"} for n in MULTI))
            with Ros2Discovery(system.domain, distro) as session:
                graph = session.read()
                assert {n.name for n in graph.nodes} == {*SOLO, *MULTI}
                yield Robot(system, session)
        finally:
            system.stop()


def test_every_node_maps_to_its_true_process(robot: Robot) -> None:
    by_node = robot.by_node()
    assert set(by_node) == {*SOLO, *MULTI}
    for name, where in by_node.items():
        assert where.found is Found.CONFIRMED, where.detail
        assert where.proc is not None and where.proc.pid == robot.pid[name]
        assert fastdds_ids.fastdds_fields(where.participant) == (
            fastdds_ids.this_host_id(),
            robot.pid[name] & 0xFFFF,
        )
    processes = hostprocs.nodes_by_process(robot.locate())
    multi = {proc.pid: nodes for proc, nodes in processes.items()}
    assert multi[robot.pid["/multi_a"]] == MULTI
    for name in SOLO:
        assert multi[robot.pid[name]] == (name,)


def test_a_process_not_readable_is_not_guessed(robot: Robot) -> None:
    """As another user, /proc/<pid>/fd of the nodes is closed: each says so, with no pid.

    setpriv (util-linux) drops to nobody: Popen's ``user=`` could not exec the venv's
    python here (its interpreter lives under /root, 0700).
    """
    if os.geteuid() != 0:
        pytest.fail("needs root (as make test runs here) to read as another user", pytrace=False)
    script = (
        "import json, sys\n"
        "from rosreconf.ros.ros2.hostprocs import locate_participants\n"
        "parts = {bytes.fromhex(k): v for k, v in json.loads(sys.argv[1]).items()}\n"
        "found = locate_participants(parts, int(sys.argv[2]))\n"
        "print(json.dumps({k.hex(): [w.found.value, w.proc is None] for k, w in found.items()}))\n"
    )
    parts = {k.hex(): list(v) for k, v in robot.session.participant_nodes.items()}
    nobody = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
    out = subprocess.run(
        [*nobody, sys.executable, "-c", script, json.dumps(parts), str(robot.system.domain)],
        capture_output=True,
        check=True,
        cwd="/",
        env={"PATH": os.environ["PATH"], "PYTHONPATH": str(ROOT)},
        timeout=60,
    )
    found = json.loads(out.stdout)
    assert len(found) == 4
    assert all(v == ["not-readable", True] for v in found.values()), found


def test_live_nodes_out_of_sight_are_never_taken_for_gone(robot: Robot) -> None:
    """From a pid namespace of its own (a container of a pod that shares the host's network),
    the nodes' processes cannot be seen: no candidate, but never gone, since the domain's
    sockets in this network namespace belong to processes out of its sight."""
    if os.geteuid() != 0:
        pytest.fail("needs root (as make test runs here) for unshare --pid", pytrace=False)
    script = (
        "import json, sys\n"
        "from rosreconf.ros.ros2.hostprocs import locate_participants\n"
        "parts = {bytes.fromhex(k): v for k, v in json.loads(sys.argv[1]).items()}\n"
        "found = locate_participants(parts, int(sys.argv[2]))\n"
        "print(json.dumps({k.hex(): [w.found.value, w.proc is None] for k, w in found.items()}))\n"
    )
    parts = {k.hex(): list(v) for k, v in robot.session.participant_nodes.items()}
    contained = ["unshare", "--pid", "--fork", "--mount-proc", "--kill-child"]
    out = subprocess.run(
        [*contained, sys.executable, "-c", script, json.dumps(parts), str(robot.system.domain)],
        capture_output=True,
        check=True,
        cwd="/",
        env={"PATH": os.environ["PATH"], "PYTHONPATH": str(ROOT)},
        timeout=60,
    )
    found = json.loads(out.stdout)
    assert len(found) == 4
    assert all(v == ["no-candidate", True] for v in found.values()), found


def test_candidates_that_cannot_be_confirmed_are_said_as_such(robot: Robot) -> None:
    some = next(iter(robot.session.participant_nodes))
    host = HostProcesses()
    with subprocess.Popen(["sleep", "60"]) as sleeper:
        try:
            # Right host, a real pid started before, but that process holds no DDS socket.
            decoy = some[:4] + (sleeper.pid & 0xFFFF).to_bytes(2, "little") + some[6:]
            where = HostProcesses().locate(decoy, robot.system.domain, ("/decoy",))
            assert where.found is Found.UNCONFIRMED and where.proc is None
            assert where.candidates == (sleeper.pid,)
        finally:
            sleeper.kill()
    other_host = some[:2] + ((fastdds_ids.this_host_id() ^ 1).to_bytes(2, "little")) + some[4:]
    assert host.locate(other_host, robot.system.domain).found is Found.OTHER_HOST
    cyclone = b"\x01\x10" + some[2:]
    assert host.locate(cyclone, robot.system.domain).found is Found.OTHER_VENDOR
    # Seen before any of these processes started: a pid's later owner is not the node's, and
    # with every socket of the domain here a process's seen here, no other could hold it
    before = host.locate(some, robot.system.domain, seen_at=1.0)
    assert before.found is Found.GONE and before.proc is None


def _poll_until(watch: ProcessWatch, want: str, proc: ProcId, seconds: float = 5.0) -> WatchEvents:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        events = watch.poll(0.1)
        if proc in getattr(events, want):
            return events
    raise AssertionError(f"{proc} not {want} within {seconds} s")


@pytest.mark.parametrize("use_pidfd", [True, False])
def test_exit_and_stop_of_a_plain_process_are_seen(use_pidfd: bool) -> None:
    with subprocess.Popen(["sleep", "60"]) as p, ProcessWatch(use_pidfd=use_pidfd) as watch:
        proc = hostprocs.read_proc_id(p.pid)
        assert proc is not None and watch.add(proc)
        assert not watch.poll(0.05)
        p.send_signal(signal.SIGSTOP)
        _poll_until(watch, "stopped", proc)
        p.send_signal(signal.SIGCONT)
        _poll_until(watch, "resumed", proc)
        p.kill()
        _poll_until(watch, "exited", proc)
        assert proc not in watch.watched


def test_kill_and_stop_of_outside_nodes_are_seen(robot: Robot) -> None:
    located = robot.by_node()
    solo1, solo2 = located["/solo1"].proc, located["/solo2"].proc
    assert solo1 is not None and solo2 is not None
    with ProcessWatch() as watch:
        watch.add_all(w.proc for w in located.values() if w.proc is not None)
        assert len(watch.watched) == 4
        os.kill(solo1.pid, signal.SIGSTOP)
        try:
            assert _poll_until(watch, "stopped", solo1).stopped == (solo1,)
        finally:
            os.kill(solo1.pid, signal.SIGCONT)
        _poll_until(watch, "resumed", solo1)
        os.kill(solo2.pid, signal.SIGKILL)
        events = _poll_until(watch, "exited", solo2)
        assert events.exited == (solo2,) and solo1 in watch.watched
    # The lease keeps the killed participant in the graph; its process is proven gone: no
    # process has its pid, and each socket of the domain here is a live process's
    still = {n: w for n, w in robot.by_node().items() if n == "/solo2"}
    assert still, "the killed node's participant is announced until its lease ends"
    assert all(w.found is Found.GONE and w.proc is None for w in still.values())
    assert all("its process has ended" in w.detail for w in still.values())
    robot.popen[solo2.pid].wait(5)


def test_stop_refuses_a_shared_process_and_stops_a_single_node_one(robot: Robot) -> None:
    located = robot.locate()
    processes = hostprocs.nodes_by_process(located)
    by_node = {n: w for w in located.values() for n in w.nodes}
    multi = by_node["/multi_b"].proc
    assert multi is not None
    refused = stop_node_process(multi, "/multi_b", processes[multi], grace=1.0)
    assert refused.outcome is Stopped.REFUSED
    assert refused.others == ("/multi_a", "/multi_c")
    assert "/multi_a" in refused.message and "/multi_c" in refused.message
    assert robot.popen[multi.pid].poll() is None
    solo = by_node["/solo3"].proc
    assert solo is not None
    stopped = stop_node_process(solo, "/solo3", processes[solo], grace=3.0)
    assert stopped.outcome is Stopped.STOPPED and stopped.signal_used is signal.SIGINT
    assert robot.popen[solo.pid].wait(5) is not None
    again = stop_node_process(solo, "/solo3", processes[solo])
    assert again.outcome is Stopped.GONE


def _fake_proc(root: Path, pid: int, ports: tuple[int, ...], *, start: int = 100) -> None:
    """Write a process into a fake /proc: stat, status, socket fds and its UDP table."""
    d = root / str(pid)
    (d / "fd").mkdir(parents=True)
    (d / "net").mkdir()
    (d / "stat").write_text(f"{pid} (python) S 1 1 1 0 -1 0 0 0 0 0 0 0 0 0 20 0 9 0 {start} 1 1\n")
    (d / "status").write_text(f"Name:\tpython\nNSpid:\t{pid}\n")
    (d / "cmdline").write_bytes(b"python\0node.py\0")
    rows = ["  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid"]
    for i, port in enumerate(ports):
        inode = pid * 100 + i
        os.symlink(f"socket:[{inode}]", d / "fd" / str(3 + i))
        rows.append(
            f"  {i}: 00000000:{port:04X} 00000000:0000 07 00000000:00000000 00:00000000 "
            f"00000000     0        0 {inode} 2 0000000000000000 0"
        )
    (d / "net" / "udp").write_text("\n".join(rows) + "\n")


def test_two_processes_that_may_hold_a_participant_are_ambiguous(tmp_path: Path) -> None:
    """Pids 0x1234 and 0x11234 share their low 16 bits; both on domain 3: never a guess."""
    domain, base = 3, 7400 + 250 * 3
    _fake_proc(tmp_path, 0x1234, (base, base + 10, base + 11))
    _fake_proc(tmp_path, 0x11234, (base + 12, base + 13))
    _fake_proc(tmp_path, 0x21234, (base + 40,))  # one port of the range alone: not the domain
    guid = b"\x01\x0f" + (0xABCD).to_bytes(2, "little") + (0x1234).to_bytes(2, "little")
    guid += bytes(10)
    host = HostProcesses({0xABCD}, tmp_path)
    where = host.locate(guid, domain, ("/n",), seen_at=1e9)
    assert where.found is Found.AMBIGUOUS and where.proc is None
    assert set(where.candidates) == {0x1234, 0x11234, 0x21234}
    (tmp_path / str(0x11234) / "stat").unlink()  # gone: one candidate left, proven
    where = HostProcesses({0xABCD}, tmp_path).locate(guid, domain, ("/n",), seen_at=1e9)
    assert where.found is Found.CONFIRMED and where.proc == ProcId(0x1234, 100)
    late = HostProcesses({0xABCD}, tmp_path).locate(guid, domain, seen_at=0.5)
    assert late.found is Found.NO_CANDIDATE  # started after the participant was seen


@pytest.mark.parametrize("distro", ros2_real.DISTROS)
def test_a_node_in_a_pid_namespace_is_found_by_its_host_pid(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    """In a pid namespace (a container) the GUID carries pid 1: NSpid links it to this host's."""
    if os.geteuid() != 0:
        pytest.fail("needs root (as make test runs here) for unshare --pid", pytrace=False)
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({"nodes": [{"name": "contained", "namespace": "/"}]}))
    argv = ["unshare", "--pid", "--fork", "--kill-child"]
    argv += [str(ros2_real.python_of(distro)), str(ros2_real.NODE), str(spec)]
    env = ros2_real.node_env(ros2_domain, tmp_path / "home")
    proc = ros2_harness.start_ready(argv, tmp_path / "err", env, "namespaced node")
    try:
        with Ros2Discovery(ros2_domain, distro) as session:
            session.read()
            located = locate_participants(session.participant_nodes, ros2_domain)
        (where,) = located.values()
        assert fastdds_ids.fastdds_fields(where.participant) == (fastdds_ids.this_host_id(), 1)
        assert where.found is Found.CONFIRMED and where.proc is not None
        status = Path(f"/proc/{where.proc.pid}/status").read_text()
        assert f"NSpid:\t{where.proc.pid}\t1" in status
        assert where.proc.pid != proc.pid  # unshare's child, not unshare itself
    finally:
        os.killpg(proc.pid, signal.SIGTERM)  # unshare ignores SIGTERM; its child does not
        ros2_real.stop_all([proc])
