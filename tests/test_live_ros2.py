"""The paper's use case on a ROS 2 graph over real DDS: a servo dies, the robot re-plans.

The bundled example's nominal Object Repositioning configuration is announced as ROS 2 nodes,
one announcer process (one DDS participant) per component, exactly as rmw_cyclonedds would
(tests/ros2_announcer.py, written from the rmw sources). ``inspect --ros2`` must find it
conformant; NSM3 is SIGKILLed (its participant cannot say goodbye, so DDS notices when its
lease expires); ``inspect`` must name it; ``watch --ros2`` (a real subprocess) must detect it
and re-plan with the fewest changes. No ROS 2 is installed here, so ``--apply`` writes the
ROS 2 launch file and says what it would run. Verified at the DDS protocol level against the
rmw sources, not against a ROS 2 installation.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import jsonschema
import ros2_harness
from conftest import Announce
from test_json_outputs import schema_of
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_bundled, load_paths

SCHEMA = "object_repositioning"
DETECT_TIMEOUT = 30.0


def _nominal() -> tuple[Any, Any]:
    bundle = load_bundled()
    return bundle.library, next(s for s in bundle.schemas if s.name == SCHEMA)


def _events(path: Path) -> list[dict[str, Any]]:
    if not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.endswith("}")]


def test_inspect_kill_and_replan(
    announce: Announce, ros2_domain: int, runner: CliRunner, tmp_path: Path
) -> None:
    library, schema = _nominal()
    chosen = [library[c] for c in schema.nominal.values()]  # each wired to the others
    nodes = {c: announce([ros2_harness.node_spec(library[c], providers=chosen)])
             for c in schema.nominal.values()}  # fmt: skip
    ros2 = ["--ros2", "--domain", str(ros2_domain)]
    inspect = ["inspect", *ros2, "--only", SCHEMA, "--json"]

    result = runner.invoke(app, inspect)
    assert result.exit_code == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["conformant"] is True
    assert report["master_uri"] == f"ros2://domain/{ros2_domain}"

    draft = tmp_path / "imported.yaml"
    result = runner.invoke(app, ["import", *ros2, "-o", str(draft)])
    assert result.exit_code == 0, result.stderr
    loaded = load_paths([draft])
    assert {c.name for c in loaded.library} == set(schema.nominal.values())
    nsm3 = loaded.library["NSM3"]
    assert {(i.label, i.type) for i in nsm3.provides} == {
        ("/arm_servo/elbow/servo_command", "robot_arm_msgs/DigitalServoCommand")
    }

    log = tmp_path / "watch.jsonl"
    argv = [sys.executable, "-m", "rosreconf", "watch", *ros2, "--only", SCHEMA, "--apply",
            "--ros2-launch", "--interval", "0.2", "--json-log", str(log)]  # fmt: skip
    err = (tmp_path / "watch.err").open("wb")
    watch = subprocess.Popen(
        argv,
        env={**ros2_harness.dds_env(), "ROS_LOG_DIR": str(tmp_path)},
        stdout=subprocess.DEVNULL,
        stderr=err,
        start_new_session=True,
    )
    try:
        ros2_harness_wait(
            lambda: "running" in [e["event"] for e in _events(log)] or watch.poll() is not None,
            DETECT_TIMEOUT,
        )
        assert [e["event"] for e in _events(log)] == ["started", "running"], _events(log)

        killed_at = time.monotonic()
        nodes["NSM3"].kill()
        ros2_harness_wait(
            lambda: any(e["event"] == "hold" for e in _events(log)) or watch.poll() is not None,
            DETECT_TIMEOUT,
        )
        took = time.monotonic() - killed_at
        events = _events(log)[2:]
        kinds = [e["event"] for e in events]
        assert kinds[:2] == ["failed", "replanned"], events
        (hold,) = (e for e in events if e["event"] == "hold")  # --restarts 0, NDC3 is left
        assert events[0]["component"] == hold["component"] == "NSM3"
        new = events[1]["configuration"]
        assert [new[r] for r in ("base_joint", "elbow_joint", "gripper_joint")] == [
            "NDC1", "NDC3", "NDC5"
        ]  # fmt: skip
        ros2_harness_wait(lambda: "would-launch" in [e["event"] for e in _events(log)], 10)
        (would,) = (e for e in _events(log) if e["event"] == "would-launch")
        assert would["command"].startswith("ros2 launch ")
        written = Path(would["launch_file"])
        assert written.parent.parent == tmp_path and "<launch>" in written.read_text()
        assert written.parent.name.startswith("rosreconf-watch-")
        print(f"SIGKILL -> replanned: {took:.2f} s (lease {ros2_harness.LEASE:g} s)")
    finally:
        if watch.poll() is None:
            watch.send_signal(signal.SIGTERM)
            watch.wait(15)
        err.close()

    result = runner.invoke(app, inspect)
    assert result.exit_code == 1
    jsonschema.validate(json.loads(result.stdout), schema_of("inspect"))
    findings = json.loads(result.stdout)["findings"]
    assert {"code": "missing-node", "component": "NSM3"}.items() <= findings[0].items()
    assert any(f["code"] == "unmet-requirement" and "NSM3" in f["message"] for f in findings)


def test_qos_mismatch_is_reported_with_both_sides(
    announce: Announce, ros2_domain: int, runner: CliRunner
) -> None:
    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == "indoor_navigation")
    # The laser publishes best effort (the sensor-data profile); AMCL asks for reliable
    # delivery every 0.1 s, which no best-effort publisher without a deadline can give.
    qos = {
        "HOKUYO_UST10": {"/scan": {"reliability": "best_effort"}},
        "AMCL": {"/scan": {"reliability": "reliable", "deadline": 0.1}},
        "TEB_PLANNER": {"/scan": {"reliability": "best_effort"}},
    }
    chosen = [bundle.library[c] for c in schema.nominal.values()]  # each wired to the others
    for comp in schema.nominal.values():
        announce([ros2_harness.node_spec(bundle.library[comp], qos.get(comp), chosen)])
    argv = ["inspect", "--ros2", "--domain", str(ros2_domain), "--only", "indoor_navigation"]
    result = runner.invoke(app, argv)
    assert result.exit_code == 1, result.stdout + result.stderr
    lines = [ln for ln in result.stdout.splitlines() if "qos-incompatible" in ln]
    assert len(lines) == 1, result.stdout
    (line,) = lines
    assert "HOKUYO_UST10 offers [best_effort" in line and "AMCL requests [reliable" in line
    assert "best effort publisher and reliable subscription" in line
    assert "subscription has a deadline (0.1 s), but publisher does not" in line
    assert len(result.stdout.splitlines()) == 2, result.stdout  # nothing else is wrong
    as_json = runner.invoke(app, [*argv, "--json"])
    report = json.loads(as_json.stdout)
    jsonschema.validate(report, schema_of("inspect"))
    assert [f["code"] for f in report["findings"]] == ["qos-incompatible"]


def ros2_harness_wait(check: Any, timeout: float) -> None:
    """Poll ``check`` every 0.05 s until it holds; fail after ``timeout`` s."""
    deadline = time.monotonic() + timeout
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)


def test_watch_lists_lifecycle_transitions_and_writes_the_launch_file(
    announce: Announce, ros2_domain: int, tmp_path: Path
) -> None:
    from dataclasses import replace

    from rosreconf.model import ComponentLibrary, Configuration
    from rosreconf.ros.options import Ros2Options, WatchOptions
    from rosreconf.ros.ros2.source import Ros2Source
    from rosreconf.ros.watcher import Event, Watcher

    library, schema = _nominal()
    managed = ComponentLibrary(
        library.name,
        tuple(
            replace(c, launch=replace(c.launch, lifecycle=True)) if c.launch else c
            for c in library.components
        ),
    )
    chosen = [library[c] for c in schema.nominal.values()]  # each wired to the others

    def managed_spec(c: str) -> dict[str, Any]:  # a managed node serves its lifecycle services
        spec = ros2_harness.node_spec(library[c], providers=chosen)
        spec["servers"] += [{"name": f"/{c}/{s}", "type": f"lifecycle_msgs/srv/{t}"}
                            for s, t in (("get_state", "GetState"),
                                         ("change_state", "ChangeState"))]  # fmt: skip
        return spec

    nodes = {c: announce([managed_spec(c)]) for c in schema.nominal.values()}
    events: list[Event] = []
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    no_ros2 = {"PATH": str(tmp_path)}  # no `ros2` command on this PATH
    options = WatchOptions(apply=True, launch_dir=tmp_path, ros2=Ros2Options(launch=True))
    watcher = Watcher(Ros2Source(ros2_domain), managed, schema, config, tmp_path, no_ros2,
                      events.append, options)  # fmt: skip
    try:
        # announcers serve get_state but cannot answer it: a managed node whose state cannot
        # be read is not known to be active, and is said so (never assumed conformant)
        first = watcher.step()
        assert {f.code for f in first.findings} == {"not-active"}, first.findings
        nodes["NSM3"].kill()
        deadline = time.monotonic() + DETECT_TIMEOUT
        while not any(e.kind == "replanned" for e in events):
            assert time.monotonic() < deadline, [e.message for e in events]
            watcher.step()
            time.sleep(0.2)
        steps = {e.data["role"]: e.data["transitions"] for e in events if e.kind == "lifecycle"}
        assert steps["elbow_joint"] == [
            "ros2 lifecycle set /NSM3 deactivate",
            "ros2 lifecycle set /NSM3 cleanup",
            "ros2 lifecycle set /NDC3 configure",
            "ros2 lifecycle set /NDC3 activate",
        ]
        (would,) = (e for e in events if e.kind == "would-launch")
        launch = tmp_path / "step1.launch.xml"
        assert would.data["command"] == f"ros2 launch {launch}"
        text = launch.read_text()
        assert '<node pkg="robot_arm_dc"' in text and 'name="NDC3"' in text
        assert "NSM1" not in text  # only the new components are started
        watcher.step()
        assert [e.kind for e in events].count("would-launch") == 1  # said once, not every poll
    finally:
        watcher.close()


def test_a_graph_caught_half_announced_is_no_lost_master(
    announce: Announce, ros2_domain: int, tmp_path: Path
) -> None:
    """Fake (as in test_ros2_discovery: an announcer whose node list never names its newest
    node): every read after it joins is partial. A failover's reads are partial for a moment
    as its nodes start, and watch said ``master-lost`` then ``master-back`` in the middle of
    one (issue 44). Partial reads are now said only when they last: ``graph-unsettled`` once,
    ``graph-settled`` when the graph reads whole again; no master was ever lost."""
    library, schema = _nominal()
    chosen = [library[c] for c in schema.nominal.values()]
    for c in schema.nominal.values():
        announce([ros2_harness.node_spec(library[c], providers=chosen)])
    log = tmp_path / "watch.jsonl"
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(ros2_domain),
            "--only", SCHEMA, "--interval", "0.2", "--json-log", str(log)]  # fmt: skip
    env = {**ros2_harness.dds_env(), "ROS_LOG_DIR": str(tmp_path)}
    watch = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)  # fmt: skip

    def said(kind: str) -> bool:
        return kind in [e["event"] for e in _events(log)] or watch.poll() is not None

    try:
        ros2_harness_wait(lambda: said("running"), DETECT_TIMEOUT)
        late = {"name": "late", "plumbing": False,
                "publishers": [{"name": "/late", "type": "std_msgs/msg/String"}]}  # fmt: skip
        joined = time.monotonic()
        extra = {
            "name": "extra",
            "subscriptions": [{"name": "/chatter", "type": "std_msgs/msg/String"}],
        }
        stale = announce([extra, late], stale_newest=True)
        ros2_harness_wait(lambda: said("graph-unsettled"), DETECT_TIMEOUT)
        assert time.monotonic() - joined >= 3.0  # not said while it may be a start
        ros2_harness.stop([stale])  # a clean exit: DDS forgets its participant at once
        ros2_harness_wait(lambda: said("graph-settled"), DETECT_TIMEOUT)
        kinds = [e["event"] for e in _events(log)]
        assert kinds.count("graph-unsettled") == kinds.count("graph-settled") == 1, kinds
        assert "master-lost" not in kinds and "master-back" not in kinds, kinds
        (unsettled,) = (e for e in _events(log) if e["event"] == "graph-unsettled")
        assert "announce endpoints that no node" in unsettled["message"], unsettled
    finally:
        watch.send_signal(signal.SIGTERM)
        watch.wait(15)
