"""rosreconf's stand-ins come up on a host where Fast DDS left a broken shared-memory port.

Fast DDS's shared-memory transport gives each participant on the host the next port file
``/dev/shm/fastrtps_port7000``, ``7001``, ... (Fast DDS 3: ``fastdds_port...``), whatever its
domain. A participant killed while it creates one leaves it 0 bytes long, and the next
participant that picks that port waits in ``rcl_node_init`` for ever: a fresh clone's
``make test`` lost seven real-node tests to one such file, ``fastrtps_port7013``, left by an
earlier test's kill. rosreconf's own participants use UDP only (``runtime.OWN_TRANSPORTS``),
so they neither leave such a file nor wait on one.

The broken files are real files of the kind Fast DDS leaves (0 bytes, no lock file), made
here since the kill that leaves one cannot be timed. Only files that did not exist are made,
and exactly those are removed. ``watch`` runs with Fast DDS's default transports (this
suite's UDP-only setting, ``conftest.py``, is taken away), as on a robot.
"""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Iterator
from pathlib import Path

import pytest
from test_watch_ros2 import NOMINAL, Watch, probe

SHM = Path("/dev/shm")
PORTS = range(7000, 7040)
"""The host-wide ports the first 40 participants here take (13 stand-ins, a probe, others)."""


@contextlib.contextmanager
def broken_ports() -> Iterator[list[Path]]:
    """Make a 0-byte port file for each of ``PORTS`` that has none; remove exactly those."""
    made: list[Path] = []
    try:
        for port in PORTS:
            for prefix in ("fastrtps", "fastdds"):  # Fast DDS 2 (Jazzy), 3 (Kilted)
                path = SHM / f"{prefix}_port{port}"
                try:
                    os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o644))
                except FileExistsError:
                    continue
                made.append(path)
        yield made
    finally:
        for path in made:
            with contextlib.suppress(FileNotFoundError):
                path.unlink()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # Fast DDS 2.14 and 3.2
def test_stand_ins_come_up_beside_a_broken_shared_memory_port(
    ros2_domain: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, distro: str
) -> None:
    from test_watch_wiring import _python

    monkeypatch.delenv("FASTDDS_BUILTIN_TRANSPORTS")
    with broken_ports() as made:
        assert made, "no port file could be made in /dev/shm"
        python = _python(distro)
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", python=python)
        try:
            done = watch.wait("conformant")
            # What watch says runs: the nominal configuration, or the repair of a stand-in that
            # died on its own (seen once in a fresh clone: NVP1 exited -11 at its start, and
            # watch replanned onto the second camera group). A stand-in stuck on a broken port
            # never comes up and is never failed, so watch would not get here.
            running = {f"/{c}" for c in done["configuration"].values() if c}
            assert len(running) == len(NOMINAL)
            # rclpy's own view (a UDP-only probe: it must not wait on the files either)
            env = {**watch.env, "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4"}
            seen = probe(env, ros2_domain, wait_for=sorted(running), python=python)
            assert running <= set(seen["nodes"]), seen["nodes"]
        finally:
            assert watch.stop() == 128 + signal.SIGTERM  # its documented exit on SIGTERM
        assert all(p.stat().st_size == 0 for p in made)  # nobody waited on them, or wrote


def test_a_team_executable_stuck_on_a_broken_port_is_named_with_the_file(
    ros2_domain: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The team's executables keep Fast DDS's default transports: they get stuck, and watch
    names the file each waits on and what to do, instead of "launched but not running".

    It runs in a /dev/shm of its own with a broken file for every port the team can take: on
    the host's /dev/shm a port file another participant left (live, or dead and reusable) was
    skipped by ``broken_ports``, so one of the 13 came up (CI, stop 52: NSM1 was not missing).
    """
    from test_watch_wiring import _ament_prefix, _python

    monkeypatch.delenv("FASTDDS_BUILTIN_TRANSPORTS")
    prefix = _ament_prefix(tmp_path, _python("jazzy"))
    planted = [f"/dev/shm/{kind}_port{port}" for port in PORTS for kind in ("fastrtps", "fastdds")]
    wrap = _private_shm("; ".join(f": > {path}" for path in planted))
    # --settle 5: the stuck processes never come up, so the 30 s default only waited
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--settle", "5",
                  stand_ins=False, env={"AMENT_PREFIX_PATH": str(prefix)}, wrap=wrap)  # fmt: skip
    try:
        said = watch.wait("missing")
        while "shared-memory" not in said["message"]:  # said again once the file is seen
            said = watch.wait("missing", after=watch.events().index(said) + 1)
    finally:
        watch.stop(signal.SIGKILL)
    assert sorted(said["components"]) == sorted(NOMINAL)
    named = [path for path in planted if path in said["message"]]
    assert named and all(p.startswith("/dev/shm/fastrtps_port") for p in named), said
    assert f"rm {named[0]}" in said["message"]


PRIVATE_SHM = """
mount -t tmpfs rosreconf-test-shm /dev/shm || exit 97
{debris}
exec "$@"
"""
"""Run watch with a /dev/shm of its own (a mount namespace: ``unshare -m``), debris planted.

Private, so the debris touches no other process of the host, and the test plants what a
crashed participant leaves on purpose: nothing else is in that /dev/shm."""

HOLD_EL_FILES = """
python3 -c '
import fcntl, os, time
fds = [os.open("/dev/shm/%s_port7000_el" % p, os.O_RDWR | os.O_CREAT, 0o666)
       for p in ("fastrtps", "fastdds")]
for fd in fds:
    fcntl.flock(fd, fcntl.LOCK_EX)
time.sleep(600)' &
sleep 0.5
"""
"""A process holding port 7000's lock files, as one that hung in Fast DDS's SHM setup does:
every Fast DDS 2.14 participant with the shared-memory transport then prints ``Failed
init_port fastrtps_port7000: open_and_lock_file failed`` on its stdout."""

ZERO_PORT_FILES = ": > /dev/shm/fastrtps_port7000; : > /dev/shm/fastdds_port7000"
"""A 0-byte port file with no lock file, as a participant killed while it made one leaves."""


def _private_shm(debris: str) -> list[str]:
    """Return the command that runs the rest of its argv in a private /dev/shm with ``debris``."""
    return ["unshare", "-m", "--propagation", "private", "sh", "-c",
            PRIVATE_SHM.format(debris=debris), "private-shm"]  # fmt: skip


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
@pytest.mark.parametrize("debris", ["held-lock", "zero-port"])
def test_managed_stand_ins_conform_beside_shared_memory_debris_in_a_private_dev_shm(
    ros2_domain: int, tmp_path: Path, distro: str, debris: str
) -> None:
    """What any local user can leave in /dev/shm stops no stand-in and no transition.

    ``held-lock`` runs with Fast DDS's default transports (``FASTDDS_BUILTIN_TRANSPORTS``
    set by the user to ``DEFAULT``, which rosreconf keeps): the lifecycle agent's participant
    then meets the held lock and Fast DDS prints its error on the agent's stdout, which was
    once read as the agent's answer (every ``configure`` failed, the watch never conformed).
    ``zero-port`` runs with rosreconf's own setting: its participants use UDP only, with the
    short-lease profile too, and never wait on the 0-byte file.
    """
    from test_watch_ros2 import _managed_library
    from test_watch_wiring import _python

    held = debris == "held-lock"
    env = {"FASTDDS_BUILTIN_TRANSPORTS": "DEFAULT"} if held else {}
    wrap = _private_shm(HOLD_EL_FILES if held else ZERO_PORT_FILES)
    library = _managed_library(tmp_path)
    python = _python(distro)
    schema = Path(__file__).resolve().parent.parent / "schemas" / "object_repositioning.yaml"
    watch = Watch(tmp_path, ros2_domain, "-l", str(library), "-s", str(schema),
                  python=python, env=env, wrap=wrap)  # fmt: skip
    try:
        done = watch.wait("conformant")
        failed = [e["message"] for e in watch.events() if e.get("transition") and not e["ok"]]
        assert not failed, failed  # no answer of the agent was a line Fast DDS printed
        assert len(watch.configured()) == len(NOMINAL)
        running = {f"/{c}" for c in done["configuration"].values() if c}
        assert len(running) == len(NOMINAL)
        if held and distro == "jazzy":  # the fault happened: Fast DDS complained, to the log
            logs = "".join(p.read_text(errors="replace") for p in tmp_path.rglob("*agent*.log"))
            assert "RTPS_TRANSPORT_SHM" in logs, sorted(map(str, tmp_path.rglob("*.log")))
    finally:
        code = watch.stop()
        with contextlib.suppress(ProcessLookupError):
            os.killpg(watch.process.pid, signal.SIGKILL)  # the lock holder, in watch's group
    assert code == 128 + signal.SIGTERM, watch.err.read_text()[-2000:]
