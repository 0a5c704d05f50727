"""Tests for rosreconf.procs.procstat: a real process whose name holds ') (' and spaces."""

from __future__ import annotations

import os
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from rosreconf.procs import descendants, read_stat
from rosreconf.ros.ros2.hostprocs import read_proc_id
from rosreconf.ros.ros2.pidwatch import proc_state

NAME = "a) (b c)"
"""A script name the kernel keeps as the command name, parentheses and spaces included."""


@pytest.fixture
def oddly_named(tmp_path: Path) -> Iterator[subprocess.Popen[bytes]]:
    """Run a shell script named ``NAME``, and wait until it sleeps reading its stdin.

    Its comm is ``NAME`` once it runs; its state stays ``S`` until stdin closes.
    """
    script = tmp_path / NAME
    script.write_text("#!/bin/sh\nread line\n")
    script.chmod(0o755)
    proc = subprocess.Popen([str(script)], stdin=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 10
        while (stat := read_stat(proc.pid)) is None or (stat.comm, stat.state) != (NAME, "S"):
            assert time.monotonic() < deadline, f"the script never ran: {stat}"
            time.sleep(0.01)
        yield proc
    finally:
        proc.kill()
        proc.wait()


def test_the_command_name_may_hold_parentheses_and_spaces(
    oddly_named: subprocess.Popen[bytes],
) -> None:
    stat = read_stat(oddly_named.pid)
    assert stat is not None
    assert (stat.pid, stat.comm, stat.ppid) == (oddly_named.pid, NAME, os.getpid())
    assert stat.state == proc_state(oddly_named.pid) == "S"
    proc_id = read_proc_id(oddly_named.pid)
    assert proc_id is not None and proc_id.start_ticks == stat.start_ticks
    own = read_stat(os.getpid())
    assert own is not None and own.start_ticks <= stat.start_ticks
    assert oddly_named.pid in descendants(os.getpid())


def test_a_process_that_has_ended_reads_as_gone(oddly_named: subprocess.Popen[bytes]) -> None:
    oddly_named.kill()
    oddly_named.wait()
    assert read_stat(oddly_named.pid) is None
    assert proc_state(oddly_named.pid) is None
    assert read_proc_id(oddly_named.pid) is None
