"""``plan`` and ``watch`` choose the same configuration, always: one preference, every engine.

The preference (``rosreconf.solve.objective.PREFERENCE``): fewest changes; then fewest
replaced (a kept node restarted to be rewired before another component in its place); then the
metric sum; then the first in enumeration order. Held here to a brute force over every valid
configuration, for elimination and clingo alike, and ``plan`` (Fast Downward on the PDDL) to
what ``watch`` decides (``rosreconf.ros.replanning.replan``): on the Nav2-shaped library of
the live tests, on the bundled example, and on generated libraries whose alternatives serve
under other names (so that a kept consumer restarts, and a restart ties with a swap).
"""

from __future__ import annotations

import itertools
import json
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force

from rosreconf.formats.loader import load_bundled, load_paths
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    Requirement,
    Role,
    RosLaunch,
    SystemGraph,
)
from rosreconf.planning.planners import PlanStatus
from rosreconf.planning.planners.fast_downward import FastDownward
from rosreconf.planning.replan import plan
from rosreconf.ros.replanning import replan
from rosreconf.solve.factors import TooHard
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.objective import unary_costs
from rosreconf.solve.optimum import minimise
from rosreconf.solve.running import change_objective
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, optimise

NAV2 = Path(__file__).with_name("data") / "nav2"
LIBRARY, SCHEMA = NAV2 / "nav2_library.yaml", NAV2 / "nav2_schema.yaml"


def _nav2() -> tuple[ComponentLibrary, InteroperabilitySchema]:
    loaded = load_paths([LIBRARY, SCHEMA])
    return loaded.library, loaded.schemas[0]


def _watch_decides(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Configuration,
    failed: frozenset[str],
) -> tuple[Configuration | None, list[tuple[str, str, str]]]:
    """Return the configuration and changes ``watch``'s replan applies (its own function)."""
    found = replan(library, schema, current, failed, lambda *_, **__: None)
    return (None, []) if found is None else found


def test_kill_amcl_restarts_the_kept_planner_rather_than_swap_it_in_plan_and_watch() -> None:
    """Both planners run as /planner_server: slam_toolbox for AMCL, and the planner either
    restarted, rewired to /pose, or replaced by the other one. Two changes either way; the
    restart replaces one component fewer, and both commands choose it."""
    library, schema = _nav2()
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    new, changes = _watch_decides(library, schema, nominal, frozenset({"amcl"}))
    assert new is not None
    assert changes == [
        ("localization", "amcl", "slam_toolbox"),
        ("planner", "planner_navfn", "planner_navfn"),  # kept, restarted to be rewired
    ]
    argv = [sys.executable, "-m", "rosreconf", "plan", "-l", str(LIBRARY), "-s", str(SCHEMA),
            "--fail", "amcl", "--json"]  # fmt: skip
    out = subprocess.run(argv, capture_output=True, text=True, timeout=120, check=False)
    assert out.returncode == 0, out.stderr
    (planned,) = json.loads(out.stdout)["schemas"]
    assert planned["configurations"] == [{"assignment": new.shown}]
    kinds = {c["role"]: c["kind"] for c in planned["changes"] if c["kind"] != "keep"}
    assert kinds == {"localization": "replace", "planner": "restart"}


@pytest.mark.parametrize("search", ["ff-first", "astar(lmcut())"])
def test_plan_chooses_what_watch_does_on_every_single_failure(search: str) -> None:
    """Every component of the nominal configurations of the Nav2 library and the bundled
    example fails in turn: the configuration ``plan`` prints is the one ``watch`` applies,
    whatever the planner's own search (ff-first ignores costs; A* breaks ties its own way)."""
    bundle = load_bundled()
    cases = [_nav2(), *((bundle.library, s) for s in bundle.schemas if s.nominal)]
    tried = 0
    for library, schema in cases:
        nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
        for comp in sorted(set(nominal.filled.values())):
            new, _ = _watch_decides(library, schema, nominal, frozenset({comp}))
            result = plan(library, schema, [comp], nominal.mapping, FastDownward(search))
            if new is None:
                assert result.status is PlanStatus.UNSOLVABLE_PROVEN, (schema.name, comp)
                continue
            assert result.status is PlanStatus.SOLVED, (schema.name, comp, result.message)
            assert result.configuration == new, (schema.name, comp, result.explanation)
            tried += 1
    assert tried >= 20


@st.composite
def rewirable(draw: st.DrawFn) -> tuple[ComponentLibrary, InteroperabilitySchema, dict[str, str]]:
    """Draw a chain of 3-5 roles whose alternatives serve their topic under other names.

    Each role's candidates provide its topic, some remapped (``ros.remappings``) to a name
    of their own, and require the topics of the roles it consumes from: a kept consumer of
    a provider that changes name restarts, which ties with replacing it.
    """
    n = draw(st.integers(3, 5))
    roles = tuple(Role(f"r{i}", f"a{i}") for i in range(n))
    edges, sources = [], {}
    for i in range(1, n):
        sources[i] = [i - 1] + ([j] if (j := draw(st.integers(0, i - 1))) != i - 1 else [])
        edges += [Edge(f"r{i}", f"r{j}") for j in sources[i]]
    comps = []
    for i in range(n):
        for k in range(draw(st.integers(2 if i else 1, 3))):
            topic = Interface(InterfaceKind.TOPIC, f"t{i}", "std_msgs/String")
            name = draw(st.sampled_from([None, f"/t{i}_x"]))
            wants = [
                Requirement((Interface(InterfaceKind.TOPIC, f"t{j}", "std_msgs/String"),))
                for j in sources.get(i, [])
            ]
            launch = RosLaunch("pkg", "exe", remappings={f"t{i}": name} if name else {})
            comps.append(
                Component(f"C{i}_{k}", f"a{i}", frozenset({topic}), tuple(wants), launch=launch)
            )
    library = ComponentLibrary("rewirable", tuple(comps))
    schema = InteroperabilitySchema("s", SystemGraph(roles, tuple(edges)), "skill", "env")
    configs = brute_force(library, schema)
    current = draw(st.sampled_from(configs)).mapping
    return library, schema, current


@settings(max_examples=examples(200))
@given(drawn=rewirable(), data=st.data())
def test_every_engine_chooses_the_brute_force_preferred_configuration(
    drawn: tuple[ComponentLibrary, InteroperabilitySchema, dict[str, str]], data: st.DataObject
) -> None:
    library, schema, current = drawn
    failed = frozenset(data.draw(st.sets(st.sampled_from(sorted(current.values())), max_size=2)))
    inst = compile_instance(library, schema, failed)
    objective = change_objective(library, schema, current)
    configs = brute_force(library, schema, failed)
    engines = {
        "optimise": optimise(inst, objective).configuration,
        "clingo": ClingoEngine().best(inst, objective),
        "clingo (elimination too hard)": optimise(inst, objective, max_rows=0).configuration,
    }
    if not configs:
        assert set(engines.values()) == {None}
        return
    preferred = min(configs, key=lambda c: objective.key(inst, c))
    assert engines == dict.fromkeys(engines, preferred)
    try:  # it answers alone when the optimum of its unary costs restarts nothing
        assert EliminationEngine().best(inst, objective) == preferred
    except TooHard:
        unary = minimise(inst, unary_costs(inst, objective), earliest=True)
        assert unary is not None and objective.restarted(unary[0].mapping)


@settings(max_examples=examples(12))
@given(drawn=rewirable(), data=st.data())
def test_plan_and_watch_agree_on_generated_libraries(
    drawn: tuple[ComponentLibrary, InteroperabilitySchema, dict[str, str]], data: st.DataObject
) -> None:
    library, schema, current = drawn
    failed = frozenset(data.draw(st.sets(st.sampled_from(sorted(current.values())), max_size=2)))
    running = Configuration.of(schema.name, current, schema.graph.roles)
    new, _ = _watch_decides(library, schema, running, failed)
    result = plan(library, schema, failed, current, FastDownward("ff-first"))
    if new is None:
        assert result.status is PlanStatus.UNSOLVABLE_PROVEN
        return
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.configuration == new, result.explanation


def test_a_plan_set_aside_says_why_and_plans_the_preferred_configuration() -> None:
    """A planner that ignores costs may return any valid configuration: ``plan`` says which
    rule of the preference sets it aside, and prints the planner's plan for the preferred."""
    said = []
    for library, schema, current in _tied_cases():
        nominal = Configuration.of(schema.name, current, schema.graph.roles)
        for comp in sorted(set(current.values())):
            new, _ = _watch_decides(library, schema, nominal, frozenset({comp}))
            result = plan(library, schema, [comp], current, FastDownward("ff-first"))
            assert result.configuration == new
            said += [line for line in result.explanation if "own plan" in line]
    assert said, "ff-first chose the preferred configuration every time: no case for the note"
    assert all("set aside: " in line and "the one watch applies" in line for line in said)


def _tied_cases() -> list[tuple[ComponentLibrary, InteroperabilitySchema, dict[str, str]]]:
    """Return small libraries where many configurations tie: two alternatives per role."""
    out = []
    for n in (3, 4):
        roles = tuple(Role(f"r{i}", f"a{i}") for i in range(n))
        edges = tuple(Edge(f"r{i}", f"r{i - 1}") for i in range(1, n))
        comps = [
            Component(
                f"C{i}_{k}",
                f"a{i}",
                frozenset({Interface(InterfaceKind.TOPIC, f"t{i}", "std_msgs/String")}),
                tuple(
                    Requirement((Interface(InterfaceKind.TOPIC, f"t{i - 1}", "std_msgs/String"),))
                    for _ in range(1)
                    if i
                ),
                launch=RosLaunch("pkg", "exe", remappings={f"t{i}": f"/t{i}_{k}"}),
            )
            for i, k in itertools.product(range(n), range(3))
        ]
        library = ComponentLibrary("tied", tuple(comps))
        schema = InteroperabilitySchema("s", SystemGraph(roles, edges), "skill", "env")
        out.append((library, schema, {f"r{i}": f"C{i}_2" for i in range(n)}))
    return out
