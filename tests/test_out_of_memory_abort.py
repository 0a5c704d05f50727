"""Dying of memory in C++ under a cap is exit 3 with rosreconf's own line (issue 32, S13).

Under ``prlimit --as`` a run died inside clingo: "error in SolveEventHandler::on_statistics
going to terminate", SIGABRT, no word from rosreconf. Where an allocation fails inside clingo
cannot be chosen from outside, so the abort is provoked: SIGABRT, as ``abort()`` raises it, is
sent to the process that runs the verb while it writes its JSON document to a file. The
reference is what a user sees: the exit status, stderr, and stdout (empty, never half a
document). The second test holds that the signals ``watch`` answers with 130/143 still work.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rosreconf.cli.capped import OUT_OF_MEMORY
from rosreconf.procs.signals import sigint_default  # as in a terminal, not a background job

CAP = 4_000_000_000
"""Address-space cap (bytes): a cap in force, larger than the runs here need."""


def _verb_pid(wrapper: subprocess.Popen[bytes], out: Path) -> int:
    """Return the pid of the process running the verb, once its output has begun."""
    deadline = time.monotonic() + 120
    while True:
        assert wrapper.poll() is None, "the run ended before its output began"
        assert time.monotonic() < deadline, "no output within 120 s"
        children = Path(f"/proc/{wrapper.pid}/task/{wrapper.pid}/children").read_text().split()
        if out.stat().st_size > 0:
            return int(children[0]) if children else wrapper.pid
        time.sleep(0.05)


def _start(tmp_path: Path, out: Path) -> subprocess.Popen[bytes]:
    subprocess.run(
        [sys.executable, "-m", "rosreconf", "generate", "--roles", "16", "--candidates", "4",
         "-o", str(tmp_path)],
        check=True, capture_output=True,
    )  # fmt: skip
    argv = [sys.executable, "-m", "rosreconf", "enumerate", "--json", "--limit", "1000000",
            "-l", str(tmp_path / "libraries"), "-s", str(tmp_path / "schemas")]  # fmt: skip
    with out.open("wb") as stdout:
        # prlimit sets the cap on itself, then execs Python: the run's pid is prlimit's
        return subprocess.Popen(["prlimit", f"--as={CAP}", "--", *argv], stdout=stdout,
                                stderr=subprocess.PIPE, preexec_fn=sigint_default())  # fmt: skip


def test_an_abort_under_a_memory_cap_is_exit_3_with_one_line(tmp_path: Path) -> None:
    out = tmp_path / "out.json"
    run = _start(tmp_path, out)
    try:
        os.kill(_verb_pid(run, out), signal.SIGABRT)  # what clingo's std::terminate raises
        _, err = run.communicate(timeout=60)
    finally:
        run.kill()
    assert run.returncode == 3, err  # before: -6 (killed by SIGABRT), no message
    assert err.decode().splitlines() == [OUT_OF_MEMORY]
    assert out.read_bytes() == b""  # not half a document


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_capped_run_still_stops_on_sigterm_and_sigint(
    sig: signal.Signals, tmp_path: Path
) -> None:
    out = tmp_path / "out.json"
    run = _start(tmp_path, out)
    try:
        _verb_pid(run, out)
        run.send_signal(sig)  # to the pid the user started
        _, err = run.communicate(timeout=60)
    finally:
        run.kill()
    assert run.returncode in (128 + sig, -sig), err  # as uncapped: 130 (said), or the signal
    assert b"Traceback" not in err
    assert OUT_OF_MEMORY.encode() not in err


def test_a_memory_error_leaves_no_half_document_in_a_file(tmp_path: Path) -> None:
    """Case: enumerate --json of 12,000 components under a 300 MB cap ran out of memory after
    writing 5,824 bytes of its document (exit 3, stdout not JSON)."""
    subprocess.run(
        [sys.executable, "-m", "rosreconf", "generate", "--roles", "600", "--candidates", "20",
         "-o", str(tmp_path)],
        check=True, capture_output=True,
    )  # fmt: skip
    out = tmp_path / "out.json"
    argv = [sys.executable, "-m", "rosreconf", "enumerate", "--json", "--limit", "3",
            "-l", str(tmp_path / "libraries"), "-s", str(tmp_path / "schemas")]  # fmt: skip
    with out.open("wb") as stdout:
        done = subprocess.run(["prlimit", "--as=300000000", "--", *argv], stdout=stdout,
                              stderr=subprocess.PIPE, timeout=300, check=False)  # fmt: skip
    assert done.returncode == 3, done.stderr
    assert done.stderr.decode().splitlines() == [OUT_OF_MEMORY]
    assert out.read_bytes() == b""
