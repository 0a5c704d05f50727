"""``rosreconf.model.switching``: what a task switch does to each component (issue 46).

The pure function ``plan --switch-to`` reports and a live watcher will perform; these tests
hold it to docs/pddl.md's table ("Task switches") without any solver or planner.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from rosreconf.formats.loader import load_bundled
from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    InteroperabilitySchema,
    Role,
    SystemGraph,
)
from rosreconf.model.switching import carried_over, count_changes, switch_changes
from rosreconf.solve.running import declared_nominal

DC_ARM = {
    "base_joint": "NDC1",
    "shoulder_joint": "NDC2",
    "elbow_joint": "NDC3",
    "wrist_joint": "NDC4",
    "gripper_joint": "NDC5",
    "camera": "NCA1",
    "gripper_sensor": "NCO1",
    "perception": "NVP1",
    "positioning": "NFB11",
    "grasping": "NFB12",
    "carrying": "NFB13",
    "placing": "NFB14",
    "reasoner": "NREA",
}


@pytest.fixture(scope="module")
def paper() -> tuple[ComponentLibrary, InteroperabilitySchema, InteroperabilitySchema]:
    loaded = load_bundled()
    schemas = {s.name: s for s in loaded.schemas}
    return loaded.library, schemas["object_repositioning"], schemas["disc_loading"]


def test_the_dc_arm_to_the_servo_arm_replaces_nine_and_restarts_the_reasoner(
    paper: tuple[ComponentLibrary, InteroperabilitySchema, InteroperabilitySchema],
) -> None:
    library, s1, s2 = paper
    nominal = declared_nominal(s2)
    assert nominal is not None
    moves = switch_changes(library, s1, DC_ARM, s2, nominal.mapping)
    kinds = {m.component: m.kind for m in moves}
    assert kinds["NDC3"] == "stop" and kinds["NSM3"] == "start" and kinds["NREA"] == "restart"
    assert kinds["NCA1"] == kinds["NVP1"] == "keep"
    start = next(m for m in moves if m.component == "NSM3")
    assert start.replaces == "NDC3" and str(start) == "start NSM3 as elbow_joint (in place of NDC3)"
    stop = next(m for m in moves if m.component == "NDC3")
    assert not stop.counted  # the replacement counts once, at its start
    assert "/arm_servo/" in next(m.why for m in moves if m.component == "NREA")
    assert count_changes(moves) == 10


def test_the_same_configuration_keeps_everything(
    paper: tuple[ComponentLibrary, InteroperabilitySchema, InteroperabilitySchema],
) -> None:
    library, s1, s2 = paper
    nominal = declared_nominal(s2)
    assert nominal is not None
    moves = switch_changes(library, s1, nominal.mapping, s2, nominal.mapping)
    assert {m.kind for m in moves} == {"keep"} and count_changes(moves) == 0


def test_a_component_s2_has_no_role_for_stops_and_a_new_role_starts(
    paper: tuple[ComponentLibrary, InteroperabilitySchema, InteroperabilitySchema],
) -> None:
    library, s1, s2 = paper
    roles = tuple(r for r in s2.graph.roles if r.name != "camera")  # S2 without the camera
    edges = tuple(e for e in s2.graph.edges if "camera" not in (e.consumer, e.provider))
    smaller = replace(s2, graph=SystemGraph(roles, edges))
    after = {r: c for r, c in DC_ARM.items() if r != "camera"}
    moves = switch_changes(library, s1, DC_ARM, smaller, after)
    camera = next(m for m in moves if m.component == "NCA1")
    assert (camera.kind, camera.role, camera.counted) == ("stop", "camera", True)
    assert "no role of its abstraction" in camera.why
    back = switch_changes(library, smaller, after, s1, DC_ARM)  # and the way back: a start
    camera = next(m for m in back if m.component == "NCA1")
    assert (camera.kind, camera.counted, camera.replaces) == ("start", True, "")


def test_components_pair_by_abstraction_when_s2_renames_a_role(
    paper: tuple[ComponentLibrary, InteroperabilitySchema, InteroperabilitySchema],
) -> None:
    _, s1, s2 = paper
    renamed = tuple(
        Role("eye", r.abstraction, r.description) if r.name == "camera" else r
        for r in s2.graph.roles
    )
    other = replace(s2, graph=SystemGraph(renamed, ()))
    carried = carried_over(s1, DC_ARM, other)
    assert carried["eye"] == "NCA1" and carried["base_joint"] == "NDC1"


def test_an_optional_role_left_empty_is_one_stop_and_filled_is_one_start() -> None:
    roles = (Role("a", "x"), Role("b", "y", optional=True))
    schema = InteroperabilitySchema("s", SystemGraph(roles, ()), "skill", "env")
    library = ComponentLibrary("l", (Component("A", "x"), Component("B", "y")))
    full, empty = {"a": "A", "b": "B"}, {"a": "A", "b": EMPTY}
    out = switch_changes(library, schema, full, schema, empty)
    assert [(m.component, m.kind, m.counted) for m in out] == [
        ("A", "keep", False),
        ("B", "stop", True),
    ]
    back = switch_changes(library, schema, empty, schema, full)
    assert [(m.component, m.kind) for m in back] == [("A", "keep"), ("B", "start")]
    assert count_changes(back) == 1
