"""The paper's use case on a real ROS 1 master: a servo dies, the robot reconfigures itself.

Stand-ins of the nominal Object Repositioning configuration (NSM arm, camera 1) run on a
private roscore; ``import`` and ``inspect`` read them; NSM3 is SIGKILLed (it lingers in the
master); ``watch --apply --stand-ins`` runs as a real subprocess and must bring the DC-arm
configuration up through the real roslaunch, which ``inspect`` then confirms, and the
master's own getSystemState too (read here, not through rosreconf). Everything
started here is stopped at the end, and the master fixture asserts no process is left.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import ros_harness
from conftest import StartStandIn
from ros2_harness import live_name

from rosreconf.cli.app import app
from rosreconf.errors import Severity
from rosreconf.formats.configfile import render_configurations
from rosreconf.formats.loader import check_loaded, load_bundled, load_paths
from rosreconf.ros.ros1.standins import standin_spec

pytestmark = pytest.mark.ros

SCHEMA = "object_repositioning"
RECONFIGURE_TIMEOUT = 40.0


def _events(path: Path) -> list[dict[str, Any]]:
    if not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.endswith("}")]


def test_import_inspect_and_self_repair(
    ros_master: ros_harness.Master, standin: StartStandIn, runner: Any, tmp_path: Path
) -> None:
    bundle = load_bundled()
    library, schema = bundle.library, next(s for s in bundle.schemas if s.name == SCHEMA)
    nodes = {c: standin(standin_spec(library[c])) for c in schema.nominal.values()}
    uri = ros_master.uri

    draft = tmp_path / "imported.yaml"
    result = runner.invoke(app, ["import", "--master", uri, "-o", str(draft)])
    assert result.exit_code == 0, result.stderr
    assert draft.read_text().startswith("# yaml-language-server: $schema=")
    loaded = load_paths([draft])
    errors = [p for p in [*loaded.problems, *check_loaded(loaded)] if p.severity is Severity.ERROR]
    assert not errors, errors
    assert {c.name for c in loaded.library} == set(schema.nominal.values())
    nsm3 = loaded.library["NSM3"]
    assert {i.label for i in nsm3.provides} == {"/arm_servo/elbow/servo_command"}

    inspect = ["inspect", "--master", uri, "--only", SCHEMA, "--json"]
    result = runner.invoke(app, inspect)
    assert result.exit_code == 0, result.stdout
    assert json.loads(result.stdout)["conformant"] is True

    nodes["NSM3"].process.send_signal(signal.SIGKILL)
    nodes["NSM3"].process.wait(5)
    result = runner.invoke(app, inspect)
    assert result.exit_code == 1
    report = json.loads(result.stdout)
    assert {"code": "dead-node", "component": "NSM3"}.items() <= report["findings"][0].items()
    assert any(
        f["code"] == "unmet-requirement" and "NSM3" in f["message"] for f in report["findings"]
    )

    log = tmp_path / "watch.jsonl"
    argv = [sys.executable, "-m", "rosreconf", "watch", "--master", uri, "--only", SCHEMA,
            "--apply", "--stand-ins", "--interval", "0.2", "--json-log", str(log)]  # fmt: skip
    err = (tmp_path / "watch.err").open("wb")
    watch = subprocess.Popen(
        argv, env=ros_master.env(), stdout=subprocess.DEVNULL, stderr=err, start_new_session=True
    )
    try:
        took = ros_harness.wait_until(
            lambda: (
                any(e["event"] == "conformant" for e in _events(log)) or watch.poll() is not None
            ),
            RECONFIGURE_TIMEOUT,
            "reconfiguration",
            interval=0.1,
        )
        events = _events(log)
        assert [e["event"] for e in events][:3] == ["started", "failed", "purged"], events
        (replanned,) = (e for e in events if e["event"] == "replanned")
        new = replanned["configuration"]
        assert [new[r] for r in ("base_joint", "elbow_joint", "gripper_joint")] == [
            "NDC1", "NDC3", "NDC5"
        ]  # fmt: skip
        assert {new["positioning"], new["placing"]} == {"NFB11", "NFB14"}
        assert new["camera"] == "NCA1" and new["reasoner"] == "NREA"
        assert events[-1]["event"] == "conformant", events[-1]
        print(f"kill -> conformant: {took:.2f} s after watch started")
        _assert_master_holds_only(uri, library, set(new.values()))

        config = tmp_path / "dc.json"
        config.write_text(render_configurations({SCHEMA: new}))
        result = runner.invoke(app, [*inspect, "--configuration", str(config)])
        assert result.exit_code == 0, result.stdout
        old = runner.invoke(app, inspect)
        assert old.exit_code == 1  # the nominal configuration no longer runs

        watch.send_signal(signal.SIGTERM)
        assert watch.wait(15) == 143
        stopped, kept = _events(log)[-2:]
        assert (stopped["event"], kept["event"]) == ("stopped", "kept")
        assert {p.name for p in Path(kept["launch_dir"]).iterdir()} == {"step1.launch", "step1.log"}
    finally:
        if watch.poll() is None:
            ros_harness.kill_group(watch.pid)
            watch.wait(5)
        err.close()
    ros_master.remember_children()
    ours = {n.process.pid for n in nodes.values()} | ros_master.pids | {ros_master.process.pid}
    left = {
        p: ros_harness.cmdline(p)
        for p in ros_harness.processes_using(ros_master.home)
        if p not in ours
    }
    assert not left, f"watch left processes behind: {left}"


def _assert_master_holds_only(uri: str, library: Any, chosen: set[str]) -> None:
    """Read the repaired graph from the master itself (getSystemState), not through rosreconf:
    only the chosen components' nodes are registered (the replaced ones stopped, dead NSM3
    purged), every topic one of them subscribes to has a publisher among them, and every
    service a chosen component requires is served by a chosen provider, at the name that
    provider's launch entry gives it. (ROS 1 service clients are not known to the master, so
    which name a consumer calls cannot be read there.)"""
    state = ros_harness.system_state(uri)
    assert state is not None, "the master did not answer getSystemState"
    pubs, subs, srvs = ({name: set(nodes) for name, nodes in part} for part in state)
    ours = {f"/{c}" for c in chosen}
    seen = {n for part in (pubs, subs, srvs) for nodes in part.values() for n in nodes}
    assert seen - {"/rosout"} == ours, f"registered beyond the configuration: {seen - ours}"
    dangling = {
        t: nodes for t, nodes in subs.items() if nodes & ours and not pubs.get(t, set()) & ours
    }
    assert not dangling, f"subscribed with no publisher of the configuration: {dangling}"
    for name in chosen:
        for need in library[name].requires:
            wanted = [o for o in need.options if o.kind == "service"]
            at = [(p, live_name(library[p], o.label)) for p in chosen for o in wanted
                  if o in library[p].provides]  # fmt: skip
            assert any(f"/{p}" in srvs.get(live, set()) for p, live in at), (name, wanted, at)
