"""A Ctrl-C that Python drops still ends rosreconf, at once, with one line.

Python cannot raise a signal's exception out of a finalizer, a weakref callback or a garbage
collector callback: it prints "Exception ignored in ..." and goes on. Fresh clone fc166: a
SIGINT to ``enumerate --json --limit 1000000`` landed in an import's module-lock callback
(``_get_module_lock.<locals>.cb``), and the run was still going 60 s later. The moment cannot
be hit on demand, so a **fake, named as one**, provokes it: a garbage collector callback that
sends the signal and waits in itself, so that the exception is raised, and dropped, there.
"""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import LOADED_MACHINE_SLACK

from rosreconf.procs.signals import sigint_default

DROPPED = """\
# A FAKE moment: the stop lands inside a garbage collector callback, where Python drops it.
import gc, os, runpy, signal, sys, time

seen = []


def stop_here(phase, info):
    seen.append(phase)
    if len(seen) == 200:
        os.kill(os.getpid(), {sig})
        time.sleep(10)  # the exception is raised in here, and dropped


gc.callbacks.append(stop_here)
sys.argv[0] = "rosreconf"
runpy.run_module("rosreconf", run_name="__main__")
"""


@pytest.fixture(scope="module")
def big(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A generated library with 4**16 configurations: enumerating a million takes minutes."""
    where = tmp_path_factory.mktemp("big")
    subprocess.run(
        [sys.executable, "-m", "rosreconf", "generate", "--roles", "16", "--candidates", "4",
         "-o", str(where)],
        check=True, capture_output=True,
    )  # fmt: skip
    return where


def test_a_ctrl_c_python_drops_still_ends_the_run_with_one_line(big: Path, tmp_path: Path) -> None:
    out = tmp_path / "out.json"
    fake = DROPPED.format(sig=int(signal.SIGINT))
    argv = [sys.executable, "-c", fake, "enumerate", "--json", "--limit", "1000000",
            "-l", str(big / "libraries"), "-s", str(big / "schemas")]  # fmt: skip
    with out.open("wb") as stdout:  # SIGINT's default action, as in a terminal
        run = subprocess.Popen(argv, stdout=stdout, stderr=subprocess.PIPE,
                               preexec_fn=sigint_default())  # fmt: skip
    try:
        _, err = run.communicate(timeout=LOADED_MACHINE_SLACK)
    finally:
        run.kill()
        run.wait()
    assert run.returncode == 130, err  # before: still enumerating after the test's 20 s
    assert err.decode() == "rosreconf: interrupted\n"
    assert out.read_bytes() == b""  # no half document
