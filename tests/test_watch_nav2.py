"""A Nav2-shaped stack under ``watch --ros2 --apply --stand-ins``: alternatives that share a name.

The library (tests/data/nav2): eleven nodes, eight managed, actions between them; AMCL or
slam_toolbox as the localiser; two global planners that both run as ``/planner_server``
(nav2_planner's one executable with another plugin). ``kill -9`` of AMCL must end ``conformant``
with the changes ``rosreconf plan --fail amcl`` prints (slam_toolbox, and the kept planner
restarted rewired: both commands apply one preference), and never two nodes of one name: a
planner that takes over ``/planner_server`` starts only once the old one's process is gone,
and the other planner never waits as a standby beside the running one. Real rclpy nodes,
Jazzy and Kilted; the end state read by the tests' own rclpy probe (``tests/ros2_probe.py``).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from test_watch_ros2 import ROOT, Watch, _env, probe, watched_by_process

NAV2 = Path(__file__).with_name("data") / "nav2"
FILES = ["--library", str(NAV2 / "nav2_library.yaml"), "--schema", str(NAV2 / "nav2_schema.yaml")]
NOMINAL = {
    "/lidar", "/wheel_odometry", "/map_server", "/amcl", "/planner_server", "/controller_server",
    "/behavior_server", "/bt_navigator", "/waypoint_follower", "/velocity_smoother",
    "/base_driver",
}  # fmt: skip
UNMANAGED = {"/lidar", "/wheel_odometry", "/base_driver"}


def _python(distro: str) -> Path:
    python = ROOT / f".venv-ros2-{distro}" / "bin" / "python"
    if not python.exists():  # make test builds it: missing is a failure, never a skip
        pytest.fail(f"the {distro} venv is missing: run `make ros2-venvs`", pytrace=False)
    return python


def _plan(failed: str) -> dict[str, str | None]:
    """Return role -> new component of ``rosreconf plan --fail``'s changes (restarts too)."""
    argv = [sys.executable, "-m", "rosreconf", "plan", *FILES, "--fail", failed, "--json"]
    out = subprocess.run(argv, capture_output=True, text=True, timeout=120, check=False)
    assert out.returncode == 0, out.stderr
    (schema,) = json.loads(out.stdout)["schemas"]
    return {c["role"]: c["after"] for c in schema["changes"] if c["kind"] != "keep"}


def _end_state(watch: Watch, domain: int, python: Path, nodes: set[str]) -> dict[str, Any]:
    """Return rclpy's view once ``nodes`` show and nothing of theirs dangles; check it."""
    managed = sorted(nodes - UNMANAGED)
    seen = probe(
        watch.env, domain, *managed, wait_for=nodes, python=python, until_wired=True
    )  # the managed ones' states asked, their calls and subscriptions wired
    names = list(seen["nodes"])
    assert len(names) == len(set(names)), f"two nodes of one name: {names}"
    assert nodes <= set(names), names
    assert seen["states"] == dict.fromkeys(managed, "active")
    assert seen["dangling"] == {"calls": [], "subscriptions": []}
    return seen


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_kill_amcl_ends_conformant_with_the_changes_plan_prints_and_one_planner_server(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, *FILES, python=python)
    try:
        watch.wait("conformant")
        _end_state(watch, ros2_domain, python, NOMINAL)
        before = len(watch.events())
        os.kill(watch.pids()["amcl"], signal.SIGKILL)
        done = watch.wait("conformant", after=before)
        after = watch.events()[before:]
        said = [e["message"] for e in after]
        assert [e["component"] for e in after if e["event"] == "failed"] == ["amcl"], said
        (replanned,) = (e for e in after if e["event"] == "replanned")
        changes = {c["role"]: c["to"] for c in replanned["changes"]}
        assert (
            changes == _plan("amcl") == {"localization": "slam_toolbox", "planner": "planner_navfn"}
        )
        assert [c["role"] for c in replanned["changes"] if c["restart"]] == ["planner"]
        assert done["configuration"]["planner"] == "planner_navfn"
        assert not [e for e in after if e["event"] in ("not-conformant", "name-taken")], said
        nodes = (NOMINAL - {"/amcl"}) | {"/slam_toolbox"}
        seen = _end_state(watch, ros2_domain, python, nodes)
        assert "/amcl" not in seen["nodes"]
        assert "/pose" in seen["topics"] and "/amcl_pose" not in seen["topics"]
    finally:
        watch.stop(signal.SIGKILL)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_planner_taking_over_planner_server_starts_once_the_hung_one_is_gone(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    """SIGSTOP the running planner: it is failed as hung and replaced by the other planner,
    whose node name is the same. The newcomer waits for the hung process to be stopped, then
    starts: configure and activate reach it, and one /planner_server is left, active."""
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, *FILES, python=python)
    hung = 0
    try:
        watch.wait("conformant")
        before = len(watch.events())
        hung = watch.pids()["planner_navfn"]
        os.kill(hung, signal.SIGSTOP)
        done = watch.wait("conformant", after=before)
        after = watch.events()[before:]
        said = [e["message"] for e in after]
        kinds = [e["event"] for e in after]
        (replanned,) = (e for e in after if e["event"] == "replanned")
        assert [(c["from"], c["to"]) for c in replanned["changes"]] == [
            ("planner_navfn", "planner_smac_hybrid")
        ], said
        (taken,) = (e for e in after if e["event"] == "name-taken")
        assert taken["component"] == "planner_smac_hybrid" and taken["node"] == "/planner_server"
        (stop,) = (e for e in after if e["event"] == "stop" and e["component"] == "planner_navfn")
        (launch,) = (e for e in after if e["event"] == "launch")
        assert launch["components"] == ["planner_smac_hybrid"]
        # break before make: held back, the old process gone, then started
        assert kinds.index("name-taken") < after.index(stop) < after.index(launch), said
        assert not Path(f"/proc/{hung}").exists()
        steps = [
            (e["transition"], e["ok"]) for e in after if e.get("node") == "/planner_server"
            and e["event"] == "lifecycle"
        ]  # fmt: skip
        assert steps == [("configure", True), ("activate", True)], said
        assert done["configuration"]["planner"] == "planner_smac_hybrid"
        assert not [e for e in after if e["event"] in ("missing", "not-conformant")], said
        _end_state(watch, ros2_domain, python, NOMINAL)
    finally:
        if hung:
            with contextlib.suppress(ProcessLookupError):
                os.kill(hung, signal.SIGCONT)
        watch.stop(signal.SIGKILL)


def test_a_standby_never_waits_under_a_running_nodes_name(ros2_domain: int, tmp_path: Path) -> None:
    """With --standby, slam_toolbox waits configured as AMCL's standby; the other planner
    cannot wait beside /planner_server: watch says so and parks none under that name. The
    failover is slam_toolbox's activate and the kept planner's restart."""
    python = _python("jazzy")
    watch = Watch(tmp_path, ros2_domain, *FILES, "--standby", python=python)
    try:
        watch.wait("conformant")
        refused = watch.wait("no-standby")
        assert refused["component"] == "planner_smac_hybrid"
        assert refused["node"] == "/planner_server" and refused["holder"] == "planner_navfn"
        standby = watch.wait("launch", after=watch.events().index(refused))
        assert standby.get("standby"), standby
        assert "planner_smac_hybrid" not in standby["components"]
        assert "slam_toolbox" in standby["components"]
        watch.until(lambda ev: "slam_toolbox" in watch.configured(ev), "slam_toolbox configured")
        names = list(probe(watch.env, ros2_domain, wait_for=["/slam_toolbox"], python=python)[
            "nodes"])  # fmt: skip
        assert len(names) == len(set(names)), names
        before = len(watch.events())
        os.kill(watch.pids()["amcl"], signal.SIGKILL)
        watch.wait("conformant", after=before)
        after = watch.events()[before:]
        said = [e["message"] for e in after]
        activated = {e["component"] for e in after if e.get("transition") == "activate"}
        assert activated == {"slam_toolbox", "planner_navfn"}, said
        launched = [c for e in after if e["event"] == "launch" and not e.get("standby")
                    for c in e["components"]]  # fmt: skip
        assert launched == ["planner_navfn"], said  # restarted rewired: the only start
        nodes = (NOMINAL - {"/amcl"}) | {"/slam_toolbox"}
        _end_state(watch, ros2_domain, python, nodes)
    finally:
        watch.stop(signal.SIGKILL)


@pytest.mark.parametrize("stop_outside", [False, True], ids=["by-hand", "stop-outside"])
def test_a_hung_planner_the_team_started_is_gone_before_the_other_one_starts(
    stop_outside: bool, ros2_domain: int, tmp_path: Path
) -> None:
    """The team's own /planner_server (planner_navfn, started as its launch file would) hangs
    (SIGSTOP). watch fails it and replaces it by planner_smac_hybrid, which runs under the same
    name: smac waits while the hung process is there, though DDS no longer shows it. A person
    ends it (or --stop-outside does), then smac starts, and one /planner_server is left."""
    from ros2_team import STANDIN, Team, wait_ready

    from rosreconf.formats.loader import load_paths
    from rosreconf.model import Configuration
    from rosreconf.ros.launchfiles import ros2_node_arguments, wiring
    from rosreconf.ros.ros2.runtime import lease_profile
    from rosreconf.ros.standin_spec import ros2_standin_spec

    python = _python("jazzy")
    loaded = load_paths([NAV2 / "nav2_library.yaml", NAV2 / "nav2_schema.yaml"])
    library, schema = loaded.library, loaded.schemas[0]
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    profile = tmp_path / "lease.xml"
    profile.write_text(lease_profile(2.0))
    env = {**_env(tmp_path, python), "ROS_DOMAIN_ID": str(ros2_domain),
           "FASTRTPS_DEFAULT_PROFILES_FILE": str(profile)}  # fmt: skip
    team = Team(python, env, tmp_path / "team")
    args = ros2_node_arguments(library, "planner_navfn", wiring(library, schema, nominal))
    spec = json.dumps(ros2_standin_spec(library["planner_navfn"]))
    ours = team.start("planner_navfn", [str(python), str(STANDIN), spec, *args])
    watch: Watch | None = None
    try:
        wait_ready({"planner_navfn": ours})
        flags = ["--stop-outside"] if stop_outside else []
        watch = Watch(tmp_path, ros2_domain, *FILES, *flags, python=python)
        watch.wait("conformant")
        assert "planner_navfn" not in watch.pids()
        watch.until(lambda ev: "/planner_server" in watched_by_process(ev),
                    "'watched' of /planner_server by its process")  # fmt: skip
        before = len(watch.events())
        os.kill(ours.pid, signal.SIGSTOP)
        taken = watch.wait("name-taken", after=before)
        assert taken["component"] == "planner_smac_hybrid"
        assert f"pid {ours.pid}" in " ".join(taken["holders"]), taken
        if not stop_outside:
            by_hand = watch.wait("stop-by-hand", after=before)
            assert by_hand["component"] == "planner_navfn"
            assert "planner_smac_hybrid starts under its node name" in by_hand["message"]
            assert "planner_smac_hybrid" not in watch.pids()  # not beside the hung one
            os.kill(ours.pid, signal.SIGKILL)  # a person ends it
        done = watch.wait("conformant", after=before)
        after = watch.events()[before:]
        said = [e["message"] for e in after]
        assert done["configuration"]["planner"] == "planner_smac_hybrid"
        (launch,) = (e for e in after if e["event"] == "launch")
        assert launch["components"] == ["planner_smac_hybrid"], said
        assert not [e for e in after if e["event"] in ("missing", "not-conformant")], said
        if stop_outside:
            (stop,) = (e for e in after if e["event"] == "stop")
            assert stop["component"] == "planner_navfn" and stop["how"] == "signal"
            assert after.index(stop) < after.index(launch), said
        ours.wait(20)
        _end_state(watch, ros2_domain, python, NOMINAL)
    finally:
        if watch is not None:
            watch.stop(signal.SIGKILL)
        with contextlib.suppress(ProcessLookupError):
            os.kill(ours.pid, signal.SIGKILL)
        team.close()
