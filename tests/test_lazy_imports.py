"""Commands that do not simulate never import the simulation's heavy libraries.

python-control, scipy and matplotlib cost seconds of CPU to import (python-control alone
imports scipy.signal, scipy.stats and matplotlib.pyplot); ``validate``, ``enumerate`` and
``--help`` run in editors' save hooks and CI steps and must not pay for them, and
``simulate`` and ``plan`` simulate on numpy alone. Each command
runs in a fresh interpreter, as a user runs it, and reports the modules it ended with.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

HEAVY = ("control", "scipy", "matplotlib", "distributed", "dask")
"""Top-level packages no command imports unless asked to draw (--plot) or to use a cluster."""

PROBE = """
import json, runpy, sys
sys.argv = ["rosreconf", *sys.argv[2:]]  # -c puts "-c" first, then "rosreconf"
try:
    runpy.run_module("rosreconf", run_name="__main__", alter_sys=True)
except SystemExit as exc:
    code = exc.code
else:
    code = 0
with open(OUT, "w") as out:
    json.dump({"code": code, "modules": sorted(sys.modules)}, out)
"""


def loaded(tmp_path: Path, *args: str) -> tuple[object, set[str]]:
    """Run ``rosreconf ARGS`` in a fresh interpreter; return its exit code and top modules."""
    out = tmp_path / "modules.json"
    probe = PROBE.replace("OUT", repr(str(out)))
    subprocess.run(
        [sys.executable, "-c", probe, "rosreconf", *args],
        cwd=tmp_path,  # an empty folder: the bundled example
        capture_output=True,
        check=False,
        timeout=120,
    )
    doc = json.loads(out.read_text())
    return doc["code"], {name.split(".")[0] for name in doc["modules"]}


@pytest.mark.parametrize(
    "args",
    [
        ["--help"],
        ["validate"],
        ["validate", "--format", "json"],
        ["enumerate"],
        ["enumerate", "--json"],
        ["simulate", "--help"],
    ],
)
def test_commands_that_do_not_simulate_import_no_heavy_library(
    tmp_path: Path, args: list[str]
) -> None:
    code, modules = loaded(tmp_path, *args)
    assert code in (0, None), (args, code)
    assert not modules & set(HEAVY), sorted(modules & set(HEAVY))


@pytest.mark.parametrize(
    "args",
    [
        ["simulate", "--only", "indoor_navigation", "--workers", "1"],
        ["simulate", "--only", "object_repositioning", "--workers", "1", "--json"],
        ["plan", "--fail", "NSM3"],  # simulates the fewest-change configuration
    ],
)
def test_commands_that_simulate_import_numpy_but_not_scipy(tmp_path: Path, args: list[str]) -> None:
    """The loops are simulated on numpy alone (``analysis.matfuncs``, issue 12).

    numpy in the list shows the probe saw the simulation run; scipy.linalg (0.15 s of CPU
    per process) is the tests' reference only, python-control and matplotlib never load.
    """
    code, modules = loaded(tmp_path, *args)
    assert code in (0, 1), (args, code)
    assert "numpy" in modules
    assert not modules & set(HEAVY), sorted(modules & set(HEAVY))
