"""Keep Cyclone DDS's C-library messages from flooding stderr: each cause is said once.

The C library writes its warnings straight to file descriptor 2 ("deserialization
ros_discovery_info/... failed", one line per undecodable sample: thousands in a few minutes
of node churn). While a DDS session is open, fd 2 is a pipe read by a thread here: a line
in Cyclone's log format (``<seconds> [<domain>] <thread>: <message>``) is said the first
time its cause (the message without GUIDs, sequence numbers and counts) appears, escaped,
and counted afterwards (a cause rosreconf brings about by design, ``_EXPECTED``, is only
counted); every other byte (Python's own stderr, rosreconf's messages) is
passed through unchanged. ``ROSRECONF_DDS_VERBOSE=1`` passes Cyclone's lines through too.

The redirection is process-wide and counted: nested sessions share one pipe, and the last
one to close puts fd 2 back and waits for the pipe to drain. Re-emitting goes to the
original fd 2, the same place the C library would have written.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import threading
from collections import Counter
from dataclasses import dataclass, field

from rosreconf.printable import printable

_CYCLONE_LINE = re.compile(rb"^\d+\.\d+ +\[-?\d+\] +[^:]{1,40}: (.*)$")
"""Cyclone's log line: a timestamp, the domain id in brackets, the thread name, the text."""
_VARIABLE = re.compile(r"[0-9a-f]+(?::[0-9a-f]+){3}|#\d+|\b\d+\b")
"""What differs between two lines of one cause: GUIDs, sequence numbers, counts."""
_EXPECTED = re.compile(r"deserialization ros_discovery_info/\S+ failed")
"""Causes rosreconf brings about itself and handles, counted but never said: without
``--distro`` it reads ``ros_discovery_info`` in both Gid layouts (``discovery``), and each
reader fails to decode the other layout's samples by design. A participant none of whose
samples decode is said by ``discovery`` itself (``undecodable``), with what to do."""


@dataclass
class _Filter:
    """The pipe on fd 2, the thread reading it, and the causes seen so far."""

    saved: int
    pipe: int
    verbose: bool
    causes: Counter[str] = field(default_factory=Counter)
    users: int = 1
    thread: threading.Thread | None = None
    lock: threading.Lock = field(default_factory=threading.Lock)

    def pump(self) -> None:
        """Read the pipe until every writer is gone, line by line."""
        rest = b""
        while chunk := os.read(self.pipe, 65536):
            *lines, rest = (rest + chunk).split(b"\n")
            for line in lines:
                self.line(line)
        if rest:
            self.line(rest)

    def line(self, raw: bytes) -> None:
        """Pass one line on, or say a Cyclone message the first time its cause appears."""
        found = _CYCLONE_LINE.match(raw)
        if found is None or self.verbose:
            self.write(raw + b"\n")
            return
        text = found.group(1).decode("utf-8", "replace")
        cause = _VARIABLE.sub("*", text)
        with self.lock:
            self.causes[cause] += 1
            first = self.causes[cause] == 1
        if first and not _EXPECTED.search(text):
            note = (
                f"rosreconf: Cyclone DDS says: {printable(text, 300)} (said once per cause; "
                "ROSRECONF_DDS_VERBOSE=1 shows every line)\n"
            )
            self.write(note.encode("utf-8"))

    def write(self, data: bytes) -> None:
        """Write to the original stderr, ignoring a closed one."""
        with contextlib.suppress(OSError):
            os.write(self.saved, data)


_active: list[_Filter] = []
_guard = threading.Lock()


def hold() -> None:
    """Start filtering fd 2 (or count one more user of the filter already running)."""
    with _guard:
        if _active:
            _active[0].users += 1
            return
        sys.stderr.flush()
        try:
            saved = os.dup(2)
        except OSError:
            return  # no stderr at all: nothing to protect
        read, write = os.pipe()
        os.dup2(write, 2)
        os.close(write)
        f = _Filter(saved, read, os.environ.get("ROSRECONF_DDS_VERBOSE") == "1")
        f.thread = threading.Thread(target=f.pump, name="rosreconf-dds-stderr", daemon=True)
        f.thread.start()
        _active.append(f)


def release() -> Counter[str]:
    """Stop one user; the last one restores fd 2. Return the causes counted so far."""
    with _guard:
        if not _active:
            return Counter()
        f = _active[0]
        f.users -= 1
        if f.users > 0:
            return Counter(f.causes)
        _active.clear()
        sys.stderr.flush()
        os.dup2(f.saved, 2)  # the pipe's last writer is gone: the thread reads to the end
        if f.thread is not None:
            f.thread.join(5)
        if f.thread is None or not f.thread.is_alive():
            os.close(f.pipe)
            os.close(f.saved)
        # else a child process started meanwhile still holds the pipe: the thread goes on
        # passing its output through (closing the pipe would break the child's stderr).
        return Counter(f.causes)


def causes() -> Counter[str]:
    """Return how often each Cyclone message cause was seen while filtering (live counts)."""
    with _guard:
        return Counter(_active[0].causes) if _active else Counter()
