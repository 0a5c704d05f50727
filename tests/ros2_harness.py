"""Start ROS 2 announcers (tests/ros2_announcer.py) on a private loopback DDS domain.

Every participant a test starts, ours and rosreconf's, gets the same CYCLONEDDS_URI: the
loopback interface only, no multicast, unicast discovery to 127.0.0.1, and a short lease so a
SIGKILLed announcer is noticed in seconds (rmw_cyclonedds' default is 10 s). The domain id is
one no real system uses (42 and up), and per test one whose discovery port is free, so
tests and other runs on the machine never see each other.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rosreconf.model import Component, InterfaceKind

ANNOUNCER = Path(__file__).with_name("ros2_announcer.py")
LEASE = 2.0
"""Seconds a participant's lease lasts in the tests (rmw_cyclonedds' default: 10 s)."""
START_TIMEOUT = 20.0
FIRST_DOMAIN = int(os.environ.get("ROSRECONF_TEST_DOMAIN_BASE", "42"))
"""The first domain id tests try (env ROSRECONF_TEST_DOMAIN_BASE: parallel runs start apart)."""


def loopback_config(lease: float = LEASE) -> str:
    """Return the CYCLONEDDS_URI XML: loopback only, no multicast, ``lease`` s leases."""
    return (
        '<CycloneDDS><Domain Id="any"><General>'
        '<Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>'
        "<AllowMulticast>false</AllowMulticast></General>"
        "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
        "<MaxAutoParticipantIndex>40</MaxAutoParticipantIndex>"
        '<Peers><Peer address="127.0.0.1"/></Peers>'
        f"<LeaseDuration>{lease:g}s</LeaseDuration></Discovery>"
        "</Domain></CycloneDDS>"
    )


def dds_env(lease: float = LEASE) -> dict[str, str]:
    """Return this process's environment with the loopback DDS configuration."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["CYCLONEDDS_URI"] = loopback_config(lease)
    return env


def xdist_worker() -> tuple[int, int]:
    """Return (this pytest-xdist worker's index, the number of workers); (0, 1) without xdist."""
    name = os.environ.get("PYTEST_XDIST_WORKER", "")
    count = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1)
    return (int(name[2:]) if name.startswith("gw") else 0), max(count, 1)


def _last_domain() -> int:
    """Return the highest domain id whose RTPS ports all lie below the kernel's ephemeral ports.

    Domain d's ports are 7400 + 250 d up to 7400 + 250 (d + 1) - 1, so with Linux's default
    range (32768-60999) the highest is 100. Above it a port may already be taken as an
    ephemeral one, by any socket's send side or TCP client on the host (seen: ``watch`` on
    domain 189 could not bind 54651). The range is only read here, never changed.
    """
    try:
        low = int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        low = 32768
    return max(FIRST_DOMAIN + 20, min(231, (low - 7400) // 250 - 1))


LAST_DOMAIN = _last_domain()
_next = [FIRST_DOMAIN + (os.getpid() * 7) % (LAST_DOMAIN + 1 - FIRST_DOMAIN)]


def _domains() -> list[int]:
    """Return the domain ids this process may take: with xdist, every n-th from its index.

    Workers never take one domain at once: a domain found free and then taken by another
    worker's first participant would mix two tests' graphs.
    """
    index, count = xdist_worker()
    return [d for d in range(FIRST_DOMAIN, LAST_DOMAIN + 1) if (d - FIRST_DOMAIN) % count == index]


LOCKS = Path(tempfile.gettempdir()) / "rosreconf-test-domains"
"""Where each test process locks the domain ids it holds (``flock``): a second test run on
this host (another clone's ``make test``, whose workers have the same indices) skips them."""
_locked: dict[int, int] = {}
"""Domain id -> the descriptor holding its lock, for every domain this process holds."""


COOLDOWN = 15.0
"""Seconds a domain given back stays unavailable to every run on the host: the test's
processes die asynchronously after it ends (stand-ins by their watchdogs after ``watch``'s
SIGKILL), and a dying /NCA1 of one run must not be seen by the next test on that domain."""


def _lock(domain: int) -> bool:
    """Lock ``domain`` for this process; False when another process holds it, or gave it back
    less than ``COOLDOWN`` s ago (the time of the release is written in the lock file)."""
    LOCKS.mkdir(exist_ok=True)
    fd = os.open(LOCKS / f"{domain}.lock", os.O_RDWR | os.O_CREAT, 0o666)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        released = float(os.pread(fd, 64, 0).decode() or 0.0)
    except (OSError, ValueError):
        os.close(fd)
        return False
    if 0.0 <= time.time() - released < COOLDOWN:
        os.close(fd)
        return False
    _locked[domain] = fd
    return True


def release(domain: int) -> None:
    """Give ``domain`` back when nothing of the test runs on it any more (idempotent)."""
    fd = _locked.pop(domain, None)
    if fd is not None:
        stamp = f"{time.time():.3f}".encode()
        os.ftruncate(fd, 0)
        os.pwrite(fd, stamp, 0)
        os.close(fd)  # closing the descriptor releases its lock


def _ports_free(domain: int) -> bool:
    """True when no participant of ``domain`` listens here: domain d's participant i binds
    UDP 7400 + 250 d + 10 + 2 i (the RTPS port mapping), i up to the tests' maximum of 40."""
    for index in range(41):
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            try:
                s.bind(("127.0.0.1", 7400 + 250 * domain + 10 + 2 * index))
            except OSError:
                return False
    return True


def free_domain() -> int:
    """Return a DDS domain id that no test process here holds, nobody gave back in the last
    ``COOLDOWN`` s, and no participant listens on, locked (``LOCKS``) until ``release`` or this
    process's end.

    Each test gives back what it took (``held_domain``, the ``ros2_domain`` fixture): a lock
    that lapsed while its nodes still ran would let another run on this host take their
    domain. A bound participant port means someone still uses the domain here. When every
    domain is cooling down, wait for one rather than fail.
    """
    mine = _domains()
    deadline = time.monotonic() + COOLDOWN + 5.0
    while True:
        for _ in range(len(mine)):
            domain = min((d for d in mine if d >= _next[0]), default=mine[0])
            _next[0] = domain + 1
            if domain in _locked or not _lock(domain):
                continue
            if not _ports_free(domain):
                os.close(_locked.pop(domain))  # not ours to stamp: someone else's nodes run
                continue
            return domain
        if time.monotonic() > deadline:
            break
        time.sleep(0.5)
    raise RuntimeError(
        f"no free DDS domain id of {mine} (this process holds {sorted(_locked)}): "
        "a test that never gave its domain back (release), or another run holds them"
    )


@contextlib.contextmanager
def held_domain() -> Iterator[int]:
    """Hold a free domain for the ``with`` block (``free_domain``), then give it back."""
    domain = free_domain()
    try:
        yield domain
    finally:
        release(domain)


def ros2_type(ros1_type: str, kind: str) -> str:
    """Return the ROS 2 type of a library type (``pkg/Name`` -> ``pkg/msg/Name``)."""
    parts = ros1_type.split("/")
    return ros1_type if len(parts) == 3 else f"{parts[0]}/{kind}/{parts[-1]}"


def _join(namespace: str, name: str) -> str:
    parts = [p for p in (*namespace.split("/"), *name.split("/")) if p]
    return "/" + "/".join(parts)


def live_name(component: Component, label: str) -> str:
    """Return the global name ``component``'s executable uses for ``label`` (its remapping)."""
    launch = component.launch
    ns = (launch.namespace if launch else None) or "/"
    target = launch.remappings.get(label, label) if launch else label
    return _join("/", target) if target.startswith("/") else _join(ns, target)


def node_spec(
    component: Component,
    qos: dict[str, dict[str, Any]] | None = None,
    providers: Sequence[Component] = (),
) -> dict[str, Any]:
    """Return the announcer node of ``component``: what its ROS 2 node would announce.

    Written here from the library, not with rosreconf's own name mapping, so that a bug
    there shows up as a test failure. ``qos`` maps a live topic name to the rmw profile of
    this node's endpoint on it. ``providers``: the other nodes of its configuration; each
    requirement option one of them provides is used under that provider's name, as a
    launch file's remapping wires it (else under its own name, unwired).
    """
    qos = qos or {}
    launch = component.launch
    ns = (launch.namespace if launch else None) or "/"

    def live(label: str) -> str:
        return live_name(component, label)

    def wired(option: Any) -> str:
        for p in providers:
            if option in p.provides:
                return live_name(p, option.label)
        return live(option.label)

    node: dict[str, Any] = {
        "namespace": ns,
        "name": (launch.node if launch else None) or component.name,
        "publishers": [],
        "subscriptions": [],
        "servers": [],
        "clients": [],
    }
    for iface in sorted(component.provides):
        name = live(iface.label)
        if iface.kind is InterfaceKind.SERVICE:
            node["servers"].append({"name": name, "type": ros2_type(iface.type, "srv")})
        else:
            typ = ros2_type(iface.type, "msg")
            node["publishers"].append({"name": name, "type": typ, "qos": qos.get(name, {})})
    for req in component.requires:
        for option in req.options:
            name = wired(option)
            if option.kind is InterfaceKind.SERVICE:
                node["clients"].append({"name": name, "type": ros2_type(option.type, "srv")})
            else:
                typ = ros2_type(option.type, "msg")
                node["subscriptions"].append({"name": name, "type": typ, "qos": qos.get(name, {})})
    return node


@dataclass
class Announcer:
    """One announcer process (one ROS 2 context)."""

    process: subprocess.Popen[bytes]
    spec: dict[str, Any]

    def kill(self) -> None:
        """SIGKILL it, like a crash: its participant cannot say goodbye."""
        self.process.send_signal(signal.SIGKILL)
        self.process.wait(5)


def start(
    tmp: Path,
    domain: int,
    nodes: list[dict[str, Any]],
    *,
    gid_size: int = 16,
    env: dict[str, str] | None = None,
    **extra: Any,
) -> Announcer:
    """Start one announcer process for ``nodes`` and wait until it has announced them.

    ``env``: its environment, the loopback-only one (``dds_env``) unless given.
    """
    spec = {"domain": domain, "gid_size": gid_size, "nodes": nodes, **extra}
    path = tmp / f"announcer-{len(list(tmp.glob('announcer-*.json')))}.json"
    path.write_text(json.dumps(spec), encoding="utf-8")
    argv = [sys.executable, str(ANNOUNCER), str(path)]
    proc = start_ready(argv, tmp / f"{path.stem}.err", env or dds_env(), "announcer")
    return Announcer(proc, spec)


def fake_python(path: Path, real: Path, fault: str, script: str | None = None) -> Path:
    """Write a provoked-fault "ROS 2 Python" at ``path``: a shell script that runs ``fault``
    (shell) when it is run for ``script`` (a file name; every run when None), and otherwise
    is the ``real`` interpreter. A real Python cannot be made to hang or be slow on cue."""
    faulty = fault if script is None else f'case "$1" in *{script}) {fault};; esac'
    path.write_text(
        f'#!/bin/sh\n# provoked fault (rosreconf tests)\n{faulty}\nexec "{real}" "$@"\n'
    )
    path.chmod(0o755)
    return path


def start_ready(
    argv: list[str], err: Path, env: dict[str, str], what: str, timeout: float = START_TIMEOUT
) -> subprocess.Popen[bytes]:
    """Start ``argv`` in a session of its own; return once it prints ``ready``, else raise.

    Its stderr goes to ``err``, whose tail the error shows.
    """
    proc = subprocess.Popen(
        argv, stdout=subprocess.PIPE, stderr=err.open("wb"), env=env, start_new_session=True
    )
    assert proc.stdout is not None
    ready, _, _ = select.select([proc.stdout], [], [], timeout)
    line = proc.stdout.readline() if ready else b""
    if line.strip() != b"ready":
        proc.kill()
        proc.wait(5)
        raise RuntimeError(
            f"{what} did not start: {line!r} {err.read_text(errors='replace')[-2000:]}"
        )
    return proc


def stop(announcers: Iterable[Announcer]) -> None:
    """Stop announcers (SIGTERM, then SIGKILL after 5 s) and reap them."""
    live = [a for a in announcers if a.process.poll() is None]
    for a in live:
        a.process.send_signal(signal.SIGTERM)
    deadline = time.monotonic() + 5
    for a in live:
        try:
            a.process.wait(max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            a.process.kill()
            a.process.wait(5)
    for a in announcers:
        if a.process.stdout is not None:
            a.process.stdout.close()


def thread_stacks(pid: int | None, out: Path) -> str:
    """Write every thread's stack of the live process ``pid`` to ``out`` (gdb); return a digest.

    A diagnosis, never a check: a test calls it when a node it did not touch fails, while the
    process still lives, so that the failure's message says where its threads were (fresh
    clones fc82 and fc114 each saw a Fast DDS 2.14 stand-in leave the graph beside a SIGKILLed
    peer and end only on SIGKILL; neither left a stack). Without gdb, or with the process gone,
    the digest says so and nothing fails for it.
    """
    if pid is None or not Path(f"/proc/{pid}").exists():
        return f"pid {pid}: no such process, no stacks"
    gdb = shutil.which("gdb")
    if gdb is None:
        return f"pid {pid}: gdb is not installed, no stacks"
    try:
        run = subprocess.run([gdb, "-p", str(pid), "-batch", "-ex", "thread apply all bt"],
                             capture_output=True, text=True, timeout=60)  # fmt: skip
    except subprocess.TimeoutExpired:
        return f"pid {pid}: gdb did not answer in 60 s"
    out.write_text(run.stdout + run.stderr)
    threads: list[list[str]] = []
    for line in run.stdout.splitlines():
        if line.startswith("Thread "):
            threads.append([])
        elif threads and line.startswith("#") and " in " in line:
            function = line.split(" in ", 1)[1].split(" (", 1)[0]
            threads[-1].append(function.split("(", 1)[0][-60:])
    if not threads:  # ptrace refused (a container without CAP_SYS_PTRACE), or the pid gone
        return f"pid {pid}: gdb read no thread: {(run.stderr or run.stdout).strip()[-300:]}"
    digest = "\n".join(" <- ".join(frames[:6]) for frames in threads)
    return f"pid {pid}: every thread's stack in {out}; each thread's innermost frames:\n{digest}"
