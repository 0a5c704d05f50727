"""Tests of rosreconf.ros.livegraph: snapshots read and written without any master.

Snapshots in ``snapshots/valid`` must load and survive a round trip; each file in
``snapshots/invalid`` is named ``<problem code>--<what is wrong>.json`` and must be refused
with that code.
"""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path

import pytest

from rosreconf.errors import InvalidInputError
from rosreconf.ros.livegraph import (
    SNAPSHOT_FORMAT,
    LiveGraph,
    LiveNode,
    from_json,
    to_json,
    without_plumbing,
)

SNAPSHOTS = Path(__file__).with_name("snapshots")
VALID = sorted((SNAPSHOTS / "valid").glob("*.json"))
INVALID = sorted((SNAPSHOTS / "invalid").glob("*.json"))


@pytest.mark.parametrize("path", VALID, ids=[p.stem for p in VALID])
def test_valid_snapshot_round_trips(path: Path) -> None:
    text = path.read_text()
    graph = from_json(text, str(path))
    assert to_json(graph) == text
    assert from_json(to_json(graph)) == graph


@pytest.mark.parametrize("path", INVALID, ids=[p.stem for p in INVALID])
def test_invalid_snapshot_is_refused_with_its_code(path: Path) -> None:
    code = path.stem.split("--")[0]
    with pytest.raises(InvalidInputError) as err:
        from_json(path.read_text(), str(path))
    assert code in {p.code for p in err.value.problems}
    assert all(p.span.file == str(path) for p in err.value.problems)


def test_not_json_points_at_line_and_column() -> None:
    with pytest.raises(InvalidInputError) as err:
        from_json('{\n  "format": ,\n}', "snap.json")
    (problem,) = err.value.problems
    assert (problem.span.line, problem.span.column) == (2, 13)


def test_schema_problem_names_the_json_path() -> None:
    with pytest.raises(InvalidInputError, match=r"nodes\[0\]\.pid"):
        from_json((SNAPSHOTS / "invalid" / "schema--pid-is-text.json").read_text())


def test_recorded_snapshot_without_plumbing() -> None:
    graph = without_plumbing(from_json((SNAPSHOTS / "valid" / "arm_and_reasoner.json").read_text()))
    assert graph.names == ("/arm", "/reasoner")
    arm, reasoner = graph.node("/arm"), graph.node("/reasoner")
    assert (arm.publishes, arm.subscribes, arm.serves) == (
        ("/dc_servo_command",),
        (),
        ("/move_arm",),
    )
    assert (reasoner.publishes, reasoner.subscribes) == (("/status",), ("/dc_servo_command",))
    assert reasoner.serves == ()
    assert dict(graph.topic_types) == {
        "/dc_servo_command": "robot_arm_msgs/DcServoCommand",
        "/status": "std_msgs/String",
    }


def test_dead_node_is_listed_but_did_not_answer() -> None:
    path = SNAPSHOTS / "valid" / "killed_reasoner_still_listed.json"
    graph = from_json(path.read_text())
    assert graph.node("/arm").answered and not graph.node("/reasoner").answered


def test_plumbing_filter_keeps_a_service_named_like_a_logger_of_another_node() -> None:
    node = LiveNode("/a", serves=("/a/get_loggers", "/b/get_loggers", "/a/set_logger_level"))
    graph = LiveGraph("http://h:1/", datetime.now(UTC), (node,))
    assert without_plumbing(graph).node("/a").serves == ("/b/get_loggers",)


def test_graph_sorts_nodes_and_answers_questions() -> None:
    b = LiveNode("/b", publishes=("/x",), serves=("/s",))
    a = LiveNode("/a", subscribes=("/y",))
    graph = LiveGraph("http://h:1/", datetime(2026, 1, 1, tzinfo=UTC), (b, a), {"/x": "m/X"})
    assert graph.names == ("/a", "/b")
    assert graph.topics == {"/x", "/y"} and graph.services == {"/s"}
    assert graph == LiveGraph("http://h:1/", graph.taken_at, (a, b), {"/x": "m/X"})
    with pytest.raises(KeyError):
        graph.node("/c")
    assert f'"format": "{SNAPSHOT_FORMAT}"' in to_json(graph)
