"""Memory that grew with the answer, held under a real cap (issue 32: N5, S13, out of memory).

Each command runs as its own process under an address-space cap (``prlimit --as``), and its
peak resident memory (whole process, ``RUSAGE_CHILDREN``) is compared between two sizes of
the same shape: the growth, not an absolute number, is what the defects were.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import jsonschema_rs
import pytest

CAP = 1_500_000_000
"""Address-space cap of the child processes (bytes)."""

MEASURE = """
import resource, subprocess, sys
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(f"{done.returncode} {peak}")
sys.stdout.write(done.stdout)
sys.stderr.write(done.stderr)
"""
"""Run a command; print its exit code and peak RSS (KiB, whole process), then its output."""

HUB_P = (0.1, 0.2, 0.3)
"""Failure probabilities of the hub's three candidates."""
CONSUMER_P = 1e-4
"""Failure probability of each single-candidate consumer."""


def measured(argv: list[str], cap: int = CAP) -> tuple[int, int, str, str]:
    """Run ``rosreconf argv`` under ``cap``: exit code, peak RSS (KiB), stdout, stderr."""
    command = [sys.executable, "-m", "rosreconf", *argv]
    done = subprocess.run(
        ["prlimit", f"--as={cap}", "--", "timeout", "300", sys.executable, "-c", MEASURE,
         *command],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    head, _, out = done.stdout.partition("\n")
    code, peak = (int(x) for x in head.split())
    return code, peak, out, done.stderr


def write_hub(folder: Path, consumers: int, *, probabilities: bool = True) -> Path:
    """Write a hub role of 3 candidates whose topic ``consumers`` one-candidate roles need.

    Its 3 configurations are each ``consumers + 1`` components long: the shape whose analysis
    held memory quadratic in that length.
    """
    (folder / "libraries").mkdir(parents=True)
    (folder / "schemas").mkdir(parents=True)
    topic = "{topic: /h, type: std_msgs/Empty}"
    lib = ["format: rosreconf/component-library", "version: 1", "name: hub", "components:"]
    for j, p in enumerate(HUB_P):
        lib += [f"  - name: HUB{j}", "    abstraction: hub", f"    provides: [{topic}]"]
        lib += [f"    failure_probability: {p}"] if probabilities else []
    for i in range(consumers):
        lib += [f"  - name: C{i}", f"    abstraction: c{i}", f"    requires: [{topic}]"]
        lib += [f"    failure_probability: {CONSUMER_P}"] if probabilities else []
    sch = [
        "format: rosreconf/interoperability-schema",
        "version: 1",
        "name: hub",
        "skill: Serve one topic to many.",
        "environment: A synthetic world.",
        "roles:",
        "  - {name: hub, abstraction: hub}",
        *(f"  - {{name: c{i}, abstraction: c{i}}}" for i in range(consumers)),
        "edges:",
        *(f"  - {{consumer: c{i}, providers: [hub]}}" for i in range(consumers)),
    ]
    (folder / "libraries" / "hub.yaml").write_text("\n".join(lib) + "\n")
    (folder / "schemas" / "hub.yaml").write_text("\n".join(sch) + "\n")
    return folder


def _analyse(folder: Path) -> tuple[int, int, dict[str, object], str]:
    argv = ["analyse", "--json", "-l", str(folder / "libraries"), "-s", str(folder / "schemas")]
    code, peak, out, err = measured(argv)
    [schema] = json.loads(out)["schemas"] if code in (0, 1) and out else [{}]
    return code, peak, schema, err


def test_analyse_memory_does_not_grow_with_the_square_of_a_configurations_length(
    tmp_path: Path,
) -> None:
    """Case N5: a hub of 3 consumed by M roles took 343 MB at M = 2,000, 1.1 GB at 4,000."""
    peaks = {}
    for m in (500, 2000):
        code, peak, schema, err = _analyse(write_hub(tmp_path / f"hub{m}", m))
        assert code == 0, err
        reliability = schema["reliability"]
        assert isinstance(reliability, dict)
        # Some hub candidate works, and every consumer works: independent events.
        expected = (1 - math.prod(HUB_P)) * (1 - CONSUMER_P) ** m
        assert reliability["probability"] == pytest.approx(expected, rel=1e-9)
        assert str(reliability["method"]).startswith("exact")
        peaks[m] = peak
    # KiB. The library grows by about 15 MB per 1,000 roles; before, 4x the roles cost 4x^2.
    assert peaks[2000] < peaks[500] + 60 * 1024, peaks


def test_simulate_json_memory_does_not_grow_with_the_document(tmp_path: Path) -> None:
    """Case S13: --limit 10000 of 1,000 roles took 3.0 GB for a 699 MB document.

    The document was held three times (pieces, their join, the whole) and every configuration
    held its own copy of each (role, component) pair; now each is written as it is made.
    """
    subprocess.run(
        [sys.executable, "-m", "rosreconf", "generate", "--roles", "400", "--candidates", "2",
         "--dynamics", "-o", str(tmp_path)],
        check=True, capture_output=True,
    )  # fmt: skip
    schema = json.loads(
        (Path(__file__).parent.parent / "rosreconf/data/output-simulate.schema.json").read_text()
    )
    peaks, sizes = {}, {}
    for n in (300, 1200):
        argv = ["simulate", "--workers", "1", "--json", "--limit", str(n),
                "-l", str(tmp_path / "libraries"), "-s", str(tmp_path / "schemas")]  # fmt: skip
        code, peak, out, err = measured(argv)
        assert code in (0, 1), err
        doc = json.loads(out)
        jsonschema_rs.validate(schema, doc)  # the published schema, checked in Rust: fast
        [simulated] = doc["schemas"]
        assert len(simulated["configurations"]) == simulated["configurations_simulated"] == n
        assert len(simulated["configurations"][0]["assignment"]) == 400
        peaks[n], sizes[n] = peak, len(out)
    assert sizes[1200] > sizes[300] + 20_000_000  # the document grows by 27 MB ...
    assert peaks[1200] < peaks[300] + 30 * 1024, peaks  # ... memory did by 99 MB (KiB)


def test_out_of_memory_is_exit_3_with_one_line_and_no_file(tmp_path: Path) -> None:
    """Out of memory was a MemoryError traceback and exit 1 ("the check failed")."""
    out = tmp_path / "out"
    # 200,000 components need about 550 MB; 400 MB is enough to start, not to finish.
    code, _, stdout, stderr = measured(
        ["generate", "--roles", "200000", "--candidates", "1", "-o", str(out)], cap=400_000_000
    )
    assert code == 3, stderr
    assert stderr.startswith("rosreconf: error: out of memory")
    assert "Traceback" not in stderr and len(stderr.splitlines()) == 1
    assert stdout == ""
    assert not list(out.rglob("*.yaml"))
