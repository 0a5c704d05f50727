"""Sum the CPU seconds each test file took, from ``make test-cpu``'s log (JSON lines).

The suite's wall time on two cores is bounded by its CPU seconds over two, and by the live
ROS 2 lanes' waits (``tests/conftest.py``): this says which files spend which, so that a cut
goes where the time is. Usage: ``python scripts/test_cpu.py test-cpu.jsonl [N]``.
"""

from __future__ import annotations

import json
import sys
from collections import defaultdict
from pathlib import Path


def main(path: Path, top: int) -> None:
    """Print the suite's totals, then the ``top`` files by CPU seconds."""
    rows = [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]
    files: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0, 0])
    for row in rows:
        name = row["test"].partition("::")[0]
        files[name][0] += row["own"] + row["children"]
        files[name][1] += row["wall"]
        files[name][2] += 1
    live = [r for r in rows if "@ros2-live-" in r["test"]]
    cpu = sum(r["own"] + r["children"] for r in rows)
    print(f"{len(rows)} tests: {cpu:.0f} CPU s, {sum(r['wall'] for r in rows):.0f} test s")
    print(
        f"  live ROS 2 lanes: {sum(r['own'] + r['children'] for r in live):.0f} CPU s,"
        f" {sum(r['wall'] for r in live):.0f} test s"
    )
    print(f"{'CPU s':>8} {'test s':>8} {'tests':>6}  file")
    for name, (c, w, n) in sorted(files.items(), key=lambda kv: -kv[1][0])[:top]:
        print(f"{c:8.1f} {w:8.1f} {n:6d}  {name}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 30)
