"""Tell the test which processes a fake started and where, so it can check they are gone.

The test sets ROSRECONF_FAKE_REPORT to a path; the fake writes ``{"pgid", "pids", "cwd"}`` there
as JSON, atomically (write then rename), once all its processes are running.
"""

from __future__ import annotations

import json
import os


def report(*pids: int) -> None:
    """Write this process group, the given pids (default: this one) and the cwd for the test."""
    path = os.environ.get("ROSRECONF_FAKE_REPORT")
    if not path:
        return
    data = {"pgid": os.getpgid(0), "pids": list(pids) or [os.getpid()], "cwd": os.getcwd()}
    with open(path + ".tmp", "w", encoding="utf-8") as file:
        json.dump(data, file)
    os.replace(path + ".tmp", path)


def plan_file(argv: list[str]) -> str:
    """Return the value of ``--plan-file`` in a Fast Downward-like command line."""
    return argv[argv.index("--plan-file") + 1]
