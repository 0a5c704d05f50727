"""The one client of rosreconf's ROS 2 helper processes: JSON lines over stdin and stdout.

rosreconf reads DDS without rclpy; what needs rclpy runs in a helper under the ROS 2 Python
(``rosreconf.ros.ros2.runtime.start_helper``: a session of its own, dying with rosreconf).
Two speak this protocol: the lifecycle agent (``lifecycle``) and the stand-in zygote
(``zygote``). A helper says ``{"ready": ...}`` first; every request is one line, every
answer one line, with the request's ``id`` where it has one. The helper answers on a
descriptor of its own (``scripts/helper_channel.py``): what the libraries under rclpy print
goes to its log, never into the answers. Should a line that is not a JSON object come all
the same, it is written to the helper's log and passed over, never taken as an answer: one
stray line must not put every later answer one behind. Nothing here prints.
"""

from __future__ import annotations

import contextlib
import json
import queue
import signal
import subprocess
import threading
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import IO, Any, ClassVar

from rosreconf.errors import ExternalToolError
from rosreconf.procs.child import release
from rosreconf.procs.signals import signal_group
from rosreconf.ros.ros2.runtime import ANSWER_SECONDS, start_helper

HUNG_LOOK = 0.25
"""Seconds between looks at a helper's silence while an answer is awaited."""


class Helper:
    """Start a helper, read its lines on a thread, hand its answers on, and end it.

    Attributes:
        name: how messages name it (its Python and script).
        log: where its stderr goes.
        process: the helper process.
        error: the error class its failures raise (a subclass may name its own).
        close_wait: seconds ``close`` waits for it to end on its own before SIGKILL.
        heard_at: when it last said anything (monotonic seconds).
    """

    error: ClassVar[type[ExternalToolError]] = ExternalToolError
    close_wait: ClassVar[float] = 1.0
    hung_after: ClassVar[float | None] = None
    """Seconds of silence (no answer, no ``{"alive": ...}`` beat) after which a helper that
    beats is hung; None for one that does not beat."""

    def __init__(
        self,
        argv: Sequence[str],
        env: Mapping[str, str],
        log: Path,
        name: str,
        keep_fds: Sequence[int] = (),
    ) -> None:
        self.name = name
        self.log = log
        self.process, self._alive = start_helper(argv, env, log, keep_fds)
        self.heard_at = time.monotonic()
        self._started = False  # silence counts only once it has said it is ready
        self._answers: queue.Queue[dict[str, Any]] = queue.Queue()
        assert self.process.stdout is not None
        threading.Thread(target=self._read, args=(self.process.stdout,), daemon=True).start()
        try:
            first = self.answer(None, ANSWER_SECONDS, "start")
        except ExternalToolError:
            self.close()
            raise
        if "ready" not in first:
            self.close()
            raise self.error(f"{name} did not start: it said {first} (see {log})")
        self._started = True

    def heard(self, said: dict[str, Any]) -> bool:
        """Take a line that is news rather than an answer (on the reader thread); True if so."""
        return False

    def ended(self) -> None:
        """Note, on the reader thread, that the helper's stdout has closed."""

    def hung(self) -> bool:
        """Tell whether a helper that beats has said nothing for ``hung_after`` seconds.

        A stopped (SIGSTOP) or deadlocked helper still runs as a process, so ``died`` never
        says it; its silence does.
        """
        return (
            self.hung_after is not None
            and self._started
            and time.monotonic() - self.heard_at > self.hung_after
            and self.process.poll() is None
        )

    def _read(self, stream: IO[bytes]) -> None:
        for line in stream:
            self.heard_at = time.monotonic()
            try:
                said = json.loads(line)
            except ValueError:
                said = None
            if not isinstance(said, dict):  # not the protocol: to the log, never an answer
                self._stray(line)
            elif "alive" in said:  # a beat: a sign of life, no answer
                continue
            elif not self.heard(said):
                self._answers.put(said)
        self.ended()
        self._answers.put({"eof": True})

    def _stray(self, line: bytes) -> None:
        """Write a line that is not the protocol to the helper's log, marked as such."""
        with contextlib.suppress(OSError), self.log.open("ab") as log:
            log.write(b"rosreconf: not a protocol line, passed over: " + line.rstrip(b"\n") + b"\n")

    def send(self, requests: Sequence[dict[str, Any]]) -> None:
        """Write ``requests``, one line each, at once.

        Raises:
            ExternalToolError: the helper has exited.
        """
        assert self.process.stdin is not None
        try:
            self.process.stdin.write("".join(json.dumps(r) + "\n" for r in requests).encode())
            self.process.stdin.flush()
        except OSError:
            raise self.error(f"{self.name} has exited (see {self.log})") from None

    def answer(self, wanted: int | None, timeout: float, what: str) -> dict[str, Any]:
        """Return the next answer (with ``wanted``: the one with that ``id``).

        Raises:
            ExternalToolError: none within ``timeout`` seconds, or the helper has exited.
        """
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            try:
                answer = self._answers.get(timeout=max(0.0, min(left, HUNG_LOOK)))
            except queue.Empty:
                if self.hung():
                    raise self.error(
                        f"{self.name} (pid {self.process.pid}) is hung: it said nothing for "
                        f"{self.hung_after:g} s ({what}; see {self.log})"
                    ) from None
                if left > HUNG_LOOK:
                    continue
                raise self.error(
                    f"{self.name} did not answer within {timeout:g} s ({what}; see {self.log})"
                ) from None
            if answer.get("eof"):
                raise self.error(f"{self.name} has exited (see {self.log})")
            if wanted is None or answer.get("id") == wanted:
                return answer

    def died(self) -> int | None:
        """Return the helper's exit status if it has ended on its own (killed, crashed)."""
        return self.process.poll()

    def close(self) -> None:
        """End the helper (its stdin closes; then SIGKILL) and release its watchdog.

        A hung helper is killed at once: it would not read its stdin's end.
        """
        if self.process.stdin is not None:
            with contextlib.suppress(OSError):
                self.process.stdin.close()
        try:
            self.process.wait(timeout=0.0 if self.hung() else self.close_wait)
        except subprocess.TimeoutExpired:
            signal_group(self.process.pid, signal.SIGKILL)
            self.process.wait()
        signal_group(self.process.pid, signal.SIGKILL)
        release(self._alive)
