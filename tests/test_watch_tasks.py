"""A running ``watch --ros2`` switches task when its face's ``task`` parameter is set (issue 46).

The paper's robot runs Object Repositioning on the DC arm, real rclpy stand-ins under Jazzy
and Kilted. The tests' own rclpy client (tests/ros2_face_client.py) sets the face's
parameter, reads its descriptors, and listens to ``/diagnostics`` and ``/rosout``; what watch
did is read from its JSON log, the end state from rclpy's own graph (tests/ros2_probe.py) and
from ``rosreconf inspect``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from datetime import datetime
from pathlib import Path
from typing import Any

import pytest
from test_tasks import DC_ARM, DL, OR, SERVO, _brute_force, _on_dc_arm
from test_watch_ros2 import Watch, _env, probe
from test_watch_wiring import _python

CLIENT = Path(__file__).with_name("ros2_face_client.py")
ROLES = len(DC_ARM)


def _dc_arm_file(tmp: Path) -> Path:
    path = tmp / "dc_arm.json"
    path.write_text(json.dumps({"format": "rosreconf/configuration", "version": 1,
                                "configurations": {"object_repositioning": DC_ARM}}))  # fmt: skip
    return path


def _client(python: Path, env: dict[str, str], *args: str) -> dict[str, Any]:
    out = subprocess.run([str(python), str(CLIENT), *args], env=env, capture_output=True,
                         text=True, timeout=120, check=False)  # fmt: skip
    assert out.returncode == 0, out.stderr[-2000:]
    return dict(json.loads(out.stdout.splitlines()[-1]))


def listen(python: Path, env: dict[str, str], heard: Path) -> subprocess.Popen[str]:
    """Start the tests' listener to /diagnostics and /rosout, writing to ``heard``; return
    once it listens."""
    argv = [str(python), str(CLIENT), "listen", str(heard)]
    listener = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True)  # fmt: skip
    assert listener.stdout is not None and "listening" in listener.stdout.readline()
    return listener


def _heard(path: Path, topic: str) -> list[dict[str, Any]]:
    if not path.exists():
        return []
    lines = [json.loads(x) for x in path.read_text().splitlines() if x.endswith("}")]
    return [x for x in lines if x["topic"] == topic]


def _at(event: dict[str, Any]) -> float:
    return datetime.fromisoformat(event["time"]).timestamp()


def _role_levels(path: Path, role: str) -> list[tuple[float, int, str]]:
    """Return (wall time, level, component) of ``role`` in every /diagnostics message."""
    out = []
    for msg in _heard(path, "/diagnostics"):
        for s in msg["status"]:
            if s["name"] == f"rosreconf: role/{role}":
                out.append((msg["at"], s["level"], s["values"]["component"]))
    return out


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_setting_task_switches_to_disc_loading_with_the_fewest_changes(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--configuration",
                  str(_dc_arm_file(tmp_path)), python=python)  # fmt: skip
    env = {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)}
    heard = tmp_path / "heard.jsonl"
    listener = listen(python, env, heard)
    try:
        first = watch.wait("conformant")
        assert first["task"] == "object_repositioning"
        params = _client(python, env, "get", "/rosreconf")
        assert params["task"]["value"] == "object_repositioning"
        assert "disc_loading" in params["task"]["constraints"]
        assert params["configuration"]["read_only"] and params["failed"]["read_only"]
        assert "elbow_joint=NDC3" in params["configuration"]["value"]
        before = len(watch.events())
        # asked twice, the second right after the first answer (a client resends when an
        # answer is lost): both taken, one switch
        answer = _client(python, env, "set", "/rosreconf", "disc_loading", "again")
        assert answer["successful"] and answer["again"]["successful"], answer
        done = watch.wait("conformant", after=before)
        after = watch.events()[before:]
        (task,) = [e for e in after if e["event"] == "task"]
        assert task["task"] == "disc_loading" and done["task"] == "disc_loading"
        # the changes performed are the brute-force minimum, counted by the tests alone
        assert len(task["changes"]) == _brute_force(_on_dc_arm(), OR, DL, frozenset())
        assert sorted(c["to"] for c in task["changes"]) == sorted([*SERVO, "NREA"])
        assert {c: done["configuration"][r] for r, c in DC_ARM.items()}["NDC3"] == "NSM3"
        stopped = {e["component"] for e in after if e["event"] == "stop"}
        assert {"NDC1", "NDC2", "NDC3", "NDC4", "NDC5"} <= stopped
        assert not {"NCA1", "NCO1", "NVP1"} & stopped  # kept, untouched
        argv = [sys.executable, "-m", "rosreconf", "inspect", "--ros2", "--domain",
                str(ros2_domain), "--only", "disc_loading"]  # fmt: skip
        out = subprocess.run(argv, env=watch.env, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stdout[-3000:]
        nodes = {f"/{c}" for c in done["configuration"].values() if c}
        seen = probe(watch.env, ros2_domain, wait_for=nodes, until_wired=True, python=python)
        assert nodes <= set(seen["nodes"]) and seen["dangling"] == {
            "calls": [],
            "subscriptions": [],
        }
        assert _client(python, env, "get", "/rosreconf")["task"]["value"] == "disc_loading"

        # /diagnostics: one status per role and one for conformance; a killed node's role
        # turns ERROR, and OK after the repair
        last = _heard(heard, "/diagnostics")[-1]
        names = [s["name"] for s in last["status"]]
        assert len(names) == ROLES + 1 and "rosreconf: conformance" in names
        assert len({n for n in names if n.startswith("rosreconf: role/")}) == ROLES
        assert all(s["hardware_id"] == "rosreconf" for s in last["status"])
        assert all(s["level_type"] == "bytes" for s in last["status"])
        assert last["stamp"] > 0
        before = len(watch.events())
        os.kill(watch.pids()["NCA1"], signal.SIGKILL)
        repaired = watch.wait("conformant", after=before)
        failed = next(e for e in watch.events()[before:] if e["event"] == "failed")
        time.sleep(1.5)
        levels = _role_levels(heard, "camera")
        error = next(at for at, level, comp in levels if level == 2 and comp == "NCA1")
        ok = next(at for at, level, comp in levels if at > error and level == 0)
        assert error - _at(failed) <= 1.0, (error, _at(failed))
        assert ok - _at(repaired) <= 1.0, (ok, _at(repaired))
        rosout = [m for m in _heard(heard, "/rosout") if m["name"].endswith("rosreconf")]
        by_level = {(m["level"], m["msg"].split(" ")[0]) for m in rosout}
        assert any(level == 40 and "NCA1" in m["msg"] for m in rosout for level in [m["level"]])
        assert any(m["level"] == 30 and m["msg"].startswith("replanned") for m in rosout), by_level
        assert any(m["level"] == 20 and "conforms" in m["msg"] for m in rosout), by_level
    finally:
        listener.kill()
        watch.stop(signal.SIGKILL)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_with_nsm3_failed_the_switch_is_refused_and_nothing_stops(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--configuration",
                  str(_dc_arm_file(tmp_path)), "--fail", "NSM3", python=python)  # fmt: skip
    env = {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)}
    try:
        watch.wait("conformant")
        before = len(watch.events())
        answer = _client(python, env, "set", "/rosreconf", "disc_loading")
        assert not answer["successful"] and "NSM3" in answer["reason"], answer
        assert answer["seconds"] < 0.5, answer  # the goal is 50 ms; measured by make bench
        refused = watch.wait("task-refused", after=before, timeout=30)
        assert "NSM3" in refused["reason"]
        time.sleep(2.0)
        kinds = {e["event"] for e in watch.events()[before:]}
        assert not kinds & {"task", "stop", "launch", "replanned"}, kinds
        assert _client(python, env, "get", "/rosreconf")["task"]["value"] == "object_repositioning"
        # rosreconf task: the same refusal, as an exit code and the reason, with no ROS 2 tools
        ask = [sys.executable, "-m", "rosreconf", "task", "--domain", str(ros2_domain)]
        out = subprocess.run([*ask, "disc_loading"], env=watch.env, capture_output=True,
                             text=True, timeout=120)  # fmt: skip
        assert out.returncode == 1 and "NSM3" in out.stdout, (out.stdout, out.stderr)
        out = subprocess.run([*ask, "--face-name", "/rosreconf_none", "--timeout", "2",
                              "disc_loading"], env=watch.env, capture_output=True, text=True,
                             timeout=120)  # fmt: skip
        assert out.returncode == 3 and "/rosreconf_none" in out.stderr, (out.stdout, out.stderr)
        kinds = {e["event"] for e in watch.events()[before:]}
        assert not kinds & {"task", "stop", "launch", "replanned"}, kinds
    finally:
        watch.stop(signal.SIGKILL)


LOSES_FIRST_ANSWER = """
import json, sys
import rclpy
from rcl_interfaces.msg import SetParametersResult
from rcl_interfaces.srv import SetParameters

rclpy.init()
node = rclpy.create_node("rosreconf", start_parameter_services=False)
asked = []

def answer(request, response):
    asked.append(request.parameters[0].value.string_value)
    print(json.dumps({"asked": asked[-1]}), flush=True)
    response.results = [SetParametersResult(successful=True)]
    return response

service = node.create_service(SetParameters, "/rosreconf/set_parameters", answer)
send = service.send_response

def lose_first(response, header):
    if len(asked) > 1:
        send(response, header)

service.send_response = lose_first
print(json.dumps({"ready": True}), flush=True)
rclpy.spin(node)
"""
"""A face stand-in whose first answer is lost, as a Fast DDS service loses its answer to a
client it has not matched both ways yet (rclpy: "failed to send response (timeout)")."""


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_rosreconf_task_asks_again_when_the_answer_is_lost(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    env = {**_env(tmp_path, python), "ROS_DOMAIN_ID": str(ros2_domain)}
    argv = [str(python), "-c", LOSES_FIRST_ANSWER]
    face = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True)  # fmt: skip
    try:
        assert face.stdout is not None and "ready" in face.stdout.readline()
        ask = [sys.executable, "-m", "rosreconf", "task", "--domain", str(ros2_domain)]
        out = subprocess.run([*ask, "disc_loading"], env=env, capture_output=True, text=True,
                             timeout=120)  # fmt: skip
        assert out.returncode == 0 and "took the switch" in out.stdout, (out.stdout, out.stderr)
    finally:
        face.kill()
    asked = [json.loads(x)["asked"] for x in face.communicate()[0].splitlines() if "asked" in x]
    assert asked[:2] == ["disc_loading", "disc_loading"], asked
