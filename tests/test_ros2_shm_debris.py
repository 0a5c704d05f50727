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
    names the file each waits on and what to do, instead of "launched but not running"."""
    from test_watch_wiring import _ament_prefix, _python

    monkeypatch.delenv("FASTDDS_BUILTIN_TRANSPORTS")
    prefix = _ament_prefix(tmp_path, _python("jazzy"))
    with broken_ports() as made:
        # --settle 5: the stuck processes never come up, so the 30 s default only waited
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--settle", "5",
                      stand_ins=False, env={"AMENT_PREFIX_PATH": str(prefix)})  # fmt: skip
        try:
            said = watch.wait("missing")
            while "shared-memory" not in said["message"]:  # said again once the file is seen
                said = watch.wait("missing", after=watch.events().index(said) + 1)
        finally:
            watch.stop(signal.SIGKILL)
        assert sorted(said["components"]) == sorted(NOMINAL)
        named = [str(p) for p in made if str(p) in said["message"]]
        assert named and all(p.startswith(str(SHM / "fastrtps_port")) for p in named), said
        assert f"rm {named[0]}" in said["message"]
