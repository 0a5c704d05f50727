"""Read a process's /proc/<pid>/stat (Linux): its name, state, parent and start time.

One reader for every module that looks at processes it may not own: the descendants of a
roslaunch, the node processes on this host, the state of a watched process.

The second field, the command name in parentheses, is chosen by the program (``prctl``, the
file name it was started from) and may itself hold spaces and ``)``: ``(a) (b)``. So the
line is split at its *last* ``)``; every field after it is a number or a state letter. The
field numbers below are those of proc(5).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

PROC = Path("/proc")


@dataclass(frozen=True)
class ProcStat:
    """The fields of /proc/<pid>/stat that rosreconf uses.

    Attributes:
        pid: the process id (field 1).
        comm: the command name, without its parentheses (field 2; at most 15 bytes).
        state: the state letter (field 3): ``R``, ``S``, ``T`` stopped, ``Z`` zombie...
        ppid: the parent's pid (field 4).
        start_ticks: when it started, in clock ticks after boot (field 22): with the pid,
            it names one process for ever, where a pid alone is recycled.
    """

    pid: int
    comm: str
    state: str
    ppid: int
    start_ticks: int


def parse_stat(text: str) -> ProcStat:
    """Parse the text of a /proc/<pid>/stat file.

    Raises:
        ValueError: the text is not a stat line.
    """
    head, close, tail = text.rpartition(")")
    pid, open_, comm = head.partition(" (")
    fields = tail.split()
    if not close or not open_ or len(fields) < 20:
        raise ValueError(f"not a /proc/<pid>/stat line: {text[:80]!r}")
    return ProcStat(int(pid), comm, fields[0], int(fields[1]), int(fields[19]))


def read_stat(pid: int | str, proc_root: Path = PROC) -> ProcStat | None:
    """Return a process's stat fields; None when it is gone (or its stat cannot be read)."""
    try:
        data = (proc_root / str(pid) / "stat").read_bytes()
    except OSError:
        return None
    try:  # a name need not be UTF-8; it is only ever shown
        return parse_stat(data.decode("utf-8", errors="replace"))
    except ValueError:
        return None
