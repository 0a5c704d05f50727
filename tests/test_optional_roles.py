"""Optional roles (issue 22): every solver and analysis agrees with the definition's brute force.

The random libraries of ``randomlib.problems(optional_roles=True)`` make some roles optional;
the brute force tries every optional role empty as well, and the definition
(``rosreconf.model.validity``) decides. Enumeration (clingo), counting, the optimum
(elimination and clingo), the marginals, single points of failure and the probability of
staying reconfigurable must all agree with it.
"""

from __future__ import annotations

import itertools
import json
import math
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from datetime import UTC, datetime
from importlib.resources import as_file
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import xmlschema
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, brute_force_probability, problems
from test_json_outputs import schema_of
from typer.testing import CliRunner

from rosreconf.analysis.library import analyse
from rosreconf.analysis.marginals import marginals
from rosreconf.analysis.whatif import evaluate, make_task
from rosreconf.cli.app import app
from rosreconf.formats.loader import Source, load_sources
from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    node_vertex,
)
from rosreconf.model.validity import is_valid, ros_graph
from rosreconf.model.wiring import node_live_name
from rosreconf.resources import Bundle, bundled
from rosreconf.ros.conformance import compare
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.solve import dense
from rosreconf.solve.counting import count
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.optimum import first
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, Objective

PROPS = settings(max_examples=examples(100))
WHEN = datetime(2026, 1, 1, tzinfo=UTC)
Problem = tuple[ComponentLibrary, InteroperabilitySchema]


@contextmanager
def _grids(dense_grids: bool) -> Iterator[None]:
    """Let the dense grids answer (the default), or make every grid too wide (sparse tables)."""
    with pytest.MonkeyPatch.context() as mp:
        if not dense_grids:
            mp.setattr(dense, "DENSE_CELLS", 0)
        yield


@PROPS
@given(problem=problems(optional_roles=True), data=st.data())
def test_optional_roles_enumeration_count_and_first_agree_with_brute_force(
    problem: Problem, data: st.DataObject
) -> None:
    library, schema = problem
    names = [c.name for c in library]
    failed = frozenset(data.draw(st.sets(st.sampled_from(names), max_size=2)))
    inst = compile_instance(library, schema, failed)
    expected = brute_force(library, schema, failed)
    listed = list(ClingoEngine().configurations(inst))
    assert [c.assignment for c in listed] == [c.assignment for c in expected]
    for dense_grids in (True, False):  # the dense grids, and the sparse tables they fall back to
        with _grids(dense_grids):
            assert count(inst) == len(expected)
            found = first(inst)
        want = expected[0].assignment if expected else None
        assert (found.assignment if found else None) == want


@PROPS
@given(problem=problems(optional_roles=True), data=st.data())
def test_optional_roles_optimum_is_the_brute_force_least_change(
    problem: Problem, data: st.DataObject
) -> None:
    """From every valid configuration as the running one, with metric weights: one least cost."""
    library, schema = problem
    configs = brute_force(library, schema)
    inst = compile_instance(library, schema)
    if not configs:
        assert EliminationEngine().best(inst, Objective()) is None
        return
    current = data.draw(st.sampled_from(configs)).mapping
    objective = Objective(current=current, weights={"cost": 1.0})
    least = min(objective.cost(inst, c) for c in configs)
    for dense_grids in (True, False):  # elimination: dense grids, then the sparse tables
        with _grids(dense_grids):
            best = EliminationEngine().best(inst, objective)
        assert best is not None and best in configs, dense_grids
        assert objective.cost(inst, best) == least == (0, least[1]), dense_grids
    best = ClingoEngine().best(inst, objective)
    assert best is not None and best in configs
    assert objective.cost(inst, best) == least


@PROPS
@given(problem=problems(optional_roles=True))
def test_optional_roles_marginals_count_empty_choices(problem: Problem) -> None:
    library, schema = problem
    inst = compile_instance(library, schema)
    expected = [dict.fromkeys((c.name for c in dom), 0) for dom in inst.domains]
    configs = brute_force(library, schema)
    for config in configs:
        for u, (role, comp) in enumerate(config.assignment):
            expected[u][as_candidate(role, comp)] += 1
    marg = marginals(inst)
    assert marg.total == len(configs)
    assert marg.per_role == expected


@settings(max_examples=examples(60))
@given(problem=problems(optional_roles=True))
def test_optional_roles_single_points_of_failure_and_probability(problem: Problem) -> None:
    """An empty optional role is no single point of failure; what fails is what every
    configuration uses; the probability is the brute force over failure states."""
    library, schema = problem
    configs = [frozenset(c.components) for c in brute_force(library, schema)]
    result = analyse(library, schema)
    expected = sorted(frozenset.intersection(*configs)) if configs else []
    assert result.single_points_of_failure == expected
    p = {c.name: c.failure_probability or 0.0 for c in library}
    total = brute_force_probability(configs, p)
    if configs:
        assert result.reliability is not None
        assert math.isclose(result.reliability.probability, total, abs_tol=1e-12)


# --- the Nav2-like held-out case, through every command -------------------------------------

NAV2 = Path(__file__).parent / "cases" / "valid" / "nav2_optional"
FILES = ["-l", str(NAV2 / "lib.yaml"), "-s", str(NAV2 / "task.yaml")]


def _json(runner: CliRunner, command: str, *args: str, code: int = 0) -> dict[str, Any]:
    result = runner.invoke(app, [command, *FILES, *args, "--json"])
    assert result.exit_code == code, result.output
    doc: dict[str, Any] = json.loads(result.stdout)  # one document
    jsonschema.validate(doc, schema_of(command))
    return doc


def test_nav2_optional_case_has_amcl_with_map_server_or_slam_without_each_with_or_without_ekf(
    runner: CliRunner,
) -> None:
    (s,) = _json(runner, "enumerate")["schemas"]
    rows = [(c["assignment"]["ekf"], c["assignment"]["map_server"]) for c in s["configurations"]]
    assert rows == [
        ("ekf_filter_node", "map_server"),
        ("ekf_filter_node", None),
        (None, "map_server"),
        (None, None),
    ]
    assert [c["assignment"]["localization"] for c in s["configurations"]] == [
        "amcl",
        "slam_toolbox",
    ] * 2
    assert s["count"] == 4
    empty = s["configurations"][3]
    assert "map_server" not in empty["components"] and "ekf_filter_node" not in empty["components"]
    assert {n["role"] for n in empty["ros_graph"]["nodes"]} == {
        "laser", "odometry", "localization", "planner", "controller", "behaviors", "smoother",
        "base",
    }  # fmt: skip
    text = runner.invoke(app, ["enumerate", *FILES]).stdout
    assert "(ekf empty), (map_server empty), slam_toolbox" in text


def test_nav2_optional_analysis_no_empty_role_is_a_single_point_of_failure(
    runner: CliRunner,
) -> None:
    (s,) = _json(runner, "analyse")["schemas"]
    by_role = {r["role"]: r for r in s["redundancy"]}
    assert by_role["ekf"]["candidates"] == ["ekf_filter_node"] and by_role["ekf"]["may_stay_empty"]
    assert by_role["map_server"]["may_stay_empty"] and not by_role["laser"]["may_stay_empty"]
    spof = set(s["single_points_of_failure"])
    assert "lidar" in spof and not spof & {"ekf_filter_node", "map_server", "amcl"}
    assert not any(n.startswith("empty-") for n in spof)


@pytest.mark.planner
def test_plan_fail_map_server_moves_to_slam_and_leaves_the_map_server_empty(
    runner: CliRunner, tmp_path: Path
) -> None:
    (s,) = _json(runner, "plan", "--fail", "map_server")["schemas"]
    assert s["status"] == "solved" and s["fewest_changes"] == 2
    new = s["configurations"][0]["assignment"]
    assert new["map_server"] is None and new["localization"] == "slam_toolbox"
    assert new["ekf"] == "ekf_filter_node"  # kept: fewest changes
    kinds = {c["role"]: c["kind"] for c in s["changes"] if c["kind"] != "keep"}
    assert kinds == {"map_server": "stop", "localization": "replace"}
    assert "stop map_server, leave map_server empty" in s["steps"]
    assert "2 part(s) change: the fewest possible." in s["explanation"]
    saved = tmp_path / "now.json"
    saved.write_text(json.dumps({"schemas": [s]}), encoding="utf-8")
    again = runner.invoke(app, ["plan", *FILES, "--fail", "map_server", "--current", str(saved)])
    assert again.exit_code == 0, again.output
    assert "unaffected, keeps running" in again.stdout  # the empty role read back as empty


@pytest.mark.planner
def test_plan_fail_ekf_leaves_the_add_on_empty_and_restarts_its_consumer(
    runner: CliRunner,
) -> None:
    """The controller read odometry/filtered from the EKF: started for a configuration, a
    node uses only its ROS-graph edges' interfaces, so it restarts to read odom alone (the
    wiring model): two changes, where an empty role alone would be one."""
    (s,) = _json(runner, "plan", "--fail", "ekf_filter_node")["schemas"]
    assert s["fewest_changes"] == 2
    assert [c for c in s["changes"] if c["kind"] != "keep"] == [
        {"role": "ekf", "before": "ekf_filter_node", "after": None, "kind": "stop"},
        {"role": "controller", "before": "controller_server", "after": "controller_server",
         "kind": "restart"},
    ]  # fmt: skip
    assert any("it no longer uses odometry/filtered at" in line for line in s["explanation"])


def test_launch_starts_nothing_for_an_empty_role(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "nav.launch.xml"
    args = ["launch", *FILES, "--only", "nav2_navigation", "--ros2", "--fail", "map_server"]
    result = runner.invoke(app, [*args, "-o", str(out)])
    assert result.exit_code == 0, result.output
    with as_file(bundled(Bundle.DATA, "ros2-launch.xsd")) as xsd:
        xmlschema.XMLSchema(str(xsd)).validate(str(out))
    names = [n.get("name") for n in ET.parse(out).getroot().iter("node")]
    assert "map_server" not in names and "amcl" not in names
    assert {"slam_toolbox", "controller_server", "behavior_server"} <= set(names)


def test_graph_draws_an_empty_role_as_such(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "ros.dot"
    result = runner.invoke(app, ["graph", *FILES, "--fail", "map_server", "-o", str(out)])
    assert result.exit_code == 0, result.output
    dot = out.read_text(encoding="utf-8")
    assert '"map_server\\n(empty)"' in dot and "dotted" in dot
    system = tmp_path / "system.dot"
    result = runner.invoke(app, ["graph", *FILES, "--view", "system", "-o", str(system)])
    assert result.exit_code == 0, result.output
    assert '"ekf\\n(ekf)\\noptional"' in system.read_text(encoding="utf-8")


def test_inspect_expects_no_node_for_an_empty_role_and_calls_a_left_out_one_extra() -> None:
    """The SLAM configuration: no map server expected; a running map server is extra."""
    loaded = load_sources(
        [Source(p.name, p.read_bytes()) for p in (NAV2 / "lib.yaml", NAV2 / "task.yaml")]
    )
    library, (schema,) = loaded.library, loaded.schemas
    mapping = {**schema.nominal, "localization": "slam_toolbox"}
    del mapping["map_server"]
    config = Configuration.of(schema.name, mapping, schema.graph.roles)
    assert config.mapping["map_server"] == EMPTY and is_valid(config, library, schema)
    nodes = [_live_node(library[c], config, library, schema) for c in config.components]
    live = LiveGraph("http://127.0.0.1:11311/", WHEN, tuple(nodes), {})
    result = compare(config, library, schema, live)
    assert result.ok, result.findings
    assert "map_server" not in result.expected_nodes
    extra = _live_node(library["map_server"], config, library, schema)
    result = compare(config, library, schema, replace(live, nodes=(*nodes, extra)))
    assert [(f.code, f.live_name) for f in result.findings] == [("extra-node", "/map_server")]
    assert result.to_dict()["configuration"]["map_server"] is None


def _live_node(
    comp: Component, config: Configuration, library: ComponentLibrary, schema: Any
) -> LiveNode:
    """Return a live node doing exactly what ``comp`` does in ``config``'s ROS-graph."""
    g = ros_graph(config, library, schema)
    me = node_vertex(comp.name)
    pubs = sorted(str(g.nodes[v]["label"]) for v in g.successors(me)) if me in g else []
    subs = sorted(str(g.nodes[v]["label"]) for v in g.predecessors(me)) if me in g else []
    return LiveNode(
        node_live_name(comp),
        "http://127.0.0.1:1/",
        1,
        tuple(f"/{p}" for p in pubs),
        tuple(f"/{s}" for s in subs),
        (),
    )


def test_validate_lets_a_nominal_leave_an_optional_role_out_but_not_a_required_one(
    runner: CliRunner, tmp_path: Path
) -> None:
    text = (NAV2 / "task.yaml").read_text(encoding="utf-8")
    (tmp_path / "lib.yaml").write_text((NAV2 / "lib.yaml").read_text(encoding="utf-8"))
    task = tmp_path / "task.yaml"
    task.write_text(text.replace("  ekf: ekf_filter_node\n", ""), encoding="utf-8")
    ok = runner.invoke(app, ["validate", str(tmp_path)])
    assert ok.exit_code == 0, ok.output
    files = ["-l", str(tmp_path / "lib.yaml"), "-s", str(task)]
    out = tmp_path / "nominal.launch"
    launched = runner.invoke(app, ["launch", *files, "--ros1", "-o", str(out)])
    assert launched.exit_code == 0, launched.output  # the nominal runs: no EKF node
    names = {n.get("name") for n in ET.parse(out).getroot().iter("node")}
    assert "ekf_filter_node" not in names and {"map_server", "amcl"} <= names
    task.write_text(text.replace("  laser: lidar\n", ""), encoding="utf-8")
    bad = runner.invoke(app, ["validate", str(tmp_path)])
    assert bad.exit_code == 1 and "leaves role 'laser' empty" in bad.stdout


def test_whatif_clingo_task_survives_exactly_when_a_configuration_avoids_the_failures() -> None:
    """The what-if workers' clingo task (``make_task``) takes the empty choices along."""
    loaded = load_sources(
        [Source(p.name, p.read_bytes()) for p in (NAV2 / "lib.yaml", NAV2 / "task.yaml")]
    )
    library, (schema,) = loaded.library, loaded.schemas
    configs = [frozenset(c.components) for c in brute_force(library, schema)]
    task = make_task(library, schema)
    names = [c.name for c in library]
    for failed in itertools.chain(
        itertools.combinations(names, 1), itertools.combinations(names, 2)
    ):
        outcome = evaluate(task, failed)
        assert outcome.survives == any(not (c & set(failed)) for c in configs), failed
        if outcome.configuration is not None:
            assert frozenset(outcome.configuration) in configs


def test_a_walk_may_forbid_an_optional_role_left_empty() -> None:
    """plan's walk forbids a failing loop's roles as the configuration fills them, EMPTY too."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.solve.search import Search

    loaded = load_paths([NAV2 / "lib.yaml", NAV2 / "task.yaml"])
    inst = compile_instance(loaded.library, loaded.schemas[0])
    search = Search(inst, Objective(), None)
    search.forbid([("ekf", EMPTY), ("map_server", EMPTY)])
    search.forbid([("ekf", "ekf_filter_node")])
    best = search.best()
    assert best is not None and best.mapping["ekf"] == EMPTY
    assert best.mapping["map_server"] == "map_server"
