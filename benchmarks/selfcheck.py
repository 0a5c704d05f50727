"""Check the benchmark harness: ``run.py --quick`` writes its table and every JSON entry.

The first step of ``make bench`` (not a pytest test: it takes minutes of a busy machine and
checks the harness, not rosreconf). Exits non-zero, with the failed assertion, when an entry
is missing or a row failed.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

RUN = Path(__file__).resolve().parent / "run.py"


def check_quick_run(tmp_path: Path) -> None:
    """Run ``run.py --quick`` and assert every entry of its JSON came out."""
    out = tmp_path / "results.json"
    # About 20 CPU seconds, but 160 s of wall-clock time under nice on a 2-core machine with a
    # load of 12: the timeout only guards against a hang.
    done = subprocess.run(
        [sys.executable, str(RUN), "--quick", "--json", str(out)],
        capture_output=True,
        text=True,
        check=True,
        timeout=900,  # a guard against hangs, not a speed test (make bench measures speed)
    )
    assert "rosreconf benchmark" in done.stdout
    doc = json.loads(out.read_text())
    assert [(r["roles"], r["candidates"]) for r in doc["grid"]] == [(8, 2), (12, 3)]
    assert all(r["count"]["status"] == "ok" for r in doc["grid"])
    assert doc["machine"]["cores"] >= 1
    assert set(doc["machine"]["load_average"]) == {"start", "end"}
    stages = doc["loading"]  # where reading and checking a library goes, stage by stage
    assert stages["scope"] == "in-process" and stages["bytes"] > 0
    assert stages["seconds"]["parse"] > 0
    assert stages["reader"].startswith("every file: libyaml's event stream"), stages["reader"]
    assert stages["seconds"]["total"] >= max(stages["seconds"].values()) - 1e-9
    floors = stages["floor_seconds"]  # libyaml's parse, PyYAML's composer
    assert set(floors) == {"libyaml", "compose"} and min(floors.values()) > 0
    assert set(stages["load_average"]) == {"start", "end"}
    big = doc["largest"]  # whole process: peak RSS and CPU beside a large library
    assert big["scope"].startswith("whole process") and big["library_bytes"] > 0
    assert big["rows"][0]["command"] == "rosreconf validate", big
    # exit 1 is an answer (plan: some schema has no configuration without NSM3)
    assert all(set(r["exit"]) <= {0, 1} and r["peak_rss_bytes"] > 0 for r in big["rows"]), big
    sim = doc["simulate"]  # the M-solution sweep, whole process
    assert sim["status"] == "ok", sim
    assert 0 < sim["loops_simulated"] == sim["distinct_loops"] <= sim["configurations"]
    fd = [r["fast_downward"]["first"] for r in doc["grid"]]  # ff-first on the rendered task
    assert all(m["status"] == "ok" and m["planned"] == "solved" and m["valid"] for m in fd), fd
    whole = doc["whole_process"]  # interleaved pairs: CPU seconds of ours and the reference
    assert [w["status"] for w in whole] == ["ok", "ok", "ok"], whole  # --help, one mistake
    assert all(w["cpu_seconds"] > 0 and w["reference_cpu_seconds"] > 0 for w in whole)
    assert all(w["scope"] == "whole-process" for w in whole)
    growth = doc["growth"]
    assert [r["roles"] for r in growth["rows"]] == [8, 16]
    assert all(r["status"] == "ok" and r["first_found"] for r in growth["rows"])
    assert growth["exponent"]["count"] is not None
    assert doc["watch"]["replan_seconds"] > 0 and doc["watch"]["fast_downward_seconds"] > 0
    assert doc["import_floor"]["status"] == "ok"
    assert doc["soak"]["status"].startswith("skipped in --quick"), doc["soak"]
    assert doc["context"]["status"].startswith("skipped in --quick"), doc["context"]


if __name__ == "__main__":
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        check_quick_run(Path(tmp))
    print("benchmark harness: every entry came out")
