"""Signals to ``simulate``/``whatif --workers 2``: the pool's workers never outlive rosreconf.

Real processes: rosreconf runs as a subprocess in its own session, on a generated library big
enough that its worker pool is busy for minutes (``whatif -k 3``) or seconds (``simulate``).
Once both workers exist, the test signals rosreconf (or its whole group, as a terminal's
Ctrl-C does) and checks that every process of the group and every descendant seen is gone,
that the exit code is the documented one and that stderr holds one line, no traceback.
The bounds only prove "no hang" (``LOADED_MACHINE_SLACK``); the old code failed them by
orphaning both workers (ppid 1, forever) and by printing two worker tracebacks.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest
from conftest import LOADED_MACHINE_SLACK, live_members

ROSRECONF = [sys.executable, "-m", "rosreconf"]
START_SECONDS = 180.0
"""How long the workers may take to appear (the machine may be loaded)."""


def generate(where: Path, *args: str) -> Path:
    """Write a generated library and schema under ``where`` (rosreconf generate)."""
    done = subprocess.run(
        [*ROSRECONF, "generate", *args, "-o", str(where)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return where


@pytest.fixture(scope="module")
def busy_whatif(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A library on which ``whatif -k 3 --workers 2`` keeps its pool busy for minutes."""
    return generate(tmp_path_factory.mktemp("whatif"), "--roles", "40", "--candidates", "6",
                    "--coupling", "0.5")  # fmt: skip


@pytest.fixture(scope="module")
def busy_simulate(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A library whose ``simulate --workers 2`` hands its pool work for seconds."""
    return generate(tmp_path_factory.mktemp("simulate"), "--roles", "9", "--candidates", "4",
                    "--dynamics")  # fmt: skip


class Run:
    """A rosreconf process in its own session, and every descendant it was seen with."""

    def __init__(self, where: Path, *args: str) -> None:
        self.process = subprocess.Popen(
            [*ROSRECONF, *args], cwd=where, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            start_new_session=True,
        )  # fmt: skip
        self.seen: list[psutil.Process] = []

    def wait_for_workers(self, n: int = 2) -> None:
        """Wait until rosreconf has ``n`` worker processes; remember every descendant."""
        me = psutil.Process(self.process.pid)
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline and self.process.poll() is None:
            kids = me.children(recursive=True)
            if len(kids) >= n:
                self.seen = kids
                return
            time.sleep(0.05)
        pytest.fail(f"no {n} workers after {START_SECONDS} s (exit {self.process.poll()})")

    def survivors(self, seconds: float = LOADED_MACHINE_SLACK) -> list[int]:
        """Return the group's members and seen descendants still alive after ``seconds``."""
        deadline = time.monotonic() + seconds
        while True:
            alive = set(live_members(self.process.pid))
            for p in self.seen:
                try:
                    if p.is_running() and p.status() != psutil.STATUS_ZOMBIE:
                        alive.add(p.pid)
                except psutil.NoSuchProcess:
                    pass
            if not alive or time.monotonic() > deadline:
                return sorted(alive)
            time.sleep(0.05)

    def stderr(self) -> str:
        """Return what rosreconf wrote to stderr (after it ended)."""
        assert self.process.stderr is not None
        return self.process.stderr.read().decode("utf-8", errors="replace")

    def cleanup(self) -> None:
        """Kill whatever is left (the old code's orphans), so no test leaves a process."""
        for p in self.seen:
            with contextlib.suppress(psutil.NoSuchProcess):
                p.kill()
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()


@pytest.fixture
def run() -> Iterator[list[Run]]:
    """Collect the runs a test starts; kill what is left of them afterwards."""
    runs: list[Run] = []
    yield runs
    for r in runs:
        r.cleanup()


def start(runs: list[Run], where: Path, *args: str) -> Run:
    """Start rosreconf with ``args`` in ``where`` and wait for its two pool workers."""
    r = Run(where, *args, "--workers", "2")
    runs.append(r)
    r.wait_for_workers()
    return r


COMMANDS = {
    "whatif": ("busy_whatif", ("whatif", "-k", "3")),
    "simulate": ("busy_simulate", ("simulate",)),
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize(
    ("sig", "code", "message"),
    [
        (signal.SIGTERM, 143, "rosreconf: terminated\n"),
        (signal.SIGKILL, -signal.SIGKILL, ""),
        (signal.SIGINT, 130, "rosreconf: interrupted\n"),
    ],
    ids=["sigterm", "sigkill", "sigint"],
)
def test_signal_to_a_sweep_with_workers_leaves_no_worker_running(
    command: str,
    sig: signal.Signals,
    code: int,
    message: str,
    run: list[Run],
    request: pytest.FixtureRequest,
) -> None:
    fixture, args = COMMANDS[command]
    r = start(run, request.getfixturevalue(fixture), *args)
    os.kill(r.process.pid, sig)
    assert r.process.wait(LOADED_MACHINE_SLACK) == code  # promptly, not when the sweep ends
    assert r.survivors() == []
    assert r.stderr() == message


def test_ctrl_c_to_the_terminal_group_stops_whatif_with_one_message_and_no_worker_traceback(
    busy_whatif: Path, run: list[Run]
) -> None:
    r = start(run, busy_whatif, "whatif", "-k", "3")
    os.killpg(r.process.pid, signal.SIGINT)  # what a terminal's Ctrl-C does
    assert r.process.wait(LOADED_MACHINE_SLACK) == 130
    assert r.survivors() == []
    assert r.stderr() == "rosreconf: interrupted\n"
