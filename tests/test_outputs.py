"""Output files (issue 10 item 2): write atomically, never destroy what is not ours.

Every command with ``-o`` goes through ``rosreconf.outfiles.output_target``: a regular file or
a new path is replaced atomically and keeps its mode, a symlink is written through, ``-`` is
stdout, and devices, FIFOs, folders and symlink loops are refused with exit 2.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import UsageError
from rosreconf.outfiles import TargetKind, output_target, write_atomic, write_files_atomic
from rosreconf.planning.pddl import PddlTask
from rosreconf.planning.pddl_names import PddlNames
from rosreconf.planning.replan import write_task

SCHEMA = "object_repositioning"
GRAPH = ["graph", "--only", SCHEMA, "--view", "system", "--format", "dot", "-o"]


def _device(tmp_path: Path) -> Path:
    """Return a character device to aim at: a private copy of /dev/full when we may make one.

    As root, the defect replaced the device node itself; a test must not risk the real one.
    """
    if os.geteuid() != 0:
        return Path("/dev/full")  # a failing run cannot replace it without root
    node = tmp_path / "full"
    os.mknod(node, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
    return node


def test_a_character_device_is_refused_and_left_a_device(runner: CliRunner, tmp_path: Path) -> None:
    device = _device(tmp_path)
    result = runner.invoke(app, [*GRAPH, str(device)])
    assert result.exit_code == 2, result.output
    assert f"{device}: is a character device" in result.stderr
    assert stat.S_ISCHR(os.stat(device).st_mode)


def test_a_fifo_is_refused_and_stays_a_fifo(runner: CliRunner, tmp_path: Path) -> None:
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    result = runner.invoke(app, [*GRAPH, str(fifo)])
    assert result.exit_code == 2 and "is a FIFO" in result.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_symlink_is_written_through(runner: CliRunner, tmp_path: Path) -> None:
    real = tmp_path / "real.dot"
    real.write_text("old")
    link = tmp_path / "link.dot"
    link.symlink_to(real)
    result = runner.invoke(app, [*GRAPH, str(link)])
    assert result.exit_code == 0, result.output
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert real.read_text().startswith("digraph")


def test_a_private_file_keeps_its_mode(runner: CliRunner, tmp_path: Path) -> None:
    secret = tmp_path / "secret.dot"
    secret.write_text("old")
    secret.chmod(0o600)
    result = runner.invoke(app, [*GRAPH, str(secret)])
    assert result.exit_code == 0, result.output
    assert stat.S_IMODE(secret.stat().st_mode) == 0o600
    assert secret.read_text().startswith("digraph")


def test_dash_writes_to_stdout(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, [*GRAPH, "-"])
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("digraph") and "wrote stdout" in result.stderr
    assert not (tmp_path / "-").exists()


def test_a_file_name_is_printed_as_written(runner: CliRunner, tmp_path: Path) -> None:
    """Names are the user's: rich must not turn ``:warning:`` in a path into an emoji."""
    target = tmp_path / "a:warning:b.dot"
    result = runner.invoke(app, [*GRAPH, str(target)])
    assert result.exit_code == 0, result.output
    assert f"wrote {target}" in result.stderr
    assert "\u26a0" not in result.stderr


@pytest.mark.parametrize("given", ["", "loop"])
def test_empty_names_and_symlink_loops_say_what_is_wrong(tmp_path: Path, given: str) -> None:
    if given:
        os.symlink(tmp_path / "loop", tmp_path / "loop")
        given = str(tmp_path / "loop")
    with pytest.raises(UsageError, match=r"empty|symlink loop"):
        output_target(given)


def test_a_folder_is_refused_as_a_file(tmp_path: Path) -> None:
    with pytest.raises(UsageError, match="is a folder"):
        write_atomic(tmp_path, "x")
    assert output_target(tmp_path / "new.dot").kind is TargetKind.NEW


@pytest.mark.parametrize("command", ["render-pddl", "generate"])
@pytest.mark.parametrize("given", ["file", ""])
def test_a_file_as_output_folder_is_a_usage_error(
    runner: CliRunner, tmp_path: Path, command: str, given: str
) -> None:
    path = tmp_path / "afile"
    path.write_text("mine")
    args = [command, "-o", str(path) if given else ""]
    if command == "generate":
        args += ["-r", "4", "-k", "2"]
    result = runner.invoke(app, args)
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert ("is a regular file, not a folder" if given else "name is empty") in result.stderr
    assert path.read_text() == "mine"


def _task(run: int) -> PddlTask:
    return PddlTask(
        f"; domain of run {run}\n" * 2000, f"; problem of run {run}\n" * 2000, PddlNames(), "s"
    )


def test_concurrent_writes_never_mix_a_domain_and_a_problem(tmp_path: Path) -> None:
    mixed = []
    for attempt in range(10):
        folder = tmp_path / str(attempt)
        barrier = threading.Barrier(4)

        def run(n: int, folder: Path = folder, barrier: threading.Barrier = barrier) -> None:
            barrier.wait()
            write_task(_task(n), folder)

        threads = [threading.Thread(target=run, args=(n,)) for n in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        domain = (folder / "s" / "domain.pddl").read_text().split("\n")[0]
        problem = (folder / "s" / "problem.pddl").read_text().split("\n")[0]
        if domain.rsplit(" ", 1)[1] != problem.rsplit(" ", 1)[1]:
            mixed.append(attempt)
    assert mixed == []


def test_a_pair_replaces_the_old_one_and_keeps_foreign_files(tmp_path: Path) -> None:
    folder = tmp_path / "out"
    write_files_atomic(folder, {"domain.pddl": "a", "problem.pddl": "a"})
    (folder / "notes.txt").write_text("mine")
    write_files_atomic(folder, {"domain.pddl": "b", "problem.pddl": "b"})
    assert sorted(p.name for p in folder.iterdir()) == ["domain.pddl", "notes.txt", "problem.pddl"]
    assert (folder / "domain.pddl").read_text() == "b" and (
        folder / "notes.txt"
    ).read_text() == "mine"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # no temp folder left


@pytest.mark.parametrize(
    ("name", "fd"),
    [
        ("/dev/stdout", 1),
        ("/dev/fd/1", 1),
        ("/proc/self/fd/1", 1),
        ("/dev/stderr", 2),
        ("/dev/fd/2", 2),
        ("/proc/self/fd/2", 2),
        ("log", 1),  # the log's own name while stdout goes to it: the same file
    ],
)
def test_dev_stdout_appended_to_a_log_keeps_the_log(tmp_path: Path, name: str, fd: int) -> None:
    # ``-o /dev/stdout >> log``: the old code wrote a temp file beside the log and renamed
    # it over the log, so the log's earlier lines were lost.
    log = tmp_path / "log"
    log.write_text("earlier line\n")
    with open(log, "ab") as appended, open(os.devnull, "wb") as other:
        streams = (
            {"stdout": appended, "stderr": other}
            if fd == 1
            else {"stdout": other, "stderr": appended}
        )
        done = subprocess.run(
            [sys.executable, "-m", "rosreconf", *GRAPH, name], cwd=tmp_path, check=False, **streams
        )
    assert done.returncode == 0
    text = log.read_text()
    assert text.startswith("earlier line\ndigraph ")  # kept, then the picture appended
    assert text.count("digraph ") == 1 and "\n}\n" in text  # once, whole
    assert sorted(p.name for p in tmp_path.iterdir()) == ["log"]  # no temp file left beside it


def test_a_symlink_to_dev_stdout_is_the_stream(tmp_path: Path) -> None:
    (tmp_path / "out").symlink_to("/dev/stdout")
    done = subprocess.run(
        [sys.executable, "-m", "rosreconf", *GRAPH, "out"], cwd=tmp_path, capture_output=True,
        text=True, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("digraph ")  # written into the pipe, not refused as a FIFO
    assert (tmp_path / "out").is_symlink()
