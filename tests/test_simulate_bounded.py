"""simulate is bounded by default and says so (issue 22).

Without ``--limit`` a schema of 10^97 configurations grew to 6.7 GB in two minutes, with no
warning. Now at most 1000 configurations per schema are simulated unless ``--limit`` says
otherwise, and the output says when there were more.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from rosreconf.analysis.simulate import DEFAULT_LIMIT, simulate_schema
from rosreconf.formats.loader import load_bundled

CAP = 4_000_000_000
"""Address-space cap of the child process (bytes)."""


def _simulate(folder: Path, *extra: str) -> subprocess.CompletedProcess[str]:
    argv = [sys.executable, "-m", "rosreconf", "simulate", "--workers", "1", "--json",
            "-l", str(folder / "libraries"), "-s", str(folder / "schemas"), *extra]  # fmt: skip
    return subprocess.run(
        ["prlimit", f"--as={CAP}", "--", "timeout", "300", *argv],
        capture_output=True, text=True, check=False,
    )  # fmt: skip


def test_simulate_on_hundreds_of_millions_of_configurations_stops_at_the_default_limit(
    tmp_path: Path,
) -> None:
    """Case: simulate without --limit on 10^97 configurations grew without bound."""
    subprocess.run(
        [sys.executable, "-m", "rosreconf", "generate", "--roles", "16", "--candidates", "4",
         "--dynamics", "-o", str(tmp_path)],
        check=True, capture_output=True,
    )  # fmt: skip
    done = _simulate(tmp_path)
    assert done.returncode in (0, 1), done.stderr
    [schema] = json.loads(done.stdout)["schemas"]
    assert schema["limited"] is True
    assert schema["configurations_simulated"] == len(schema["configurations"]) == DEFAULT_LIMIT
    done = _simulate(tmp_path, "--limit", "40")
    [schema] = json.loads(done.stdout)["schemas"]
    assert (schema["limited"], schema["configurations_simulated"]) == (True, 40)
    table = subprocess.run(
        [sys.executable, "-m", "rosreconf", "simulate", "--workers", "1", "--limit", "40",
         "-l", str(tmp_path / "libraries"), "-s", str(tmp_path / "schemas")],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert "only the first 40 valid configurations were simulated" in " ".join(table.stdout.split())


def test_a_limit_at_the_number_of_configurations_is_not_said_to_have_stopped_the_listing() -> None:
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "indoor_navigation")
    everything = simulate_schema(loaded.library, schema)
    n = len(everything.configurations)
    assert not everything.limited
    assert not simulate_schema(loaded.library, schema, limit=n).limited
    fewer = simulate_schema(loaded.library, schema, limit=n - 1)
    assert fewer.limited and len(fewer.configurations) == n - 1
