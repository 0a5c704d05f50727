"""A task switch (issue 46): its changes are the brute-force minimum, its refusals say why.

Pure: no ROS. The live switch is tests/test_watch_tasks.py's; here the target
(``tasks.switch_target``), the request queue, the feasibility table and the face's tables
(``facestate``) are checked on the paper's robot.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from rosreconf.formats.loader import load_bundled
from rosreconf.model import Configuration, InteroperabilitySchema
from rosreconf.model.validity import is_valid
from rosreconf.model.wiring import wiring_of
from rosreconf.planning.planners import planner_named
from rosreconf.planning.switch import switch
from rosreconf.ros.events import Event
from rosreconf.ros.facestate import ERROR, OK, WARN, Health, level_of, role_rows, snapshot
from rosreconf.ros.ros1.source import MasterSource
from rosreconf.ros.tasks import Tasks, feasibility, switch_target
from rosreconf.ros.watcher import Watcher

DC_ARM = {"base_joint": "NDC1", "shoulder_joint": "NDC2", "elbow_joint": "NDC3",
          "wrist_joint": "NDC4", "gripper_joint": "NDC5", "camera": "NCA1",
          "gripper_sensor": "NCO1", "perception": "NVP1", "positioning": "NFB11",
          "grasping": "NFB12", "carrying": "NFB13", "placing": "NFB14",
          "reasoner": "NREA"}  # fmt: skip
SERVO = ["NSM1", "NSM2", "NSM3", "NSM4", "NSM5", "NFB21", "NFB22", "NFB23", "NFB24"]

BUNDLE = load_bundled()
LIBRARY = BUNDLE.library
SCHEMAS = {s.name: s for s in BUNDLE.schemas}
OR, DL = SCHEMAS["object_repositioning"], SCHEMAS["disc_loading"]


def _on_dc_arm() -> Configuration:
    return Configuration.of(OR.name, DC_ARM, OR.graph.roles)


def _brute_force(running: Configuration, s1: InteroperabilitySchema, s2: InteroperabilitySchema,
                 failed: frozenset[str]) -> int:  # fmt: skip
    """Return the fewest changes of any valid configuration of ``s2`` from ``running``.

    Counted here, role by role: a role of ``s2`` whose component is not the running one of
    the same role, a kept one whose wiring changes (it restarts), and a running component on
    a role ``s2`` does not have that the new configuration does not use (stopped).
    """
    roles = s2.graph.roles
    by_role = {r.name for r in roles}
    doms = [[c.name for c in LIBRARY.candidates(r.abstraction)] for r in roles]
    old = running.mapping
    before = wiring_of(LIBRARY, s1, old)
    best: int | None = None
    for combo in itertools.product(*doms):
        mapping = dict(zip([r.name for r in roles], combo, strict=True))
        config = Configuration.of(s2.name, mapping, roles)
        if not is_valid(config, LIBRARY, s2, failed):
            continue
        after = wiring_of(LIBRARY, s2, mapping)
        n = sum(old.get(r) != c or before.get(r) != after.get(r) for r, c in mapping.items())
        # a running component on no role of s2 (its role changes are counted above) stops
        n += len({c for r, c in old.items() if r not in by_role} - set(mapping.values()))
        best = n if best is None else min(best, n)
    assert best is not None
    return best


def test_the_switch_to_disc_loading_is_the_brute_force_minimum() -> None:
    found = switch_target(LIBRARY, OR, _on_dc_arm(), DL, frozenset())
    assert found is not None
    new, changes = found
    assert [new.mapping[r] for r in DC_ARM if r.endswith("_joint")] == SERVO[:5]
    assert len(changes) == _brute_force(_on_dc_arm(), OR, DL, frozenset())
    moved = {r: (a, b) for r, a, b in changes}
    assert moved["reasoner"] == ("NREA", "NREA")  # kept, restarted: it calls the servo arm now
    assert sorted(b for _, _, b in changes) == sorted([*SERVO, "NREA"])
    assert {"camera", "gripper_sensor", "perception"}.isdisjoint(moved)


@pytest.mark.parametrize("failed", [frozenset(), frozenset({"NCA1"}), frozenset({"NVP1"})])
def test_back_to_object_repositioning_is_the_brute_force_minimum(failed: frozenset[str]) -> None:
    running = Configuration.of(DL.name, DL.nominal, DL.graph.roles)
    found = switch_target(LIBRARY, DL, running, OR, failed)
    assert found is not None
    assert len(found[1]) == _brute_force(running, DL, OR, failed)


def test_with_nsm3_failed_disc_loading_is_refused_with_the_reason() -> None:
    assert switch_target(LIBRARY, OR, _on_dc_arm(), DL, {"NSM3"}) is None
    said: list[tuple[str, str, dict[str, object]]] = []
    tasks = Tasks(SCHEMAS)
    tasks.ask("disc_loading")
    task = tasks.take(lambda k, m, **d: said.append((k, m, d)))
    assert task == "disc_loading"
    found = tasks.decide(LIBRARY, task, _on_dc_arm(), OR, {"NSM3"},
                         lambda k, m, **d: said.append((k, m, d)))  # fmt: skip
    assert found is None and tasks.switching is None
    ((kind, message, data),) = said
    assert kind == "task-refused" and "NSM3" in str(data["reason"]) and "NSM3" in message


def test_a_request_while_a_switch_is_under_way_is_refused_not_queued() -> None:
    said: list[tuple[str, dict[str, object]]] = []
    tasks = Tasks(SCHEMAS)
    tasks.ask("disc_loading")
    tasks.ask("object_repositioning")
    assert tasks.take(lambda k, m, **d: said.append((k, d))) == "disc_loading"
    assert [k for k, _ in said] == ["task-refused"]
    assert "under way" in str(said[0][1]["reason"])
    tasks.switching = "disc_loading"
    tasks.ask("object_repositioning")
    assert tasks.take(lambda k, m, **d: said.append((k, d))) is None
    tasks.show(LIBRARY, DL, _on_dc_arm(), set(), set(), Event("conformant", "ok"))
    assert tasks.switching is None


def test_the_feasibility_table_has_a_verdict_and_reason_per_task() -> None:
    table = {v.task: v for v in feasibility(LIBRARY, SCHEMAS, OR.name, _on_dc_arm(), set())}
    assert table["object_repositioning"].ok and table["object_repositioning"].changes == 0
    assert table["disc_loading"].ok and table["disc_loading"].changes == 10
    failed = {v.task: v for v in feasibility(LIBRARY, SCHEMAS, OR.name, _on_dc_arm(), {"NSM3"})}
    assert not failed["disc_loading"].ok and "NSM3" in failed["disc_loading"].reason


def test_a_watcher_switches_task_on_request_and_says_it(tmp_path: Path) -> None:
    events: list[Event] = []
    tasks = Tasks(SCHEMAS)
    watcher = Watcher(MasterSource("http://127.0.0.1:9"), LIBRARY, OR, _on_dc_arm(), tmp_path,
                      {}, events.append, tasks=tasks)  # fmt: skip
    tasks.ask("disc_loading")
    assert not watcher._retask()  # without --apply: decided, said, nothing to confirm
    assert watcher.schema is DL and watcher.current.schema == DL.name
    (said,) = [e for e in events if e.kind == "task"]
    assert said.data["task"] == "disc_loading" and len(said.data["changes"]) == 10
    assert tasks.switching is None  # without --apply a switch is over once said
    tasks.ask("disc_loading")  # the task running now
    assert not watcher._retask()
    assert events[-1].kind == "task-refused" and "running now" in events[-1].message


@pytest.mark.parametrize(
    ("mapping_change", "failed", "running", "level"),
    [
        ({}, set(), set(DC_ARM.values()), OK),
        ({}, {"NDC3"}, set(DC_ARM.values()), ERROR),
        ({}, set(), set(DC_ARM.values()) - {"NDC3"}, WARN),
    ],
)
def test_the_role_rows_say_ok_warn_error(
    mapping_change: dict[str, str], failed: set[str], running: set[str], level: int
) -> None:
    rows = {r["name"]: r for r in role_rows(LIBRARY, OR, _on_dc_arm(), failed, running)}
    assert len(rows) == len(OR.graph.roles)
    elbow = rows["rosreconf: role/elbow_joint"]
    assert elbow["level"] == level and elbow["hardware_id"] == "rosreconf"
    assert elbow["values"] == [["component", "NDC3"], ["node", "/NDC3"]]
    others = [r["level"] for n, r in rows.items() if n != "rosreconf: role/elbow_joint"]
    assert set(others) == {OK}


def test_a_missing_standby_warns_on_its_role_until_it_is_configured() -> None:
    health = Health()
    health.saw(Event("no-standby", "NSM3 cannot wait as a standby", {"component": "NSM3"}))
    running = set(DC_ARM.values())
    rows = {r["name"]: r for r in role_rows(LIBRARY, OR, _on_dc_arm(), set(), running,
                                            health.no_standby)}  # fmt: skip
    assert rows["rosreconf: role/elbow_joint"]["level"] == WARN
    assert "standby missing" in rows["rosreconf: role/elbow_joint"]["message"]
    assert rows["rosreconf: role/base_joint"]["level"] == OK
    health.saw(Event("lifecycle", "configured", {"component": "NSM3", "transition": "configure",
                                                 "ok": True}))  # fmt: skip
    assert health.no_standby == {}


def test_the_conformance_row_follows_the_events() -> None:
    health = Health()
    doc = snapshot(LIBRARY, OR, _on_dc_arm(), set(), set(), health, [], None)
    assert doc["diagnostics"][-1]["name"] == "rosreconf: conformance"
    assert doc["diagnostics"][-1]["level"] == WARN
    health.saw(Event("not-conformant", "still not", {"findings": ["/NDC3 is missing"]}))
    assert health.level == ERROR and health.findings == ["/NDC3 is missing"]
    health.saw(Event("conformant", "conforms"))
    assert (health.level, health.findings) == (OK, [])


@pytest.mark.parametrize(
    ("kind", "level"),
    [("failed", "error"), ("no-configuration", "error"), ("replanned", "warn"),
     ("task-refused", "warn"), ("conformant", "info"), ("task", "info"), ("why", "info"),
     ("helper", "debug")],
)  # fmt: skip
def test_every_decision_has_a_rosout_level(kind: str, level: str) -> None:
    assert level_of(kind) == level


def test_a_failure_after_a_switch_is_replanned_within_the_new_task(tmp_path: Path) -> None:
    events: list[Event] = []
    tasks = Tasks(SCHEMAS)
    watcher = Watcher(MasterSource("http://127.0.0.1:9"), LIBRARY, OR, _on_dc_arm(), tmp_path,
                      {}, events.append, tasks=tasks)  # fmt: skip
    tasks.ask("disc_loading")
    watcher._retask()
    watcher.failed = {"NCA1"}
    watcher._replan()
    (replanned,) = [e for e in events if e.kind == "replanned"]
    assert watcher.current.schema == "disc_loading"
    assert replanned.data["configuration"]["camera"] == "NCA2"
    assert replanned.data["configuration"]["elbow_joint"] == "NSM3"  # Disc Loading's arm
    watcher.failed = {"NCA1", "NSM3"}  # Disc Loading cannot do without it: said, not left
    watcher._hopeless = None
    watcher._replan()
    (none,) = [e for e in events if e.kind == "no-configuration"]
    assert "NSM3" in none.message


@pytest.mark.parametrize(
    "failed", [frozenset(), frozenset({"NCA1"}), frozenset({"NVP1"}), frozenset({"NSM1"})]
)
def test_the_live_switch_and_plan_switch_to_agree(failed: frozenset[str]) -> None:
    """The live watcher and ``plan --switch-to`` make the same switch, counted alike, or
    both find none (NSM1 is Disc Loading's only base joint)."""
    found = switch_target(LIBRARY, OR, _on_dc_arm(), DL, failed)
    planned = switch(LIBRARY, OR, DC_ARM, DL, failed, planner_named("fd", None))
    if found is None or planned.result.configuration is None:
        assert found is None and planned.result.configuration is None and "NSM1" in failed
        return
    assert found[0].mapping == planned.result.configuration.mapping
    assert len(found[1]) == planned.count == planned.result.fewest_changes
