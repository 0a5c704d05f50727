"""``watch`` sees nodes it did not start fail by their processes, not by the DDS lease (issue 31).

The team's own nodes are real rclpy processes started as their launch file would (wired by
``-r`` rules), with Fast DDS's default 20 s lease: a crash that only the lease showed would
be seen after 19-21 s. ``watch`` confirms each node's process through /proc and watches it,
so a ``kill -9`` is ``failed`` by ``process-exited`` and a SIGSTOP by ``process-hung``, each
said as seen by watching the process. No timing is asserted: ``make bench``'s.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from collections.abc import Mapping
from pathlib import Path

import pytest
from ros2_team import STANDIN, Member, Team, wait_ready
from test_watch_ros2 import NOMINAL, ROOT, Watch, _env, _ros2_python, probe, watched_by_process
from test_watch_wiring import _python

Node = subprocess.Popen[bytes] | Member
HANG = Path(__file__).with_name("ros2_hang_on_usr1.py")
"""The fault injector: the node's executor stops for good on SIGUSR1 (its process runs on)."""


def _team(
    tmp: Path,
    domain: int,
    library_file: Path | None = None,
    hang: str = "",
    python: Path | None = None,
    alone: Mapping[str, Mapping[str, str]] | None = None,
) -> tuple[Team, dict[str, Node]]:
    """Start the nominal configuration's 13 nodes as the team's launch file would.

    Each is its own rclpy process, wired by the ``-r`` rules a launch file gives it, with Fast
    DDS's default 20 s lease, forked from one warm process (``ros2_team``); each is up (it
    said ``ready``) when this returns. The library is the bundled one unless ``library_file``
    is given; ``hang`` runs under ``HANG``, a process of its own; the nodes run under
    ``python`` (default: the Jazzy venv's). ``alone``: components run as processes of their
    own, each with these variables added to its environment.
    """
    from rosreconf.formats.loader import load_bundled, load_paths
    from rosreconf.model import Configuration
    from rosreconf.ros.launchfiles import ros2_node_arguments, wiring
    from rosreconf.ros.standin_spec import ros2_standin_spec

    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
    library = load_paths([library_file]).library if library_file else bundle.library
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    remaps = wiring(library, schema, nominal)
    env = {**_env(tmp), "ROS_DOMAIN_ID": str(domain)}
    interpreter = python or _ros2_python()
    team = Team(interpreter, env, tmp / "team")
    ours: dict[str, Node] = {}
    try:
        for c in NOMINAL:
            argv = [str(interpreter), str(STANDIN), json.dumps(ros2_standin_spec(library[c]))]
            argv += ros2_node_arguments(library, c, remaps)
            if c == hang or c in (alone or {}):  # a process of its own
                wrapped = [argv[0], str(HANG), *argv[1:]] if c == hang else argv
                own = {**env, **(alone or {}).get(c, {})}
                quiet = subprocess.DEVNULL
                ours[c] = subprocess.Popen(wrapped, env=own, stdout=subprocess.PIPE, stderr=quiet)
            else:
                ours[c] = team.start(c, argv)
        for c, p in ours.items():  # all up before watch looks, or it would start its own
            if isinstance(p, subprocess.Popen):
                assert p.stdout is not None and b'"ready"' in p.stdout.readline(), c
        wait_ready({c: p for c, p in ours.items() if isinstance(p, Member)})
    except BaseException:
        _end(None, team, ours)
        raise
    return team, ours


def _end(watch: Watch | None, team: Team, ours: dict[str, Node]) -> None:
    """Stop the watch, then every team node left (a stopped one is resumed to be killed)."""
    if watch is not None:
        watch.stop(signal.SIGKILL)
    for p in ours.values():
        if p.poll() is None:
            p.send_signal(signal.SIGCONT)
            p.kill()
        p.wait()
    team.close()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # Fast DDS 2.14 and 3.2: GUID layouts
def test_outside_nodes_are_watched_by_their_processes_crash_and_hang_seen_so(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    team, ours = _team(tmp_path, ros2_domain, python=python)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", python=python)
        watch.wait("running")
        assert not watch.pids()  # it started none of them
        every = {f"/{c}" for c in NOMINAL}  # every node found and watched by its process
        events = watch.until(lambda ev: every <= watched_by_process(ev).keys(),
                             "'watched' by its process for every node")  # fmt: skip
        by_process = watched_by_process(events)
        assert all(by_process[f"/{c}"] == ours[c].pid for c in NOMINAL), by_process
        before = len(watch.events())
        os.kill(ours["NCA1"].pid, signal.SIGSTOP)  # hung: the process runs no more
        hung = watch.wait("failed", after=before)
        assert (hung["component"], hung["how"], hung["outside"]) == ("NCA1", "process-hung", True)
        before = len(watch.events())
        ours["NSM3"].kill()
        crash = watch.wait("failed", after=before, timeout=15.0)  # well inside the 20 s lease
        assert (crash["component"], crash["how"]) == ("NSM3", "process-exited")
        # (no configuration is left without both NCA1 and NSM3 that meets the schema's
        # performance requirements: watch says so and keeps watching)
    finally:
        _end(watch, team, ours)


def test_an_impostor_named_like_a_component_is_a_name_clash_never_the_component(
    ros2_domain: int, tmp_path: Path
) -> None:
    """An outside node named /NSM3 with none of NSM3's endpoints is not NSM3: watch says the
    clash, fails NSM3 and moves the configuration away from it; the impostor keeps running."""
    env = {**_env(tmp_path), "ROS_DOMAIN_ID": str(ros2_domain)}
    other = [{"service": "/not/a/servo", "type": "std_srvs/srv/Trigger"}]
    spec = json.dumps({"name": "NSM3", "namespace": "/", "serve": other})
    impostor = subprocess.Popen([str(_ros2_python()), str(STANDIN), spec], env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    watch: Watch | None = None
    try:
        assert impostor.stdout is not None and b'"ready"' in impostor.stdout.readline()
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning")
        clash = watch.wait("failed")
        assert (clash["component"], clash["how"], clash["node"]) == ("NSM3", "name-clash", "/NSM3")
        assert "name clash" in clash["message"]
        assert not [e for e in watch.events() if e["event"] == "running"]  # never "all run"
        watch.wait("conformant", after=watch.events().index(clash))
        (replanned,) = [e for e in watch.events() if e["event"] == "replanned"]
        assert replanned["failed"] == ["NSM3"], replanned
        assert "NDC3" in watch.pids() and "NSM3" not in watch.pids()
        assert impostor.poll() is None  # not rosreconf's: left running
    finally:
        if watch is not None:
            watch.stop(signal.SIGKILL)
        impostor.kill()
        impostor.wait()


def test_a_hung_outside_node_is_failed_and_with_stop_outside_its_process_is_gone(
    ros2_domain: int, tmp_path: Path
) -> None:
    """SIGSTOP of a team's node: failed as hung, replaced, and (--stop-outside) its process
    stopped though it is stopped itself (stopproc resumes it after each signal)."""
    team, ours = _team(tmp_path, ros2_domain)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--stop-outside")
        watch.wait("running")
        watch.until(lambda ev: "/NCA1" in watched_by_process(ev), "'watched' of /NCA1")
        before = len(watch.events())
        os.kill(ours["NCA1"].pid, signal.SIGSTOP)
        hung = watch.wait("failed", after=before)
        assert (hung["component"], hung["how"]) == ("NCA1", "process-hung")
        stop = watch.wait("stop", after=before)
        while stop["component"] != "NCA1":  # the replaced NCO1 and NVP1 are stopped too
            stop = watch.wait("stop", after=watch.events().index(stop) + 1)
        assert (stop["how"], stop["pid"]) == ("signal", ours["NCA1"].pid)
        assert ours["NCA1"].wait(5) is not None  # gone: stopped by rosreconf, not by the test
    finally:
        _end(watch, team, ours)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # the state query over plain DDS
def test_a_managed_outside_node_that_stops_answering_is_hung_failed_and_its_process_stopped(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """A managed team node whose executor stops (its process runs on, state S): it answered
    its state query before and answers no more, so it is failed as hung (``unanswered``),
    replaced, and with --stop-outside its process is stopped."""
    text = (ROOT / "libraries" / "robot_arms.yaml").read_text()
    at = text.index("    ros:\n", text.index("  - name: NCA1\n")) + len("    ros:\n")
    library = tmp_path / "nca1_managed.yaml"
    library.write_text(text[:at] + "      lifecycle: true\n" + text[at:])
    python = _python(distro)
    team, ours = _team(tmp_path, ros2_domain, library, hang="NCA1", python=python)
    watch: Watch | None = None
    try:
        schema = str(ROOT / "schemas" / "object_repositioning.yaml")
        watch = Watch(tmp_path, ros2_domain, "--library", str(library), "--schema", schema,
                      "--stop-outside", python=python)  # fmt: skip
        first = watch.wait("conformant")  # NCA1 (unconfigured) made active first
        assert {e["component"] for e in watch.events() if e.get("state") == "active"} == {"NCA1"}
        before = watch.events().index(first) + 1
        os.kill(ours["NCA1"].pid, signal.SIGUSR1)
        hung = watch.wait("failed", after=before)
        assert (hung["component"], hung["how"], hung["node"]) == ("NCA1", "unanswered", "/NCA1")
        assert ours["NCA1"].poll() is None  # its process ran on: no exit, no stop showed it
        stop = watch.wait("stop", after=before)
        while stop["component"] != "NCA1":  # the other replaced nodes are stopped too
            stop = watch.wait("stop", after=watch.events().index(stop) + 1)
        assert (stop["how"], stop["pid"]) == ("signal", ours["NCA1"].pid)
        assert ours["NCA1"].wait(5) is not None  # gone: stopped by rosreconf, not by the test
        (replanned,) = [e for e in watch.events() if e["event"] == "replanned"]
        assert replanned["failed"] == ["NCA1"], replanned
        # (the kept team nodes that must be rewired are named "restart this by hand":
        # rosreconf cannot restart what it did not start, so no conformant is awaited here)
    finally:
        _end(watch, team, ours)


def _forged_profile(tmp: Path, pid: int) -> Path:
    """Write a Fast DDS profile that gives every participant this host's id and ``pid``'s bits.

    The attack of the hostile round: one XML line, and the GUID says another process runs
    the node (``rosreconf.ros.ros2.fastdds_ids``: bytes 2-3 the host id, 4-5 the pid's low
    16 bits, both little endian).
    """
    from rosreconf.ros.ros2.fastdds_ids import this_host_id

    host = this_host_id()
    prefix = bytes([0x01, 0x0F, host & 0xFF, host >> 8, pid & 0xFF, (pid >> 8) & 0xFF,
                    0x5A, 0x5A, 0, 0, 0, 1])  # fmt: skip
    path = tmp / "forged.xml"
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<dds xmlns="http://www.eprosima.com"><profiles>'
        '<participant profile_name="forged" is_default_profile="true"><rtps><prefix>'
        + ".".join(f"{b:02x}" for b in prefix)
        + "</prefix></rtps></participant></profiles></dds>\n"
    )
    return path


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # Fast DDS 2.14 and 3.2
def test_a_forged_guid_never_gets_a_bystander_signalled(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """NSM3's participant claims, in its GUID, to be another team's node on the domain (the
    bystander). watch may take the bystander for NSM3's process, but with --stop-outside it
    must not signal it when the arm is replaced: the kernel says NSM3's datagrams come from
    another process's sockets, so NSM3 is named for a person. The bystander lives, the real
    NSM3 runs on, and the genuine nodes replaced beside it are still stopped."""
    python = _python(distro)
    env = {**_env(tmp_path), "ROS_DOMAIN_ID": str(ros2_domain)}
    spec = json.dumps({"name": "other_team_node", "namespace": "/"})
    bystander = subprocess.Popen([str(python), str(STANDIN), spec], env=env,
                                 stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    team: Team | None = None
    ours: dict[str, Node] = {}
    watch: Watch | None = None
    try:
        assert bystander.stdout is not None and b'"ready"' in bystander.stdout.readline()
        profile = str(_forged_profile(tmp_path, bystander.pid))
        forged = {
            "FASTRTPS_DEFAULT_PROFILES_FILE": profile,
            "FASTDDS_DEFAULT_PROFILES_FILE": profile,
        }
        team, ours = _team(tmp_path, ros2_domain, python=python, alone={"NSM3": forged})
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--stop-outside",
                      python=python)  # fmt: skip
        watch.wait("running")
        events = watch.until(lambda ev: {"/NSM3", "/NSM1"} <= watched_by_process(ev).keys(),
                             "'watched' of /NSM3 and /NSM1")  # fmt: skip
        watched = watched_by_process(events)
        assert watched["/NSM3"] == bystander.pid  # the forgery took: the GUID names it
        before = len(watch.events())
        ours["NSM1"].kill()  # the servo arm goes: NSM3 and its neighbours are replaced
        by_hand = watch.wait("stop-by-hand", after=before)
        while by_hand["component"] != "NSM3":
            by_hand = watch.wait("stop-by-hand", after=watch.events().index(by_hand) + 1)
        said = watch.events()[before:]
        assert "not proven" in by_hand["message"], by_hand["message"]
        assert str(bystander.pid) in by_hand["message"]
        assert f"process(es) [{ours['NSM3'].pid}] do" in by_hand["message"]  # the real sender
        assert not [e for e in said if e["event"] == "stop" and e.get("pid") == bystander.pid]
        stopped = {e["component"] for e in said if e["event"] == "stop" and e["how"] == "signal"}
        assert "NSM2" in stopped, [e["message"] for e in said]  # genuine ones: proven, stopped
        assert bystander.poll() is None  # alive: never signalled
        assert ours["NSM3"].poll() is None  # the real NSM3 runs on, for a person to stop
    finally:
        if team is not None:
            _end(watch, team, ours)
        elif watch is not None:
            watch.stop(signal.SIGKILL)
        bystander.kill()
        bystander.wait()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # Fast DDS 2.14 and 3.2: GUID layouts
def test_an_outside_node_killed_before_its_process_is_found_is_failed_at_once(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """kill -9 of a team's node right after watch first sees it, before its process is looked
    for (the next poll looks: ``--interval 5``). Its participant is announced until its 20 s
    lease ends, but its GUID names this host and a pid no process here has, while every socket
    of the domain here is a process's watch can see: it is failed at that poll."""
    python = _python(distro)
    team, ours = _team(tmp_path, ros2_domain, python=python)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--interval", "5",
                      python=python)  # fmt: skip
        running = watch.wait("running")
        ours["NCA1"].kill()
        killed = time.monotonic()
        looked = [e for e in watch.events() if e["event"] == "watched"]
        assert not looked, f"the test was too slow: its process was looked for already {looked}"
        failed = watch.wait("failed", after=watch.events().index(running) + 1, timeout=30.0)
        seen = time.monotonic() - killed
        assert (failed["component"], failed["how"]) == ("NCA1", "process-exited"), failed
        assert seen < 15.0, seen  # one poll, well inside the lease (18.9-20.8 s measured)
        gone = [e for e in watch.events() if e["event"] == "watched" and e["how"] == "gone"]
        assert [e["nodes"] for e in gone] == [["/NCA1"]], gone
        assert "no process here has the pid" in gone[0]["why"]
        replanned = watch.wait("replanned", after=watch.events().index(failed))
        assert replanned["failed"] == ["NCA1"] and replanned["configuration"]["camera"] == "NCA2"
        watch.wait("launch", after=watch.events().index(replanned))
        seen_graph = probe(watch.env, ros2_domain, wait_for=["/NCA2"], python=python)
        assert "/NCA2" in seen_graph["nodes"]  # the replacement runs, as rclpy's graph shows
        assert ours["NCA1"].poll() is not None
    finally:
        _end(watch, team, ours)
