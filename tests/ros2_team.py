"""The team's own ROS 2 nodes, forked from one warm rclpy process: what a launch file starts.

Several tests start "the team's own nodes" (a whole configuration of 13, started as its launch
file would, wired by ``-r`` rules) to show what ``watch`` and ``inspect`` make of nodes they did
not start. Each such node started on its own pays the interpreter and rclpy's imports again
(0.6-0.8 CPU s on this machine, about 190 of them in the suite). Here one process of the
distro's venv, rosreconf's own stand-in zygote script (``standin_zygote.py``, run by the test,
not by rosreconf), imports them once and forks one child per node. Each child is still what a
launch file's process is: its own pid, session and DDS participant, its command line the one
it would have had on its own (``/proc/<pid>/cmdline``), the same executable, started by a
process rosreconf knows nothing of. Without ``ROSRECONF_STANDIN_ALIVE_FD`` in its environment
each child dies with the zygote (a parent-death signal), so closing the team stops them all.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import threading
import time
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
ZYGOTE = ROOT / "rosreconf" / "ros" / "ros2" / "scripts" / "standin_zygote.py"
STANDIN = ROOT / "rosreconf" / "ros" / "ros2" / "scripts" / "standin_node.py"
TITLE_ROOM = 32768
"""Bytes of command line the zygote is given, for its children's (as rosreconf gives it)."""


def _running(pid: int) -> bool:
    """Tell whether ``pid`` is a process that has not ended (not gone, not a zombie)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] not in ("Z", "X")


class Member:
    """One forked node, seen as ``subprocess.Popen`` shows a process (pid, poll, wait, kill)."""

    stdout = None
    """Its output is in ``log`` (as ``Popen`` says of a process whose stdout is not a pipe)."""

    def __init__(self, team: Team, pid: int, log: Path, key: str, argv: Sequence[str]) -> None:
        self.team, self.pid, self.log = team, pid, log
        self.key, self.argv = key, list(argv)
        self.crashed: list[str] = []
        """What each earlier process of this member left in its log when it crashed."""

    def start_again(self) -> None:
        """Fork this node once more (same argv, a new log): it is then that new process."""
        again = self.team.start(self.key, self.argv)
        self.pid, self.log = again.pid, again.log

    @property
    def returncode(self) -> int | None:
        """The exit status the zygote reported (negative: killed by that signal), or None."""
        return self.team.exit_of(self.pid)

    def poll(self) -> int | None:
        """Return the exit status, or None while it runs.

        The zygote reaps its children: a process already gone (or a zombie) whose end the
        zygote has not said yet is waited for briefly, as ``Popen.poll`` would reap it.
        """
        if self.returncode is None and not _running(self.pid):
            with contextlib.suppress(subprocess.TimeoutExpired):
                return self.wait(5.0)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        """Wait for its end; raise ``subprocess.TimeoutExpired`` after ``timeout`` seconds."""
        return self.team.wait_for(self.pid, timeout)

    def send_signal(self, sig: int) -> None:
        """Signal its process (only while the zygote has not reported its end)."""
        if self.poll() is None:
            with contextlib.suppress(ProcessLookupError):  # it ended just now
                os.kill(self.pid, sig)

    def kill(self) -> None:
        """SIGKILL its process."""
        self.send_signal(signal.SIGKILL)

    def tail(self, size: int = 3000) -> str:
        """Return the end of its log (a crash's stacks, a traceback), for a failure's message."""
        if not self.log.exists():
            return "(no log)"
        return self.log.read_bytes()[-size:].decode(errors="replace")

    def ready(self) -> bool:
        """Tell whether the node has said ``ready`` (in its log)."""
        return self.log.exists() and b'"ready"' in self.log.read_bytes()


class Team:
    """One zygote under ``python`` with ``env``, forking the team's nodes on request."""

    def __init__(self, python: Path, env: Mapping[str, str], tmp: Path) -> None:
        self.tmp = tmp
        self.tmp.mkdir(parents=True, exist_ok=True)
        self._exits: dict[int, int] = {}
        self._answers: dict[int, dict[str, Any]] = {}
        self._changed = threading.Condition()
        self._next = 0
        self._zygote = subprocess.Popen(
            [str(python), str(ZYGOTE), " " * TITLE_ROOM],
            env={k: v for k, v in env.items() if k != "ROSRECONF_STANDIN_ALIVE_FD"},
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=(tmp / "zygote.err").open("wb"),
            start_new_session=True,
        )
        assert self._zygote.stdout is not None
        first = self._zygote.stdout.readline()
        if b'"ready"' not in first:
            self._zygote.kill()
            self._zygote.wait()
            err = (tmp / "zygote.err").read_text(errors="replace")[-2000:]
            raise RuntimeError(f"the team's zygote did not start: {first!r} {err}")
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self._zygote.stdout is not None
        for line in self._zygote.stdout:
            said = json.loads(line)
            with self._changed:
                if "exited" in said:
                    self._exits[int(said["exited"])] = int(said["code"])
                else:
                    self._answers[int(said["id"])] = said
                self._changed.notify_all()

    def start(self, key: str, argv: Sequence[str]) -> Member:
        """Fork one node running ``argv`` (``[python, script, ...]``); its output goes to a log."""
        self._next += 1
        log = self.tmp / f"{key}-{self._next}.log"  # a node started again gets a new log
        request = {"id": self._next, "argv": [str(a) for a in argv], "log": str(log)}
        assert self._zygote.stdin is not None
        self._zygote.stdin.write((json.dumps(request) + "\n").encode())
        self._zygote.stdin.flush()
        with self._changed:
            if not self._changed.wait_for(lambda: self._next in self._answers, 30.0):
                raise RuntimeError(f"the team's zygote did not fork {key} within 30 s")
            answer = self._answers.pop(self._next)
        if "pid" not in answer:
            raise RuntimeError(f"the team's zygote could not fork {key}: {answer}")
        return Member(self, int(answer["pid"]), log, key, argv)

    def exit_of(self, pid: int) -> int | None:
        """Return the exit status the zygote reported for ``pid``, or None."""
        with self._changed:
            return self._exits.get(pid)

    def wait_for(self, pid: int, timeout: float | None) -> int:
        """Wait until the zygote reports ``pid``'s end; return its status."""
        with self._changed:
            if not self._changed.wait_for(lambda: pid in self._exits, timeout):
                raise subprocess.TimeoutExpired(str(pid), timeout or 0.0)
            return self._exits[pid]

    def close(self) -> None:
        """Stop every node left (the zygote kills them when its stdin closes) and the zygote."""
        if self._zygote.stdin is not None and not self._zygote.stdin.closed:
            self._zygote.stdin.close()
        try:
            self._zygote.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(self._zygote.pid, signal.SIGKILL)
            self._zygote.wait()
        self._reader.join(5)


def wait_ready(members: Mapping[str, Member], timeout: float = 60.0) -> None:
    """Return once every member has said ``ready``; fail naming those that did not.

    A member killed by a signal before ready (a crash in rclpy or DDS, as Kilted's SIGSEGV;
    the team's robot, not what a test is about) is started once more, with a warning that
    carries its log (faulthandler's stacks). Any other exit before ready fails, with its log.
    """
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        late = [k for k, m in members.items() if not m.ready()]
        gone = [k for k in late if members[k].poll() is not None]
        crashed = [k for k in gone if (members[k].returncode or 0) < 0 and not members[k].crashed]
        for k in crashed:
            m = members[k]
            m.crashed.append(m.tail())
            warnings.warn(f"team node {k} crashed before ready (exit {m.returncode}), started "
                          f"once more; its log ends:\n{m.crashed[-1]}", stacklevel=2)  # fmt: skip
            m.start_again()
        gone = [k for k in gone if k not in crashed]
        if gone:
            said = "; ".join(
                f"{k} (exit {members[k].returncode}): {members[k].tail()}" for k in gone
            )
            raise AssertionError(f"team nodes exited before ready: {said}")
        if not late:
            return
        time.sleep(0.05)
    raise AssertionError(f"team nodes not ready in {timeout} s: {late}")
