"""whatif reduces failure sets to their summaries as they are decided (issue 22).

Every failure set used to be kept: ``whatif -k 2`` on 1000 roles x 10 candidates reached
8.9 GB, and 10^4 candidates in one role ran out of memory. Here a whole ``rosreconf whatif``
child keeps its peak memory while the pairs of failures grow 100-fold, its summaries equal
those of brute force (a count per failure set), and the listing is cut at ``LISTED`` sets and
says so.
"""

from __future__ import annotations

import itertools
import json
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest
from manylib import write_many
from shapes import write_hub

from rosreconf.analysis import whatif
from rosreconf.analysis.whatif import LISTED
from rosreconf.formats.loader import load_paths
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance

CAP = 4_000_000_000
"""Address-space cap of the child processes (bytes)."""

MEASURE = """
import resource, subprocess, sys
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(f"{done.returncode} {peak}")
sys.stdout.write(done.stdout)
"""
"""Run a command; print its exit code and peak RSS (KiB, whole process), then its stdout."""


def _whatif(folder: Path, *extra: str) -> tuple[int, int, dict[str, object]]:
    argv = [sys.executable, "-m", "rosreconf", "whatif", "-k", "2", "--json", *extra,
            "-l", str(folder / "libraries"), "-s", str(folder / "schemas")]  # fmt: skip
    done = subprocess.run(
        ["prlimit", f"--as={CAP}", "--", "timeout", "300", sys.executable, "-c", MEASURE, *argv],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    head, _, out = done.stdout.partition("\n")
    code, peak = (int(x) for x in head.split())
    [schema] = json.loads(out)["schemas"]
    return code, peak, schema


def test_whatif_k2_with_100x_more_failure_pairs_keeps_its_peak_memory(tmp_path: Path) -> None:
    """Case: whatif -k 2 on 1000 x 10 reached 8.9 GB; 10^4 candidates: MemoryError."""
    peaks = {}
    for n in (100, 1000):
        code, peak, schema = _whatif(write_many(tmp_path / f"many{n}", n), "--workers", "1")
        assert code == 0
        relevant = schema["relevant"]
        assert isinstance(relevant, list)
        m = len(relevant)
        listed = schema["failure_sets"]
        assert isinstance(listed, list)
        every = 1 + m + m * (m - 1) // 2
        assert len(listed) == min(every, LISTED)
        assert schema["failure_sets_complete"] is (every <= LISTED)
        # the listing is the first sets by (size, names): the empty set, then single failures
        assert [s["failed"] for s in listed[: m + 1]] == [[], *sorted([c] for c in relevant)]
        peaks[n] = peak
    assert peaks[1000] < peaks[100] + 40 * 1024, peaks  # KiB: 361 MB before, for n = 1000


def test_whatif_shares_and_pairs_equal_brute_force_when_the_listing_is_cut(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With the listing cut, the summaries still cover every set: held to brute force."""
    monkeypatch.setattr(whatif, "LISTED", 50)
    loaded = load_paths([write_many(tmp_path, 40) / "libraries", tmp_path / "schemas"])
    library, schema = loaded.library, loaded.schemas[0]
    with ProcessPoolExecutor(max_workers=2) as pool:
        report = whatif.analyse(library, schema, 2, pool, chunk_size=4)
    assert not report.listed_all and len(report.listed) == 50
    assert [o.failed for o in report.listed] == sorted(
        (o.failed for o in report.listed), key=lambda f: (len(f), f)
    )
    relevant = report.relevant
    alive = {c: count(compile_instance(library, schema, [c])) > 0 for c in relevant}
    assert report.critical == [c for c in relevant if not alive[c]]
    survivors = [c for c in relevant if alive[c]]
    pairs = [
        (a, b)
        for a, b in itertools.combinations(survivors, 2)
        if count(compile_instance(library, schema, [a, b])) == 0
    ]
    assert report.critical_pairs == pairs
    names = [c.name for c in library]
    for k in (1, 2):
        sets = list(itertools.combinations(names, k))
        survive = sum(count(compile_instance(library, schema, f)) > 0 for f in sets)
        assert report.survived(k) == (survive, len(sets))


def test_whatif_k2_past_its_search_time_exits_3_saying_which_sets_were_decided(
    tmp_path: Path,
) -> None:
    """Case: whatif -k 2 on generate 1000 x 10 ran past 300 s; now it stops at its budget.

    A hub of 2,000 consumers has C(4002, 2) = 8 million pairs: far more than a second's work.
    """
    folder = write_hub(tmp_path, 2000)
    done = subprocess.run(
        [sys.executable, "-m", "rosreconf", "whatif", "-k", "2", "--workers", "1",
         "--search-time", "1", "-l", str(folder / "libraries"), "-s", str(folder / "schemas")],
        capture_output=True, text=True, check=False, timeout=600,
    )  # fmt: skip
    words = " ".join(done.stderr.split())
    assert done.returncode == 3, done.stderr
    assert done.stdout == "" and "Traceback" not in done.stderr
    assert "ran out of its time (--search-time 1)" in words
    # where it stopped depends on the machine's speed; what it says of it does not
    singles = "of the 4,002 sets of 1 failed component(s) (of its 4,002 relevant components)"
    pairs = "every set of up to 1 failed component(s) was decided (critical components: none), and "
    assert singles in words or (pairs in words and "of the 8,006,001 sets of 2 failed" in words)
    assert "(raise --search-time, or lower --max-failures)" in words


def test_whatif_whose_deadline_has_passed_says_nothing_was_decided(tmp_path: Path) -> None:
    loaded = load_paths([write_many(tmp_path, 40) / "libraries", tmp_path / "schemas"])
    library, schema = loaded.library, loaded.schemas[0]
    with pytest.raises(whatif.SweepOutOfTime, match=r"0 of the \d+ sets of 1 failed"):
        whatif.analyse(library, schema, 2, deadline=time.monotonic())
    report = whatif.analyse(library, schema, 2, deadline=time.monotonic() + 3600)
    assert report.survived(1)[1] == len(library)  # a deadline not reached changes nothing
