"""Start a real ROS 1 master and stand-in nodes for tests, and make sure none outlives them.

roscore's children (rosmaster, rosout) are started by roslaunch with ``setsid``, so each sits
in its own session and process group: killing roscore's group alone would orphan them.
Teardown therefore kills the group of every process descended from roscore, recorded while
they run, and then checks that no process is left whose environment names this master's
private ROS_HOME (that also catches stand-ins a test forgot).

Everything here talks to the master with raw ``xmlrpc.client`` so that a bug in
``rosreconf.ros.ros1.rosmaster`` cannot hide behind the harness.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import time
import xmlrpc.client
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosreconf.procs import descendants

SYSTEM_PYTHON = "/usr/bin/python3"
"""Debian's Python, the one with rospy (the project's venv has none)."""
STANDIN = Path(__file__).parents[1] / "rosreconf" / "ros" / "ros1" / "scripts" / "standin_node.py"
MASTER_START_TIMEOUT = 20.0
NODE_START_TIMEOUT = 15.0
STOP_TIMEOUT = 5.0


def ros_installed() -> bool:
    """Tell whether roscore and the system Python's rospy are there (scripts/system-deps.sh)."""
    if shutil.which("roscore") is None or not Path(SYSTEM_PYTHON).exists():
        return False
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import rospy"], capture_output=True, check=False)
    return probe.returncode == 0


PORTS = range(20000, 32000)
"""TCP ports the tests' masters take (below Linux's ephemeral range, 32768 up, so no
connection's own port is handed out here); with xdist each worker takes its own share."""
_next_port = [0]


def free_port() -> int:
    """Return a TCP port on 127.0.0.1 that nothing listens on right now, from this worker's
    share of ``PORTS`` (two workers never pick the same port before one binds it)."""
    name = os.environ.get("PYTEST_XDIST_WORKER", "")
    count = max(int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1), 1)
    index = int(name[2:]) if name.startswith("gw") else 0
    share = len(PORTS) // count
    first = PORTS.start + index * share
    for _ in range(share):
        port = first + (_next_port[0] + os.getpid()) % share
        _next_port[0] += 1
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    raise RuntimeError(f"no free TCP port in {first}..{first + share - 1}")


def wait_until(
    check: Callable[[], bool], timeout: float, what: str, interval: float = 0.05
) -> float:
    """Poll ``check`` until it holds; return the seconds it took, or fail naming ``what``."""
    start = time.monotonic()
    while True:
        if check():
            return time.monotonic() - start
        if time.monotonic() - start > timeout:
            raise TimeoutError(f"{what} did not happen within {timeout:g} s")
        time.sleep(interval)


class _Patient(xmlrpc.client.Transport):
    """An XML-RPC transport that gives up after ``timeout`` seconds."""

    def __init__(self, timeout: float) -> None:
        super().__init__()
        self.timeout = timeout

    def make_connection(self, host: Any) -> Any:
        conn = super().make_connection(host)
        conn.timeout = self.timeout
        return conn


def system_state(uri: str, timeout: float = 2.0) -> list[Any] | None:
    """Return getSystemState's ``[pubs, subs, srvs]``, or None if the master does not answer."""
    try:
        answer: Any = xmlrpc.client.ServerProxy(uri, transport=_Patient(timeout)).getSystemState(
            "/h"
        )
    except (OSError, xmlrpc.client.Error):
        return None
    return list(answer[2]) if answer[0] == 1 else None


def registered(uri: str, node: str) -> tuple[set[str], set[str], set[str]]:
    """Return the topics node publishes, subscribes and the services it serves, per master."""
    state = system_state(uri) or [[], [], []]
    pubs, subs, srvs = ({name for name, nodes in part if node in nodes} for part in state)
    return pubs, subs, srvs


def ros_env(uri: str, home: Path) -> dict[str, str]:
    """Return this environment minus ROS/Python settings, plus a private master and ROS_HOME."""
    keep = {k: v for k, v in os.environ.items() if not k.startswith(("ROS", "PYTHON"))}
    keep.pop("VIRTUAL_ENV", None)
    return keep | {
        "ROS_MASTER_URI": uri,
        "ROS_HOME": str(home),
        "ROS_LOG_DIR": str(home / "log"),
        "ROS_HOSTNAME": "127.0.0.1",
    }


@dataclass
class Master:
    """A running roscore: its URI, its private ROS_HOME and every process it started."""

    uri: str
    port: int
    home: Path
    process: subprocess.Popen[bytes]
    pids: set[int] = field(default_factory=set)

    def env(self) -> dict[str, str]:
        """Return the environment a ROS process needs to use this master and nothing else."""
        return ros_env(self.uri, self.home)

    def remember_children(self) -> None:
        """Record every living descendant of roscore, for teardown."""
        self.pids |= descendants(self.process.pid)


def _stat(pid: int) -> tuple[str, int] | None:
    """Return (state, parent pid) from /proc, or None if ``pid`` is gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2 :].split()
    return fields[0], int(fields[1])


def running(pid: int) -> bool:
    """Tell whether ``pid`` is a process that is not a zombie."""
    st = _stat(pid)
    return st is not None and st[0] != "Z"


def processes_using(home: Path) -> list[int]:
    """Return the living processes whose environment has ROS_HOME=``home``."""
    needle = f"ROS_HOME={home}\0".encode()
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and int(entry.name) != os.getpid():
            with suppress(OSError):
                if needle in (entry / "environ").read_bytes() + b"\0" and running(int(entry.name)):
                    found.append(int(entry.name))
    return found


def kill_group(pid: int, sig: int = signal.SIGKILL) -> None:
    """Send ``sig`` to the process group ``pid`` leads (a no-op when it is gone)."""
    with suppress(ProcessLookupError, PermissionError):
        os.killpg(pid, sig)


def stop(*processes: subprocess.Popen[bytes], grace: float = STOP_TIMEOUT) -> None:
    """Stop processes started in their own sessions: SIGTERM each group, SIGKILL after ``grace``.

    All are signalled before any is waited for, so stopping n nodes costs one grace, not n.
    """
    for process in processes:
        kill_group(process.pid, signal.SIGTERM)
    deadline = time.monotonic() + grace
    for process in processes:
        try:
            process.wait(max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            kill_group(process.pid)
            process.wait(grace)
        kill_group(process.pid)  # anything it left in its group


def _start_roscore(master: Master) -> None:
    """Start ``roscore -p PORT`` for ``master`` and wait until it answers."""
    log = (master.home / "roscore.out").open("ab")
    proc = subprocess.Popen(
        ["roscore", "-p", str(master.port)], env=master.env(), stdout=log,
        stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    log.close()
    master.process = proc

    def up() -> bool:
        if proc.poll() is not None:
            out = (master.home / "roscore.out").read_text(errors="replace")[-2000:]
            raise RuntimeError(f"roscore exited with {proc.returncode}:\n{out}")
        return system_state(master.uri, timeout=0.5) is not None

    wait_until(up, MASTER_START_TIMEOUT, f"ROS master answering at {master.uri}")
    master.remember_children()


ROSCORES_OWN = frozenset({"roscore", "rosmaster", "rosout"})
"""Programs roscore itself runs; any other process left using a master's ROS_HOME is a leak."""


def _roscores_own(pid: int) -> bool:
    """Tell whether ``pid`` is roscore, its master or its rosout (by its program's name)."""
    argv = cmdline(pid).split()
    return any(Path(arg).name in ROSCORES_OWN for arg in argv[:2])


def _kill_roscore(master: Master) -> None:
    """Kill roscore and every process it started (rosmaster, rosout), and wait for them.

    roscore (a roslaunch) runs rosout with respawn="true" and in a session of its own: a
    rosout killed while roscore still lives is started again under a new pid that no record
    holds (a fresh clone's suite once found such a rosout alive after teardown; this is our
    reading of it). So roscore dies first, then the children recorded before, then whatever
    of roscore's own programs still uses this master's ROS_HOME; anything else there stays
    for the leftover check, which is what it is for.
    """
    master.remember_children()
    kill_group(master.process.pid)
    with suppress(subprocess.TimeoutExpired):
        master.process.wait(STOP_TIMEOUT)
    for pid in master.pids:
        kill_group(pid)
    strays = {pid for pid in processes_using(master.home) if _roscores_own(pid)}
    for pid in strays:
        kill_group(pid)
        with suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)
    gone = master.pids | strays
    wait_until(lambda: not any(running(p) for p in gone), STOP_TIMEOUT, "roscore exit")


def restart_master(master: Master) -> None:
    """Kill the master (SIGKILL, like a crash) and start a new one on the same port.

    Nodes registered with the old master keep running; ROS 1 nodes do not register again,
    so the new master lists none of them.
    """
    _kill_roscore(master)
    _start_roscore(master)


@contextmanager
def running_master(home: Path) -> Iterator[Master]:
    """Run ``roscore -p <free port>`` with a private ROS_HOME; kill all of it on exit."""
    home.mkdir(parents=True, exist_ok=True)
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    master = Master(uri, port, home, None)  # type: ignore[arg-type]  # set by _start_roscore
    try:
        _start_roscore(master)
        yield master
    finally:
        if master.process is not None:
            _kill_roscore(master)
        left = _lingering(home, STOP_TIMEOUT)
        for pid in left:
            kill_group(pid)
            with suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        assert not left, f"processes left after stopping the master at {uri} (killed): {left}"


def _lingering(home: Path, grace: float) -> dict[int, str]:
    """Return the processes using ``home`` that are still alive ``grace`` seconds from now.

    Teardown SIGKILLs process groups without waiting for every member (``stop``), and a killed
    process is listed until the kernel has torn it down, which under load can outlast the
    scan that follows at once: a fresh clone's suite once failed so (1 run in 12). What
    outlives the grace is a real leftover and fails the test, named by its command line.
    """
    deadline = time.monotonic() + grace
    while (left := processes_using(home)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return {pid: cmdline(pid) for pid in left}


def cmdline(pid: int) -> str:
    """Return ``pid``'s command line, for naming a leftover ("?" when it is gone)."""
    try:
        return (
            Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        )
    except OSError:
        return "?"


@dataclass
class StandIn:
    """A running stand-in node: its global name, its spec and its process."""

    name: str
    spec: dict[str, Any]
    process: subprocess.Popen[bytes]


def start_standin(master: Master, spec: dict[str, Any]) -> StandIn:
    """Start ROS 1's ``scripts/standin_node.py`` with ``spec``; return once the master lists it."""
    name = "/" + spec["name"].lstrip("/")
    spec_file = master.home / f"standin-{spec['name']}.json"
    spec_file.write_text(json.dumps(spec))
    out = (master.home / f"standin-{spec['name']}.out").open("wb")
    proc = subprocess.Popen(
        [SYSTEM_PYTHON, str(STANDIN), str(spec_file)], env=master.env(), stdout=out,
        stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    out.close()
    node = StandIn(name, spec, proc)
    # rospy registers a node's own logger services after its topics (RegManager.start), in a
    # thread: wait for them too, so a stop sent once this returns finds nothing in flight (an
    # unregister that reaches the master before a late register leaves the node listed).
    loggers = {f"{name}/get_loggers", f"{name}/set_logger_level"}
    want = (
        {p["topic"] for p in spec.get("publish", [])},
        {s["topic"] for s in spec.get("subscribe", [])},
        {s["service"] for s in spec.get("serve", [])} | loggers,
    )

    def listed() -> bool:
        if proc.poll() is not None:
            text = (master.home / f"standin-{spec['name']}.out").read_text(errors="replace")
            raise RuntimeError(f"stand-in {name} exited with {proc.returncode}:\n{text[-2000:]}")
        have = registered(master.uri, name)
        return all(w <= h for w, h in zip(want, have, strict=True))

    try:
        wait_until(listed, NODE_START_TIMEOUT, f"stand-in {name} registering")
    except BaseException:
        stop(proc)
        raise
    return node
