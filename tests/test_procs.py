"""Tests for rosreconf.procs: limits, timeouts and interrupts must leave no process or dir."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from conftest import FAKE_START_SECONDS, LOADED_MACHINE_SLACK, fake, read_report, wait_until_gone

from rosreconf.errors import ExternalToolError
from rosreconf.procs import (
    GRACE_SECONDS,
    MISSING_RETURNCODE,
    Background,
    Terminated,
    clean_stale_workdirs,
    private_workdir,
    run_program,
    start_program,
)
from rosreconf.procs.workdirs import MARKER, STALE_AFTER_SECONDS

PY = sys.executable


def test_captures_output_exit_code_and_time() -> None:
    code = "import sys; print('out'); print('err', file=sys.stderr); sys.exit(3)"
    result = run_program([PY, "-c", code], timeout=10)
    assert (result.returncode, result.stdout, result.stderr) == (3, "out\n", "err\n")
    assert not result.ok and not result.timed_out and not result.missing
    assert 0 < result.elapsed < 10


def test_arguments_are_never_interpreted_by_a_shell(tmp_path: Path) -> None:
    trap = f"$(touch {tmp_path}/pwned); echo hi > {tmp_path}/pwned2"
    result = run_program([PY, "-c", "import sys; print(sys.argv[1])", trap], timeout=10)
    assert result.stdout == trap + "\n"
    assert list(tmp_path.iterdir()) == []


def test_runs_in_a_new_session_with_stdin_cwd_and_env(tmp_path: Path) -> None:
    code = (
        "import os, sys; data = sys.stdin.read();"
        "print(os.getsid(0) == os.getpid(), os.getcwd(), os.environ['ROSRECONF_X'], data)"
    )
    env = {**os.environ, "ROSRECONF_X": "42"}
    result = run_program([PY, "-c", code], timeout=10, cwd=tmp_path, stdin=b"fed", env=env)
    assert result.stdout.split() == ["True", str(tmp_path), "42", "fed"]


def test_stdin_is_empty_by_default() -> None:
    result = run_program([PY, "-c", "import sys; print(repr(sys.stdin.read()))"], timeout=10)
    assert result.stdout == "''\n"


def test_a_missing_program_is_a_result_and_check_raises() -> None:
    result = run_program(["rosreconf-no-such-program"], timeout=10)
    assert result.missing and result.returncode == MISSING_RETURNCODE
    with pytest.raises(ExternalToolError, match="rosreconf-no-such-program was not found"):
        result.check()


def test_a_missing_working_directory_raises(tmp_path: Path) -> None:
    with pytest.raises(ExternalToolError, match="no directory"):
        run_program([PY, "-c", "pass"], timeout=10, cwd=tmp_path / "absent")


def test_check_names_the_failure() -> None:
    ok = run_program([PY, "-c", "pass"], timeout=10)
    assert ok.check() is ok
    failed = run_program([PY, "-c", "import sys; sys.exit('bad input')"], timeout=10)
    with pytest.raises(ExternalToolError, match="exit code 1: bad input"):
        failed.check()


def test_output_keeps_only_the_tail() -> None:
    code = "print('x' * 300000); print('THE END')"
    result = run_program([PY, "-c", code], timeout=10, max_output_bytes=1000)
    assert result.truncated and len(result.stdout) == 1000
    assert result.stdout.endswith("THE END\n")


def test_memory_limit_makes_allocation_fail() -> None:
    code = "bytearray(600 << 20)"
    assert run_program([PY, "-c", code], timeout=20).returncode == 0
    limited = run_program([PY, "-c", code], timeout=20, memory_limit_mb=300)
    assert limited.returncode == 1 and "MemoryError" in limited.stderr


def test_cpu_limit_sends_sigxcpu() -> None:
    # One CPU second, not the wall-clock limit, ends it: under nice on a loaded machine one CPU
    # second can take a minute of wall-clock time, so the limit is far away.
    result = run_program([PY, "-c", "while True: pass"], timeout=120, cpu_limit_s=1)
    assert result.signal is signal.SIGXCPU and not result.timed_out


def test_timeout_kills_the_whole_group_even_a_child_ignoring_sigterm(report: Path) -> None:
    start = time.monotonic()
    result = run_program(fake("fork_ignore_term.py"), timeout=FAKE_START_SECONDS)
    assert result.timed_out and not result.ok
    # The fake hangs forever: returning at all proves the kill; the bound leaves room for a
    # loaded machine (2 cores shared with other jobs) without letting a hang pass.
    assert time.monotonic() - start < FAKE_START_SECONDS + GRACE_SECONDS + LOADED_MACHINE_SLACK
    facts = read_report(report)
    assert len(facts["pids"]) == 2 and facts["pids"][0] == facts["pgid"]
    assert wait_until_gone(facts["pgid"]) == []


def test_a_child_left_behind_by_a_finished_program_is_killed(
    report: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FAKE_PARENT_EXITS", "1")
    result = run_program(fake("fork_ignore_term.py"), timeout=10)
    assert result.returncode == 0 and not result.timed_out
    # Did not wait for the child, which holds stdout open forever (that would end in the timeout).
    assert result.elapsed < 10
    assert wait_until_gone(read_report(report)["pgid"]) == []


@pytest.mark.parametrize(
    ("sig", "raised"), [(signal.SIGINT, KeyboardInterrupt), (signal.SIGTERM, Terminated)]
)
def test_an_interrupt_kills_the_group_and_removes_the_workdir(
    report: Path, signal_when_started: Any, tmp_path: Path, sig: signal.Signals, raised: type
) -> None:
    parent = tmp_path / "work"
    parent.mkdir()
    signal_when_started(sig)
    with pytest.raises(raised), private_workdir(parent) as workdir:
        run_program(fake("fork_ignore_term.py"), timeout=30, cwd=workdir)
    facts = read_report(report)
    assert facts["cwd"] == str(workdir)
    assert wait_until_gone(facts["pgid"]) == []
    assert list(parent.iterdir()) == []
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # the handler was put back


def test_terminated_exits_like_sigterm() -> None:
    assert issubclass(Terminated, SystemExit)
    assert Terminated(143).code == 128 + signal.SIGTERM


def test_private_workdir_is_private_and_removed_on_success_and_error(tmp_path: Path) -> None:
    with private_workdir(tmp_path) as workdir:
        assert stat.S_IMODE(workdir.stat().st_mode) == 0o700
        (workdir / "sub").mkdir()
        (workdir / "sub" / "file").write_text("x")
    assert not workdir.exists()
    with pytest.raises(RuntimeError), private_workdir(tmp_path) as workdir:
        raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []


def test_bad_arguments_are_programming_errors() -> None:
    with pytest.raises(ValueError):
        run_program([], timeout=1)
    with pytest.raises(ValueError):
        run_program([PY, "-c", "pass"], timeout=0)


def _killed_rosreconf(report: Path, workdir_parent: Path) -> dict[str, Any]:
    """Start a Python running rosreconf's run_program in a private workdir; SIGKILL it.

    Returns what the fake program (which forks a child ignoring SIGTERM, like Fast
    Downward's driver forks its search) reported about its group.
    """
    code = (
        "import sys; from pathlib import Path;"
        "from rosreconf.procs import private_workdir, run_program;"
        "cm = private_workdir(Path(sys.argv[2])); w = cm.__enter__();"
        "(w / 'output.sas').write_bytes(b'x' * 4096);"
        "run_program([sys.executable, sys.argv[1]], timeout=60, cwd=w)"
    )
    argv = [PY, "-c", code, fake("fork_ignore_term.py")[1], str(workdir_parent)]
    facts = _sigkill_after_report(argv, report)
    return facts


def test_the_group_dies_with_rosreconf_even_under_sigkill(report: Path, tmp_path: Path) -> None:
    facts = _killed_rosreconf(report, tmp_path)
    assert len(facts["pids"]) == 2  # the program and the child it forked
    assert wait_until_gone(facts["pgid"], seconds=5) == []


def test_a_killed_runs_temp_dir_is_removed_by_the_next_run(report: Path, tmp_path: Path) -> None:
    foreign = [
        tmp_path / "rosreconf-notapid-x",
        tmp_path / "other-1-x",
        tmp_path / f"rosreconf-{os.getpid()}-live",
    ]
    for path in foreign:
        path.mkdir()
    _killed_rosreconf(report, tmp_path)
    stale = [p for p in tmp_path.iterdir() if p.is_dir() and p not in foreign]
    assert len(stale) == 1 and (stale[0] / "output.sas").exists()
    age(stale[0] / MARKER, STALE_AFTER_SECONDS + 1)
    removed = clean_stale_workdirs(tmp_path)
    assert removed == stale and not stale[0].exists()
    assert all(p.is_dir() for p in foreign)  # not ours, or its owner is alive


def age(path: Path, seconds: float) -> None:
    """Make ``path`` look ``seconds`` old (its modification time)."""
    then = time.time() - seconds
    os.utime(path, (then, then))


def dead_pid() -> int:
    """Return the pid of a process that has ended (and been reaped)."""
    probe = subprocess.Popen([PY, "-c", "pass"])
    probe.wait()
    return probe.pid


def test_a_user_folder_named_like_a_temp_dir_of_a_dead_pid_is_never_removed(
    tmp_path: Path,
) -> None:
    # ``generate -o $TMPDIR/rosreconf-<n>-10``: the old cleanup removed it, content and all.
    pid = dead_pid()
    made = subprocess.run(
        [PY, "-m", "rosreconf", "generate", "--roles", "2", "--candidates", "1",
         "-o", str(tmp_path / f"rosreconf-{pid}-10")],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert made.returncode == 0, made.stderr
    users = tmp_path / f"rosreconf-{pid}-10"
    age(users, STALE_AFTER_SECONDS + 1)
    assert clean_stale_workdirs(tmp_path) == []
    assert (users / "libraries" / "generated.yaml").is_file()


def test_a_stale_temp_dir_is_removed_only_with_our_marker_for_its_pid_and_old_enough(
    tmp_path: Path,
) -> None:
    pid = dead_pid()
    text = f"rosreconf temp dir of process {pid}; removed when that process is gone\n"
    cases = {
        "ours": (text, STALE_AFTER_SECONDS + 1),
        "young": (text, 0.0),
        "other-pid": (text.replace(str(pid), str(pid + 1)), STALE_AFTER_SECONDS + 1),
        "no-marker": (None, STALE_AFTER_SECONDS + 1),
    }
    for name, (marker, seconds) in cases.items():
        folder = tmp_path / f"rosreconf-{pid}-{name}"
        folder.mkdir()
        (folder / "keep.txt").write_text("user data")
        if marker is not None:
            (folder / MARKER).write_text(marker)
            age(folder / MARKER, seconds)
    assert clean_stale_workdirs(tmp_path) == [tmp_path / f"rosreconf-{pid}-ours"]
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == [f"rosreconf-{pid}-{n}" for n in ("no-marker", "other-pid", "young")]


def test_a_private_workdir_carries_the_marker_of_its_process(tmp_path: Path) -> None:
    with private_workdir(tmp_path) as work:
        assert work.name.startswith(f"rosreconf-{os.getpid()}-")
        assert (work / MARKER).read_text() == (
            f"rosreconf temp dir of process {os.getpid()}; removed when that process is gone\n"
        )
    assert list(tmp_path.iterdir()) == []


def test_new_output_gives_each_part_of_the_log_once_and_only_its_tail(tmp_path: Path) -> None:
    log = tmp_path / "prog.log"
    code = "import time; print('a' * 50, flush=True); time.sleep(30)"
    prog = start_program([sys.executable, "-c", code], log=log)
    try:
        deadline = time.monotonic() + 10
        while log.stat().st_size < 51 and time.monotonic() < deadline:
            time.sleep(0.02)
        assert prog.new_output(limit=10) == "a" * 9 + "\n"
        assert prog.new_output() == ""
        with log.open("a") as f:
            f.write("ERROR: more\n")
        assert prog.new_output() == "ERROR: more\n"
    finally:
        prog.stop(grace=1.0)
    assert Background(("x",), prog.process).new_output() == ""  # no log known


# --- rosreconf started with SIGINT ignored (a background job of a script) --------------------


@pytest.fixture
def sigint_ignored() -> Iterator[None]:
    """Ignore SIGINT in this test process, as a shell does for a background job."""
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


SIGINT_IGNORED = "import signal; print(signal.getsignal(signal.SIGINT) is signal.SIG_IGN)"


@pytest.mark.parametrize("limits", [{}, {"memory_limit_mb": 1024, "cpu_limit_s": 60}])
def test_a_program_gets_sigint_back_when_rosreconf_ignores_it(
    sigint_ignored: None, limits: dict[str, int]
) -> None:
    assert run_program([PY, "-c", SIGINT_IGNORED], timeout=10, **limits).stdout == "False\n"


def test_a_background_program_stops_on_sigint_when_rosreconf_ignores_it(
    sigint_ignored: None, tmp_path: Path
) -> None:
    log = tmp_path / "log"
    code = "import time; print('up', flush=True); time.sleep(60)"
    program = start_program([PY, "-c", code], log=log)
    deadline = time.monotonic() + 10
    while "up" not in log.read_text() and time.monotonic() < deadline:
        time.sleep(0.01)
    # Stopped by the SIGINT itself (Python re-raises it to die), not by the SIGKILL after grace.
    assert program.stop(grace=20, sig=signal.SIGINT) == -signal.SIGINT


def test_the_interrupt_tests_pass_when_pytest_runs_as_a_background_job() -> None:
    # A shell starts a background job with SIGINT ignored; the tests that send themselves a
    # SIGINT must still see their KeyboardInterrupt (conftest.signal_when_started).
    tests = Path(__file__).parent
    argv = [PY, "-m", "pytest", "-q", "-p", "no:cacheprovider",
            "-k", "interrupt_kills_the_group or interrupted_solve_kills",
            str(tests / "test_procs.py"), str(tests / "test_planners.py")]  # fmt: skip
    done = subprocess.run(
        argv,
        cwd=tests.parent,
        capture_output=True,
        text=True,
        # a bound against a hang only: the inner run takes 12 s here alone, and 112 s (4
        # passed) beside two clones' suites on two cores (fc100), past the 120 s it had
        timeout=600,
        check=False,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN),
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "4 passed" in done.stdout


def test_a_background_programs_group_dies_with_rosreconf_even_under_sigkill(
    report: Path, tmp_path: Path
) -> None:
    """What roslaunch and ROS 2 nodes run as (start_program): gone when rosreconf is killed.

    Issue 22: SIGKILL of ``watch`` left roslaunch and its 13 stand-ins running.
    """
    code = (
        "import sys, time; from pathlib import Path;"
        "from rosreconf.procs import start_program;"
        "start_program([sys.executable, sys.argv[1]], log=Path(sys.argv[2]));"
        "time.sleep(60)"
    )
    argv = [PY, "-c", code, fake("fork_ignore_term.py")[1], str(tmp_path / "out.log")]
    facts = _sigkill_after_report(argv, report)
    assert len(facts["pids"]) == 2  # the program and the child it forked
    assert wait_until_gone(facts["pgid"], seconds=5) == []


def _sigkill_after_report(argv: list[str], report: Path) -> dict[str, Any]:
    """Run ``argv``, wait (20 s at most) for the fake's report, SIGKILL it, return the report.

    SIGKILL: no finally block and no signal handler of the parent runs, so what survives it is
    what the parent-death handling alone left alive.
    """
    parent = subprocess.Popen(argv)
    deadline = time.monotonic() + 20
    while not report.exists() and time.monotonic() < deadline:
        time.sleep(0.02)
    facts = read_report(report)
    parent.kill()
    parent.wait()
    return facts
