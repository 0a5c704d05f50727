"""Lifecycle transitions that time out are tried again, and lifecycle faults that last are repaired.

``watch`` runs each component's own executable here (an ament prefix the test writes, as
colcon would install it), so the nodes are what a robot's packages are: real rclpy processes
started with ``--ros-args``. The end state is read with the tests' own rclpy probe.

- A managed node whose ``on_configure`` outlasts the agent's call (5 s, and 5 s more for the
  state read back) is not left ``inactive`` until ``--settle`` has passed: it is activated
  once it answers ``inactive`` (3 of 10 camera switches with standbys ended
  ``not-conformant`` before). The node is ``tests/ros2_node.py``'s real ``LifecycleNode``
  whose ``on_configure`` sleeps in its executor, as a slow driver does.
- A managed node that keeps leaving ``active`` after it was brought back, and one whose
  ``get_state`` server has left discovery for good, are failed and replaced, where before
  the first was left as it was and the second was never repaired. No real managed node does
  either on demand: the fault injector ``tests/ros2_state_faults.py`` (named as such) gives a
  stand-in lifecycle services of its own that do.
"""

from __future__ import annotations

import json
import os
import signal
from pathlib import Path

import pytest
from test_watch_ros2 import ROOT, Watch, probe
from test_watch_wiring import _python

from rosreconf.ros.ros2.runtime import own_profile

NODE = Path(__file__).with_name("ros2_node.py")
FAULTS = Path(__file__).with_name("ros2_state_faults.py")
STANDIN = ROOT / "rosreconf" / "ros" / "ros2" / "scripts" / "standin_node.py"
CONFIGURE_SECONDS = 12.0
"""How long the slow node's ``on_configure`` takes: more than the agent waits for the call
and the state read back after it (5 s each), so the configure times out."""

SLOW_LIBRARY = """\
format: rosreconf/component-library
version: 1
name: slow
components:
  - name: TALKER
    abstraction: talker
    provides:
      - {topic: chatter, type: std_msgs/String}
    ros: {package: slow_demo, executable: talker, lifecycle: true}
  - name: LISTENER
    abstraction: listener
    requires:
      - {topic: chatter, type: std_msgs/String}
    ros: {package: slow_demo, executable: listener}
"""
SLOW_SCHEMA = """\
format: rosreconf/interoperability-schema
version: 1
name: slow
skill: say something and hear it
environment: anywhere
roles:
  - {name: speaker, abstraction: talker}
  - {name: hearer, abstraction: listener}
edges:
  - {consumer: hearer, providers: [speaker]}
nominal: {speaker: TALKER, hearer: LISTENER}
"""


def _program(prefix: Path, package: str, executable: str, script: str) -> None:
    """Install ``script`` (a shell script's body) as ``package``'s ``executable``."""
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True, exist_ok=True)
    (index / package).touch()
    program = prefix / "lib" / package / executable
    program.parent.mkdir(parents=True, exist_ok=True)
    program.write_text("#!/bin/sh\n" + script)
    program.chmod(0o755)


def _robot_env(tmp: Path, prefix: Path) -> dict[str, str]:
    """Return the environment of this file's robot: its programs in ``prefix``, each with
    the short lease and no XTypes type lookup (a profile of their own, which watch keeps).

    Kilted's Fast DDS 3 sometimes segfaults a participant as it starts, in its type lookup
    service (``rosreconf.ros.ros2.runtime.NO_TYPE_LOOKUP``): a program of the robot that
    crashed so (NFB21, exit -11, in fresh clone fc6) changed the configuration under the
    test, whose faults then hit a node out of service. These tests are about lifecycle
    faults, not that crash.
    """
    profile = str(own_profile(tmp / "robot"))
    return {
        "AMENT_PREFIX_PATH": str(prefix),
        "FASTDDS_DEFAULT_PROFILES_FILE": profile,
        "FASTRTPS_DEFAULT_PROFILES_FILE": profile,
    }


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_configure_that_timed_out_is_tried_again_within_settle(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    prefix = tmp_path / "install"
    nodes = {
        "talker": {"name": "TALKER", "lifecycle": "unconfigured",
                   "configure_seconds": CONFIGURE_SECONDS,
                   "publishers": [{"name": "/chatter", "type": "std_msgs/msg/String"}]},
        "listener": {"name": "LISTENER",
                     "subscriptions": [{"name": "/chatter", "type": "std_msgs/msg/String"}]},
    }  # fmt: skip
    for executable, node in nodes.items():
        spec = tmp_path / f"{executable}.json"
        spec.write_text(json.dumps({"nodes": [{"namespace": "/", **node}]}))
        _program(prefix, "slow_demo", executable, f'exec "{python}" "{NODE}" "{spec}" "$@"\n')
    (tmp_path / "slow.yaml").write_text(SLOW_LIBRARY)
    (tmp_path / "slow_schema.yaml").write_text(SLOW_SCHEMA)
    files = [
        "--library",
        str(tmp_path / "slow.yaml"),
        "--schema",
        str(tmp_path / "slow_schema.yaml"),
    ]
    ament = _robot_env(tmp_path, prefix)
    watch = Watch(tmp_path, ros2_domain, *files, "--restarts", "1", "--settle", "40",
                  python=python, stand_ins=False, env=ament)  # fmt: skip
    try:
        for phase in ("start", "restart in place"):
            before = len(watch.events())
            done = watch.wait("conformant", after=before, timeout=180.0)
            said = watch.events()[before : watch.events().index(done)]
            kinds = [e["event"] for e in said]
            assert "not-conformant" not in kinds, (phase, [e["message"] for e in said])
            tries = [e for e in said if e["event"] == "lifecycle" and e.get("node") == "/TALKER"]
            timed_out = [e for e in tries if e["transition"] == "configure" and not e["ok"]]
            assert timed_out and "did not answer within 5 s" in timed_out[0]["error"], tries
            assert tries[-1]["transition"] == "activate" and tries[-1]["ok"], tries
            assert done["seconds"] < 40.0  # within --settle: it was not left for the next poll
            seen = probe(watch.env, ros2_domain, "/TALKER", wait_for=["/LISTENER"], python=python)
            assert seen["states"] == {"/TALKER": "active"}, (phase, seen)
            assert seen["dangling"]["subscriptions"] == [], seen
            if phase == "start":
                os.kill(watch.pids()["TALKER"], signal.SIGKILL)  # restarted in place: slow again
    finally:
        watch.stop(signal.SIGKILL)


def _robot_prefix(tmp: Path, python: Path, library: Path, faulty: tuple[str, ...]) -> Path:
    """Install every component of ``library`` as an executable: rosreconf's stand-in acting
    out its entry in full (as ``test_watch_wiring`` does), ``faulty`` ones under the fault
    injector, each picked by its ``__node:=`` rule."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.ros.standin_spec import ros2_standin_spec

    prefix = tmp / "install"
    chosen = "|".join(faulty)
    for comp in load_paths([library]).library.components:
        launch = comp.launch
        assert launch is not None
        (tmp / f"{comp.name}.json").write_text(json.dumps(ros2_standin_spec(comp)))
        run = f'"{STANDIN}" "$(cat "{tmp}/$n.json")" "$@"'
        _program(prefix, launch.package, launch.executable,
                 'for a in "$@"; do case "$a" in __node:=*) n="${a#__node:=}";; esac; done\n'
                 f'case "$n" in {chosen}) exec "{python}" "{FAULTS}" {run};; esac\n'
                 f'exec "{python}" {run}\n')  # fmt: skip
    return prefix


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_lifecycle_faults_that_last_are_repaired(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """NSM3 falls back to inactive after each activation: brought back once, then failed
    and replaced; NCA1's get_state server leaves discovery for good: read managed for 5 s
    more, then plain (``not-managed``), failed and replaced 5 s later. ``--hold 3``: with
    both held, no configuration meets the schema's performance requirements."""
    python = _python(distro)
    text = (ROOT / "libraries" / "robot_arms.yaml").read_text()
    for name in ("NCA1", "NSM3"):
        at = text.index("    ros:\n", text.index(f"  - name: {name}\n")) + len("    ros:\n")
        text = text[:at] + "      lifecycle: true\n" + text[at:]
    library = tmp_path / "two_managed.yaml"
    library.write_text(text)
    prefix = _robot_prefix(tmp_path, python, library, ("NCA1", "NSM3"))
    schema = str(ROOT / "schemas" / "object_repositioning.yaml")
    ament = _robot_env(tmp_path, prefix)
    watch = Watch(tmp_path, ros2_domain, "--library", str(library), "--schema", schema,
                  "--hold", "3", python=python, stand_ins=False, env=ament)  # fmt: skip
    try:
        watch.wait("conformant")
        for name, sig, how in (
            ("NSM3", signal.SIGUSR1, "lifecycle"),
            ("NCA1", signal.SIGUSR2, "not-managed"),
        ):
            before = len(watch.events())
            os.kill(watch.pids()[name], sig)
            failed = watch.wait("failed", after=before)
            assert (failed["component"], failed["how"]) == (name, how), failed
            replanned = watch.wait("replanned", after=watch.events().index(failed))
            assert replanned["failed"] == [name], replanned
            done = watch.wait("conformant", after=watch.events().index(replanned))
            said = watch.events()[before : watch.events().index(failed)]
            if name == "NSM3":  # said, and brought back first
                (fault,) = [e for e in said if e["event"] == "not-active"]
                assert fault["state"] == "inactive", fault
                assert [e["transition"] for e in said if e["event"] == "lifecycle"] == ["activate"]
        # (NSM3, released 3 s after its hold, may run again: a process of its own, started
        # anew, configured and activated; NCA1's faulty process was stopped, replaced)
        expected = {f"/{c}" for c in done["configuration"].values() if c}
        managed = sorted(expected & {"/NSM3"})
        seen = probe(watch.env, ros2_domain, *managed, wait_for=expected, python=python)
        assert expected <= set(seen["nodes"]) and "/NCA1" not in seen["nodes"], seen["nodes"]
        assert seen["states"] == dict.fromkeys(managed, "active"), seen["states"]
        assert seen["dangling"]["subscriptions"] == [], seen["dangling"]
        # a real executable acts out every alternative: the reasoner's calls to the arm that
        # is not running are its own, never wired; nothing else may dangle
        assert all(n == "/NREA" for n, _ in seen["dangling"]["calls"]), seen["dangling"]
    finally:
        watch.stop(signal.SIGKILL)
