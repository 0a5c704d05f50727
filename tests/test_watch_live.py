"""``Watcher`` on a real ROS 1 master: a master that restarts, and a roslaunch that fails.

A restarted master lists none of the nodes registered with the old one (ROS 1 nodes do not
register again), which is not the same as every node failing. And when roslaunch cannot start
a node (here: the robot's real packages are not installed), its own error must be shown and
its launch file and output kept. Everything started is stopped; the master fixture asserts
that no process is left.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

import pytest
import ros_harness
from conftest import FAKES, StartStandIn
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import ExternalToolError
from rosreconf.formats.loader import load_bundled
from rosreconf.model import Configuration
from rosreconf.ros.options import WatchOptions
from rosreconf.ros.ros1.source import MasterSource
from rosreconf.ros.ros1.standins import standin_spec
from rosreconf.ros.watcher import Event, Watcher

pytestmark = pytest.mark.ros

SCHEMA = "object_repositioning"


def _watcher(
    master: ros_harness.Master, tmp_path: Path, events: list[Event], **kw: object
) -> Watcher:
    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == SCHEMA)
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    work = tmp_path / "work"
    work.mkdir()
    source = MasterSource(master.uri)
    return Watcher(
        source, bundle.library, schema, nominal, work, master.env(), events.append,
        WatchOptions(**{"apply": True, **kw}),  # type: ignore[arg-type]
    )  # fmt: skip


def test_a_restarted_master_is_said_and_the_configuration_brought_back(
    ros_master: ros_harness.Master, tmp_path: Path
) -> None:
    events: list[Event] = []
    watcher = _watcher(ros_master, tmp_path, events, stand_ins=True, settle=30.0)
    try:
        assert watcher.step().ok, [e.message for e in events]
        ros_harness.restart_master(ros_master)
        deadline = time.monotonic() + 60
        check = None
        while time.monotonic() < deadline:
            try:
                check = watcher.step()
            except ExternalToolError:
                time.sleep(0.2)
                continue
            if check.ok:
                break
        kinds = [e.kind for e in events]
        assert "master-restarted" in kinds, kinds
        assert "failed" not in kinds and "no-configuration" not in kinds, kinds
        assert check is not None and check.ok, [e.message for e in events[-3:]]
        assert watcher.current.mapping == dict(watcher.schema.nominal)
    finally:
        watcher.close()


def test_a_master_read_before_roscore_sets_run_id_is_not_a_restart(
    ros_master: ros_harness.Master, tmp_path: Path
) -> None:
    """roscore's master answers before ``/run_id`` is set: one master, read twice, not two.

    Before the fix the watcher said "master-restarted" (and, with launches, stopped and
    started them again) when a watch began in that gap; under load the gap is seconds long.
    The gap is re-created on the real master by taking ``/run_id`` away and putting it back.
    """
    master = xmlrpc.client.ServerProxy(ros_master.uri)
    deadline = time.monotonic() + 30  # the gap itself: roscore may not have set it yet
    while (answer := master.getParam("/test", "/run_id"))[0] != 1 and time.monotonic() < deadline:
        time.sleep(0.1)
    code, _, run_id = answer
    assert code == 1 and isinstance(run_id, str), answer
    events: list[Event] = []
    watcher = _watcher(ros_master, tmp_path, events, apply=False)
    try:
        master.deleteParam("/test", "/run_id")
        watcher.step()
        master.setParam("/test", "/run_id", run_id)
        watcher.step()
        master.setParam("/test", "/run_id", run_id + "-new")  # a real change of run: said
        watcher.step()
    finally:
        master.setParam("/test", "/run_id", run_id)
        watcher.close()
    kinds = [e.kind for e in events]
    assert kinds.count("master-restarted") == 1, kinds
    said = next(e for e in events if e.kind == "master-restarted")
    assert said.data["new_run_id"] == run_id + "-new", said.data


def test_roslaunchs_error_is_shown_and_its_files_kept(
    ros_master: ros_harness.Master, tmp_path: Path
) -> None:
    events: list[Event] = []
    keep = tmp_path / "kept"
    watcher = _watcher(ros_master, tmp_path, events, settle=10.0, launch_dir=keep)
    try:
        check = watcher.step()
        again = watcher.step()  # what did not start is not launched again and again
    finally:
        watcher.close()
    assert not check.ok and not again.ok
    kinds = [e.kind for e in events]
    assert kinds.count("launch") == 1, kinds
    errors = [e for e in events if e.kind == "launch-error"]
    assert errors and "cannot launch node of type" in errors[0].message, kinds
    assert all(e.message.isprintable() for e in events)
    launch_file, log = Path(errors[0].data["launch_file"]), Path(errors[0].data["output"])
    assert launch_file.parent == keep and launch_file.read_text().startswith("<")
    assert "cannot launch node of type" in log.read_text()
    assert str(launch_file) in errors[0].message and str(log) in errors[0].message


def test_watch_apply_says_roslaunchs_error_and_where_its_files_are(
    ros_master: ros_harness.Master, runner: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    for key, value in ros_master.env().items():
        monkeypatch.setenv(key, value)
    argv = ["watch", "--master", ros_master.uri, "--only", SCHEMA, "--apply", "--once"]
    # watch ends as soon as roslaunch has exited (1.6 s here); the settle only bounds a slow
    # roslaunch: 5 s ran out at a load of 16 (a fresh clone beside another), its error unsaid
    result = runner.invoke(app, [*argv, "--settle", "60"])
    assert result.exit_code == 1, result.stderr
    assert "cannot launch node of type" in result.stderr
    kept = sorted((ros_master.home / "log").glob("rosreconf-watch-*"))
    assert len(kept) == 1 and str(kept[0]) in result.stderr
    assert sorted(p.name for p in kept[0].iterdir()) == ["step1.launch", "step1.log"]


def test_without_apply_a_restart_leaves_components_missing_not_failed(
    ros_master: ros_harness.Master, standin: StartStandIn, tmp_path: Path
) -> None:
    events: list[Event] = []
    watcher = _watcher(ros_master, tmp_path, events, apply=False)
    for comp in watcher.current.components:
        standin(standin_spec(watcher.library[comp]))
    assert watcher.step().ok
    ros_harness.restart_master(ros_master)
    check = watcher.step()
    kinds = [e.kind for e in events]
    assert kinds == ["running", "master-restarted", "missing"], kinds
    assert not check.ok and "failed" not in kinds
    assert events[2].data["components"] == list(watcher.current.components)


def test_sigterm_says_what_was_stopped_though_roslaunch_is_slow_to_stop(
    ros_master: ros_harness.Master, tmp_path: Path
) -> None:
    """A roslaunch that does not end on SIGINT is killed within watch's bounded stop, and
    watch still says so (``stopped``, ``kept``) before it exits 143.

    A fault injector stands in for roslaunch (``fakes/roslaunch_slow_to_stop.py``, first on
    PATH as ``roslaunch``): a real one whose nodes are slow to stop cannot be made on demand.
    """
    fake_bin = tmp_path / "bin"
    fake_bin.mkdir()
    (fake_bin / "roslaunch").symlink_to(FAKES / "roslaunch_slow_to_stop.py")
    env = ros_master.env()
    env["PATH"] = f"{fake_bin}{os.pathsep}{env.get('PATH', os.defpath)}"
    log = tmp_path / "watch.jsonl"
    argv = [sys.executable, "-m", "rosreconf", "watch", "--master", ros_master.uri,
            "--only", SCHEMA, "--apply", "--stand-ins", "--interval", "0.2",
            "--json-log", str(log)]  # fmt: skip
    watch = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)  # fmt: skip
    try:
        ros_harness.wait_until(
            lambda: (
                bool(list(ros_master.home.glob("log/rosreconf-watch-*/*.fake-pid")))
                or watch.poll() is not None
            ),
            60.0,
            "the fake roslaunch to start",
            interval=0.1,
        )
        (pid_file,) = ros_master.home.glob("log/rosreconf-watch-*/*.fake-pid")
        fake = int(pid_file.read_text())
        watch.send_signal(signal.SIGTERM)
        assert watch.wait(10) == 143
        said = [json.loads(line)["event"] for line in log.read_text().splitlines()]
        assert said[-2:] == ["stopped", "kept"], said
        gone = lambda: not Path(f"/proc/{fake}").exists()  # noqa: E731
        ros_harness.wait_until(gone, 5.0, "the fake roslaunch to be gone")  # killed, reaped
    finally:
        if watch.poll() is None:
            watch.kill()
            watch.wait()
