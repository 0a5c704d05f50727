"""The rows the benchmarks measure, typed, and how each is written into results.json.

benchmarks/results.json is read by the docs (``run.py --markdown``): each ``to_json`` keeps
the keys it has always had. A row that did not finish holds only its ``status`` (and what
names it), so a reader tells a time from a failure by ``status == "ok"``.
"""

from __future__ import annotations

import os
import platform
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path
from typing import Any

OK = "ok"


def _present(row: Any) -> dict[str, Any]:
    """Return a dataclass's fields that hold a value (None: not measured by this kind)."""
    return {f.name: getattr(row, f.name) for f in fields(row) if getattr(row, f.name) is not None}


@dataclass
class Measured:
    """One in-process measurement in a fresh child: seconds, peak RSS and what it found.

    Which of the optional answers a child gives depends on its kind (``children.KINDS``).
    """

    status: str = OK
    seconds: float | None = None
    rss_kib: int | None = None
    digits: int | None = None
    found: bool | None = None
    engine: str | None = None
    solver_calls: int | None = None
    planned: str | None = None
    cost: float | None = None
    valid: bool | None = None
    listed: int | None = None

    @property
    def ok(self) -> bool:
        return self.status == OK

    def to_json(self) -> dict[str, Any]:
        return _present(self) if self.ok else {"status": self.status}


@dataclass
class GrowthRow:
    """Count, first and optimal one after the other on one library of ``roles`` x 10."""

    roles: int
    status: str = OK
    digits: int | None = None
    count: float | None = None
    first_found: bool | None = None
    first: float | None = None
    optimal_found: bool | None = None
    optimal: float | None = None
    rss_kib: int | None = None

    def to_json(self) -> dict[str, Any]:
        return _present(self) if self.status == OK else {"roles": self.roles, "status": self.status}


@dataclass
class GridRow:
    """One cell row of the in-process grid: each solver kind and Fast Downward's two searches."""

    roles: int
    candidates: int
    kinds: dict[str, Measured] = field(default_factory=dict)
    fast_downward: dict[str, Measured] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {
            "roles": self.roles,
            "candidates": self.candidates,
            **{kind: m.to_json() for kind, m in self.kinds.items()},
            "fast_downward": {key: m.to_json() for key, m in self.fast_downward.items()},
        }


@dataclass
class Pair:
    """One whole-process row: ours against a reference, run back to back (CPU seconds)."""

    what: str
    status: str = OK
    scope: str = "whole-process"
    runs: int = 0
    cpu_seconds: float = 0.0
    wall_seconds: float = 0.0
    reference: str = ""
    reference_cpu_seconds: float = 0.0
    ratio: float | None = None
    goal_ratio: float | None = None
    goal_seconds: float | None = None
    met: bool = False

    def to_json(self) -> dict[str, Any]:
        return asdict(self) if self.status == OK else {"what": self.what, "status": self.status}


@dataclass
class Watched:
    """The watcher's step from a detected failure to the new configuration (in-process)."""

    replan_seconds: float
    fast_downward_seconds: float
    search: str
    goal: str
    met: bool
    scope: str = "in-process"

    def to_json(self) -> dict[str, Any]:
        return asdict(self)


@dataclass
class Sweep:
    """``rosreconf simulate`` with 1 and 2 workers, whole process (``sweep.simulate_sweep``)."""

    status: str
    scope: str = "whole-process"
    configurations: int = 0
    distinct_loops: int = 0
    loops_simulated: int = 0
    meeting_requirements: int = 0
    unstable: int = 0
    seconds_1_worker: float = 0.0
    seconds_2_workers: float = 0.0
    cpu_seconds_1_worker: float = 0.0
    cpu_seconds_2_workers: float = 0.0
    speedup_2_workers: float = 0.0
    goal_seconds: float = 0.0
    met: bool = False
    load_average: list[float] = field(default_factory=list)
    runs: int = 0
    instance: str | None = None
    machine: dict[str, Any] | None = None

    def to_json(self) -> dict[str, Any]:
        if self.status != OK:  # what it was run on, and why it did not finish
            return {k: v for k, v in _present(self).items() if k in ("status", "instance")}
        return _present(self)


def machine() -> dict[str, Any]:
    """Describe the machine: cores, CPU model, Python."""
    model = ""
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return {"cores": os.cpu_count(), "cpu": model, "python": platform.python_version()}
