#!/usr/bin/env python3
"""Fork rclpy stand-ins from one warm process, so a cold start does not import rclpy again.

Importing rclpy and the message modules costs a stand-in about 0.5 s of CPU (measured:
the interpreter's start 0.09 s, the imports 0.47 s, ``rclpy.init`` and the node 0.04 s).
Nine stand-ins started at once on two busy cores wait seconds for that. This process, run by
``rosreconf.ros.ros2.zygote`` under the ROS 2 Python, imports everything once and then
forks one child per stand-in: each child is one process with its own pid, its own session
and its own DDS participant, running ``standin_node.main`` as if it had been started on its
own. It never calls ``rclpy.init`` itself and starts no thread. The threads its libraries
start are accounted for at every fork: LTTng-UST's two listeners (loaded with rclpy's
tracepoints; with no session daemon they wait on a futex for good), around which LTTng's own
fork hooks run, as its ``liblttng-ust-fork.so`` would run them; and, until the first fork,
OpenBLAS's worker (numpy, which the message modules import), which OpenBLAS's own
``pthread_atfork`` handler stops before each fork. A child starts with its one thread.

The SIGSEGV that Kilted's stand-ins sometimes died of as they started (seen in ``create_node``,
``create_service``) was not the fork's: the faulting thread is Fast DDS 3's type lookup
reply thread, which the child's own participant starts, racing its discovery thread (cores
read with gdb); exec'd stand-ins and plain rclpy processes run the same code. rosreconf's own
participants run without that service (``rosreconf.ros.ros2.runtime.NO_TYPE_LOOKUP``).

Each child: a new session (rosreconf signals its group), stdin from /dev/null, its output
appended to its log, and its command line rewritten (as ``setproctitle`` does) to the one it
would have had on its own, so ``ps`` and ``pgrep -f '__node:=NSM3'`` find it. A child does
not die with this process: a helper's death is not a component's failure. It dies with
rosreconf instead: rosreconf passes the read end of a pipe only it writes to
(``ROSRECONF_STANDIN_ALIVE_FD``), and each child forks a watchdog into its own group that
kills the group when that pipe closes, that is when rosreconf has died (the same watchdog as
``rosreconf.procs.child``'s). Without that variable a child gets a parent-death signal, as
before.

Protocol, JSON lines: rosreconf writes ``{"id": 1, "argv": [...], "log": "/path"}`` on
stdin; the answer, on the pipe rosreconf gave as stdout and kept for answers alone
(``helper_channel``: fd 1 itself goes to the log), is ``{"id": 1, "pid": 4711}`` (or
``"error"``); whenever a child ends, ``{"exited": 4711, "code": 0}`` (a negative code:
killed by that signal), as
``subprocess`` says it. This process reaps every child. When stdin closes it kills what is
left and exits. The first line it writes is ``{"ready": <pid>}``.
"""

from __future__ import annotations

import contextlib
import ctypes
import importlib.util
import json
import os
import select
import signal
import sys
import traceback
from pathlib import Path
from typing import Any

from helper_channel import Channel, take_channel

PR_SET_PDEATHSIG = 1
ALIVE_ENV = "ROSRECONF_STANDIN_ALIVE_FD"
_HERE = Path(__file__).resolve().parent


def _alive_fd() -> int | None:
    """Return the pipe the children's watchdogs wait on (rosreconf holds its other end)."""
    text = os.environ.get(ALIVE_ENV, "")
    return int(text) if text.isdigit() else None


def _watchdog(alive: int) -> None:
    """Fork a process into this group that kills the group when ``alive`` reads EOF.

    Forked twice, so that it is nobody's child to wait for. It closes every other descriptor
    (the log, /dev/null) so that it holds nothing of the stand-in's.
    """
    middle = os.fork()
    if middle == 0:
        if os.fork() == 0:
            try:
                os.closerange(0, alive)
                os.closerange(alive + 1, 65536)
                while os.read(alive, 64):
                    pass
                os.killpg(0, signal.SIGKILL)
            finally:
                os._exit(0)
        os._exit(0)
    os.waitpid(middle, 0)


def _load_standin() -> Any:
    """Import ``standin_node.py`` (next to this file): rclpy and the messages come with it."""
    spec = importlib.util.spec_from_file_location("standin_node", _HERE / "standin_node.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.warm()
    return module


def _lttng() -> Any:
    """Return LTTng-UST's library when rclpy loaded it (its fork hooks), else None."""
    with open("/proc/self/maps", encoding="utf-8") as maps:
        paths = {line.split()[-1] for line in maps if "/liblttng-ust" in line}
    for path in sorted(paths):
        if "tracepoint" in path or "fork" in path:
            continue
        lib = ctypes.CDLL(path)
        if hasattr(lib, "ust_before_fork"):
            return lib
    return None


def _set_title(argv: list[str]) -> None:
    """Rewrite this process's command line (``/proc/self/cmdline``) as ``setproctitle`` does.

    The room is the zygote's own command line, which rosreconf pads (``zygote.TITLE_ROOM``);
    a longer one is cut.
    """
    with open("/proc/self/stat", encoding="utf-8") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    start, end = int(fields[45]), int(fields[46])  # arg_start, arg_end (proc(5) 48, 49)
    size = end - start
    title = b"\0".join(a.encode() for a in argv)[: size - 1]
    ctypes.memmove(start, title + b"\0" * (size - len(title)), size)


class Zygote:
    """Fork stand-ins on request and report their exits (see the module docstring)."""

    def __init__(self, standin: Any, answers: Channel) -> None:
        self.standin = standin
        self.answers = answers
        self.lttng = _lttng()
        self.children: set[int] = set()
        self.me = os.getpid()
        wake_read, wake_write = os.pipe()
        os.set_blocking(wake_write, False)
        os.set_blocking(wake_read, False)
        self.wake, self.wake_write = wake_read, wake_write
        signal.set_wakeup_fd(wake_write)
        signal.signal(signal.SIGCHLD, lambda *_: None)
        self.libc = ctypes.CDLL(None, use_errno=True)

    def say(self, answer: dict[str, Any]) -> None:
        """Write one JSON line to rosreconf."""
        self.answers.say(answer)

    def fork(self, argv: list[str], log: str) -> int:
        """Fork one stand-in running ``argv``; return its pid (in the parent only)."""
        mask = ctypes.create_string_buffer(128)  # sigset_t
        if self.lttng is not None:
            self.lttng.ust_before_fork(mask)
        pid = os.fork()
        if pid == 0:
            if self.lttng is not None:
                self.lttng.ust_after_fork_child(mask)
            self._child(argv, log)  # never returns
        if self.lttng is not None:
            self.lttng.ust_after_fork_parent(mask)
        self.children.add(pid)
        return pid

    def _child(self, argv: list[str], log: str) -> None:
        code = 1
        try:
            os.setsid()
            alive = _alive_fd()
            if alive is not None:  # dies with rosreconf, not with the zygote
                _watchdog(alive)
            else:
                self.libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
                if os.getppid() != self.me:  # the zygote died before prctl took effect
                    os._exit(1)
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            os.close(self.wake)
            os.close(self.wake_write)
            self.answers.close_in_child()  # only the zygote answers rosreconf
            null = os.open(os.devnull, os.O_RDONLY)
            out = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
            os.dup2(null, 0)  # rosreconf's pipes are the zygote's, not the child's
            os.dup2(out, 1)
            os.dup2(out, 2)
            os.close(null)
            os.close(out)
            _set_title(argv)
            sys.argv = list(argv[1:])
            code = int(self.standin.main(sys.argv) or 0)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 1
            if not isinstance(exc.code, int) and exc.code is not None:
                print(exc.code, file=sys.stderr)
        except BaseException:  # a child must never return into the zygote's loop
            traceback.print_exc()
        finally:
            with contextlib.suppress(Exception):
                sys.stdout.flush()
                sys.stderr.flush()
            os._exit(code)

    def reap(self) -> None:
        """Report every child that has ended."""
        while self.children:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            self.children.discard(pid)
            self.say({"exited": pid, "code": os.waitstatus_to_exitcode(status)})

    def serve(self) -> None:
        """Answer requests until stdin closes, then kill what is left."""
        self.say({"ready": self.me})
        pending = b""
        while True:
            try:
                readable, _, _ = select.select([0, self.wake], [], [])
            except InterruptedError:
                continue
            if self.wake in readable:
                with contextlib.suppress(BlockingIOError):
                    os.read(self.wake, 512)
                self.reap()
            if 0 not in readable:
                continue
            data = os.read(0, 65536)
            if not data:
                break
            pending += data
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                self.answer(json.loads(line))
        for pid in self.children:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(pid, signal.SIGKILL)
        while self.children:
            pid, _ = os.waitpid(-1, 0)
            self.children.discard(pid)

    def answer(self, request: dict[str, Any]) -> None:
        """Fork the stand-in one request asks for, and say its pid (or why not)."""
        try:
            pid = self.fork([str(a) for a in request["argv"]], str(request["log"]))
        except (OSError, KeyError) as exc:
            self.say({"id": request.get("id"), "error": str(exc)})
            return
        self.say({"id": request.get("id"), "pid": pid})
        self.reap()


def main() -> int:
    """Import rclpy once, then fork stand-ins until rosreconf closes stdin."""
    answers = take_channel()  # before rclpy loads: what its libraries print goes to the log
    Zygote(_load_standin(), answers).serve()
    return 0


if __name__ == "__main__":
    sys.exit(main())
