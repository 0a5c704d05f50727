"""rosreconf's ROS 2 face: the node that shows a running ``watch --ros2`` and takes task requests.

The node (``scripts/face_node.py``, under the ROS 2 Python) needs rclpy and
``diagnostic_msgs``, so it runs in a helper process (``rosreconf.ros.ros2.helper``), as the
lifecycle agent does. rosreconf pushes it the watch's state (``rosreconf.ros.facestate``)
and every decision; it pushes back, unasked, the switch requests its ``task`` parameter took
and the ones it refused (``Helper.heard``), handed to ``asked`` (``tasks.Tasks.ask``: a queue
the watcher drains at its next step). It also reads the library's context topics
(``livecontext``): each reading is handed to ``context`` (``LiveContext.heard``) as it
comes. With ``serve`` False (``watch --no-face``) the node only reads context. A face that
dies takes nothing down with it: what it was sent is dropped, said once in its log. Nothing
here prints.
"""

from __future__ import annotations

import contextlib
import json
import queue
import subprocess
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.model.context import ContextValue, ContextVariable
from rosreconf.ros.events import Event
from rosreconf.ros.facestate import level_of
from rosreconf.ros.ros2.helper import Helper
from rosreconf.ros.ros2.runtime import ros2_python

FACE_SCRIPT = Path(__file__).parent / "scripts" / "face_node.py"
QUEUED = 256
"""Lines waiting for the face at most; more are dropped (it is hung)."""


class FaceNode(Helper):
    """Own the face's helper process (see the module docstring); a ``tasks.Face``."""

    def __init__(
        self,
        name: str,
        env: Mapping[str, str],
        log: Path,
        asked: Callable[[str, str], None],
        context: Sequence[ContextVariable] = (),
        heard: Callable[[str, ContextValue], None] | None = None,
        unreadable: Callable[[str, str], None] | None = None,
        serve: bool = True,
    ) -> None:
        """``asked(task, refused)``: a switch request ("" refused) or a refusal, with why.
        ``heard(name, value)``: a reading of a ``context`` variable; ``unreadable(name,
        why)``: a context topic it cannot read. ``serve``: parameters and /diagnostics too.

        Raises:
            ExternalToolError: no ROS 2 Python with rclpy, or the node did not start.
        """
        self.asked = asked  # before the reader thread starts
        self.context_heard, self.unreadable = heard, unreadable
        self.gone = False
        self._out: queue.Queue[dict[str, Any]] = queue.Queue(maxsize=QUEUED)
        python = ros2_python(env)
        topics = [{"name": v.name, "topic": v.topic, "type": v.type, "field": v.field}
                  for v in context]  # fmt: skip
        argv = [python, str(FACE_SCRIPT), name, json.dumps(topics), *([] if serve else ["--quiet"])]
        super().__init__(argv, env, log, f"the face {name}")
        threading.Thread(target=self._write, name="rosreconf-face", daemon=True).start()

    def heard(self, said: dict[str, Any]) -> bool:
        """Hand on a switch request or a refusal (on the reader thread)."""
        kind = said.get("event")
        if kind == "switch":
            self.asked(str(said.get("task", "")), "")
        elif kind == "refused":
            self.asked(str(said.get("task", "")), str(said.get("reason", "")))
        elif kind == "context" and self.context_heard is not None:
            value = said.get("value")
            if isinstance(value, bool | str | float | int):
                self.context_heard(str(said.get("name", "")), value)
        elif kind == "context-error" and self.unreadable is not None:
            self.unreadable(str(said.get("name", "")), str(said.get("reason", "")))
        else:
            return False
        return True

    def _push(self, line: dict[str, Any]) -> None:
        """Queue one line for the writer thread: a face that hangs (its pipe full) never
        holds the watcher up; what it cannot take is dropped, and the next state renews it."""
        if not self.gone:
            with contextlib.suppress(queue.Full):
                self._out.put_nowait(line)

    def _write(self) -> None:
        """Send the queued lines (a thread); a face that has exited is written to no more."""
        while not self.gone:
            line = self._out.get()
            try:
                self.send([line])
            except (ExternalToolError, ValueError):  # ValueError: its stdin closed already
                self.gone = True

    def close(self) -> None:
        """End the face, once it has taken the watcher's last words (0.5 s at most)."""
        deadline = time.monotonic() + 0.5
        while self._out.qsize() and not self.gone and time.monotonic() < deadline:
            time.sleep(0.01)
        self.gone = True
        with contextlib.suppress(queue.Full):
            self._out.put_nowait({"op": "end"})  # wakes the writer, which then ends
        super().close()

    def state(self, doc: dict[str, Any]) -> None:
        """Show the watch's state (``facestate.snapshot``)."""
        self._push({"op": "state", "state": doc})

    def line(self, event: Event) -> None:
        """Say one decision on /rosout, at its level (``facestate.level_of``)."""
        self._push({"op": "log", "level": level_of(event.kind), "text": event.message})


TASK_SCRIPT = Path(__file__).parent / "scripts" / "task_client.py"


def ask_switch(face: str, task: str, env: Mapping[str, str], timeout: float) -> tuple[bool, str]:
    """Ask the face ``face`` of a running watch to switch to ``task``; return (taken, reason).

    Runs ``scripts/task_client.py`` under the ROS 2 Python (a ``SetParameters`` call, sent
    again after 1.5 s unanswered): no ROS 2 tools needed. ``env`` names the domain
    (``ROS_DOMAIN_ID``).

    Raises:
        ExternalToolError: no ROS 2 Python, or no face answered within ``timeout`` seconds.
    """
    argv = [ros2_python(env), str(TASK_SCRIPT), face, task, f"{timeout:g}"]
    try:
        out = subprocess.run(
            argv, env=dict(env), capture_output=True, text=True, timeout=timeout + 30, check=False
        )
    except subprocess.TimeoutExpired:
        raise ExternalToolError(f"asking {face} did not end within {timeout + 30:g} s") from None
    lines = [x for x in out.stdout.splitlines() if x.startswith("{")]
    said = json.loads(lines[-1]) if lines else {"error": out.stderr.strip()[-500:] or "no answer"}
    if "error" in said:
        raise ExternalToolError(str(said["error"]))
    return bool(said["successful"]), str(said.get("reason", ""))
