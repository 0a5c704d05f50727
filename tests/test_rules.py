"""Every rule of validity, one at a time: all five encodings agree with the definition.

``rosreconf.model.validity.RULES`` lists the rules once. For each rule, ``CASES`` builds small
libraries that exercise that rule (a *witness* configuration breaks it and nothing else; for
a rule that relaxes another, the witness is valid here and invalid without the rule). On every
case the definition's brute force (every component in every role) is the reference, and

* clingo enumerates exactly its configurations, in its order;
* counting (sum-product elimination) returns exactly their number;
* elimination (min-plus) and clingo's optimiser reach its least cost;
* Fast Downward, planning and forbidding, finds exactly its configurations.

A rule added to ``RULES`` without cases fails ``test_every_rule_has_cases``; a rule without an
encoding place fails ``test_rule_names_a_place_in_every_encoding``; a violation code or an
encoding line (clingo program, counting table) that names no rule fails a named test too.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import pytest
from pddlcheck import chosen, plan_all

from rosreconf.formats.loader import load_bundled
from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Configuration,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    Requirement,
    Role,
    SystemGraph,
    validity,
)
from rosreconf.model.validity import RULES, Encoding, Rule, is_valid, violations
from rosreconf.planning.pddl import render
from rosreconf.planning.planners import FastDownward, solve
from rosreconf.solve.counting import count
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.factors import constraint_factors
from rosreconf.solve.instance import compile_instance, prune
from rosreconf.solve.solver import PROGRAM, ClingoEngine, EliminationEngine, Objective

RULE_NAMES = {r.name for r in RULES}


# --- building small cases -----------------------------------------------------------------


def topic(label: str) -> Interface:
    """Return the topic ``label`` typed from its name, or ``label:Type`` typed ``m/Type``."""
    name, _, kind = label.partition(":")
    return Interface(InterfaceKind.TOPIC, name, f"m/{kind or name.capitalize()}")


def comp(
    name: str,
    abstraction: str,
    provides: Sequence[str] = (),
    requires: Sequence[Sequence[str]] = (),
    **more: object,
) -> Component:
    """Return a component; ``requires`` is a list of option lists (``[[a, b]]`` = any_of)."""
    return Component(
        name=name,
        abstraction=abstraction,
        provides=frozenset(topic(p) for p in provides),
        requires=tuple(Requirement(tuple(topic(o) for o in opts)) for opts in requires),
        **more,  # type: ignore[arg-type]
    )


@dataclass(frozen=True)
class Case:
    """One small problem exercising a rule.

    Attributes:
        name: the case's id.
        library: the components (every one gets a ``cost`` metric for the optimum check).
        schema: the schema.
        witnesses: role -> component assignments (possibly partial or not label-respecting)
            that break exactly this rule: each one's violation codes are non-empty and all
            among the rule's codes. For a relaxing rule: valid here, invalid in ``without``.
        failed: unavailable components.
        without: the same schema with this rule turned off (relaxing rules only).
    """

    name: str
    library: ComponentLibrary
    schema: InteroperabilitySchema
    witnesses: tuple[dict[str, str], ...]
    failed: frozenset[str] = frozenset()
    without: InteroperabilitySchema | None = None


def make(
    name: str,
    comps: Sequence[Component],
    roles: Sequence[tuple[str, str] | tuple[str, str, bool]],
    edges: Sequence[Edge],
    *witnesses: dict[str, str],
    failed: Sequence[str] = (),
) -> Case:
    """Build a case; components get costs 0, 1, 2, 0, ... so optima are not all ties.

    A role given as ``(name, abstraction, True)`` is optional.
    """
    costed = tuple(
        replace(c, metrics={"cost": float(i % 3)}) if not c.metrics else c
        for i, c in enumerate(comps)
    )
    made = tuple(Role(r[0], r[1], optional=len(r) > 2 and bool(r[2])) for r in roles)
    graph = SystemGraph(made, tuple(edges))
    schema = InteroperabilitySchema("s", graph, "skill", "env")
    without = None
    if any(e.optional for e in edges) or any(r.optional for r in made):
        strict = SystemGraph(
            tuple(replace(r, optional=False) for r in made),
            tuple(replace(e, optional=False) for e in edges),
        )
        without = replace(schema, graph=strict)
    return Case(
        name,
        ComponentLibrary("lib", costed),
        schema,
        tuple(witnesses),
        frozenset(failed),
        without,
    )


def chain(n: int, k: int, **extra: dict[str, object]) -> list[Component]:
    """Return k candidates per role of an n-role chain r0 <- r1 <- ... where all fit.

    Role i's candidates publish ``t{i}`` and subscribe ``t{i+1}``; the edges of ``chain_edges``
    make every label-respecting assignment valid. ``extra`` adds fields per component name.
    """
    out = []
    for i in range(n):
        for j in range(k):
            name = f"C{i}_{j}"
            reqs = [[f"t{i + 1}"]] if i + 1 < n else []
            out.append(comp(name, f"l{i}", [f"t{i}"], reqs, **extra.get(name, {})))
    return out


def chain_roles(n: int) -> list[tuple[str, str]]:
    """Return the roles r0 .. r(n-1) of ``chain``."""
    return [(f"r{i}", f"l{i}") for i in range(n)]


def chain_edges(n: int) -> list[Edge]:
    """Return the required edges r_i uses r_(i+1) of ``chain``."""
    return [Edge(f"r{i}", f"r{i + 1}") for i in range(n - 1)]


def same(j: int, n: int) -> dict[str, str]:
    """Return the assignment taking candidate ``j`` in every role of ``chain``."""
    return {f"r{i}": f"C{i}_{j}" for i in range(n)}


def cases_complete() -> list[Case]:
    return [
        make("partial", chain(2, 2), chain_roles(2), chain_edges(2), {"r1": "C1_0"}),
        make(
            "unknown",
            chain(2, 2),
            chain_roles(2),
            chain_edges(2),
            {"r0": "C0_0", "r1": "C1_0", "r9": "C1_1"},
            {"r0": "nobody", "r1": "C1_0"},
        ),
    ]


def cases_available() -> list[Case]:
    return [
        make("one", chain(3, 2), chain_roles(3), chain_edges(3), same(0, 3), failed=["C1_0"]),
        make(
            "two",
            chain(3, 2),
            chain_roles(3),
            chain_edges(3),
            same(1, 3),
            failed=["C0_0", "C2_1"],
        ),
        make(
            "all", chain(2, 2), chain_roles(2), chain_edges(2), same(0, 2), failed=["C1_0", "C1_1"]
        ),
    ]


def cases_abstraction() -> list[Case]:
    lib = [*chain(2, 2), comp("Stray", "elsewhere", ["t1"])]
    return [
        make("swapped", lib, chain_roles(2), (), {"r0": "C1_0", "r1": "C1_1"}),
        make("stray", lib, chain_roles(2), chain_edges(2), {"r0": "C0_0", "r1": "Stray"}),
    ]


def cases_in_schema() -> list[Case]:
    limited = {"C0_1": {"schemas": frozenset({"other"})}, "C1_0": {"schemas": frozenset("s")}}
    only_other = {f"C1_{j}": {"schemas": frozenset({"other"})} for j in range(2)}
    return [
        make("one", chain(2, 2, **limited), chain_roles(2), chain_edges(2), same(1, 2)),
        make("none", chain(2, 2, **only_other), chain_roles(2), chain_edges(2), same(0, 2)),
    ]


def cases_one_role_each() -> list[Case]:
    selfish = [comp(f"S{j}", "l", ["t"], [["t"]]) for j in range(3)]
    return [
        make(
            "free",
            selfish,
            [("a", "l"), ("b", "l")],
            [Edge("a", "b", optional=True), Edge("b", "a", optional=True)],
            {"a": "S0", "b": "S0"},
        ),
        make(
            "wired",
            selfish,
            [("a", "l"), ("b", "l"), ("c", "l")],
            [Edge("a", "b"), Edge("b", "c"), Edge("c", "a")],
            {"a": "S1", "b": "S2", "c": "S1"},
        ),
    ]


def cases_edge_realised() -> list[Case]:
    lib = [
        comp("U0", "u", [], [["a", "b"]]),
        comp("U1", "u", [], [["c"]]),
        comp("V0", "v", ["a"]),
        comp("V1", "v", ["c"]),
        comp("W0", "w", ["b"]),
    ]
    roles = [("u", "u"), ("v", "v"), ("w", "w")]
    return [
        make(
            "met-elsewhere",
            lib,
            roles,
            [Edge("u", "v"), Edge("u", "w", optional=True)],
            {"u": "U0", "v": "V1", "w": "W0"},
        ),
        make(
            "provider-gives-nothing",
            [*lib, comp("V2", "v", [])],
            roles,
            [Edge("u", "v"), Edge("u", "w", optional=True), Edge("v", "w", optional=True)],
            {"u": "U0", "v": "V2", "w": "W0"},
        ),
    ]


def cases_edge_interfaces() -> list[Case]:
    lib = [
        comp("U0", "u", [], [["a", "b"]]),
        comp("V0", "v", ["a", "b"]),
        comp("V1", "v", ["b"]),
        comp("W0", "w", ["b"]),
    ]
    roles = [("u", "u"), ("v", "v"), ("w", "w")]
    only_a = frozenset({"a"})
    return [
        make(
            "restricted-edge",
            lib,
            roles,
            [Edge("u", "v", only_a), Edge("u", "w", optional=True)],
            {"u": "U0", "v": "V1", "w": "W0"},
        ),
        make(
            "restricted-requirement",
            lib[:3],
            roles[:2],
            [Edge("u", "v", only_a, optional=True)],
            {"u": "U0", "v": "V1"},
        ),
    ]


def cases_requirement_met() -> list[Case]:
    lib = [
        comp("U0", "u", [], [["a"], ["b"]]),
        comp("U1", "u", [], [["a"]]),
        comp("V0", "v", ["a"]),
        comp("V1", "v", ["x"]),
        comp("W0", "w", ["b"]),
        comp("W1", "w", ["y"]),
    ]
    roles = [("u", "u"), ("v", "v"), ("w", "w")]
    optional = [Edge("u", "v", optional=True), Edge("u", "w", optional=True)]
    return [
        make("two-needs", lib, roles, optional, {"u": "U0", "v": "V1", "w": "W0"}),
        make(
            "no-edge-to-it",
            lib,
            roles,
            [Edge("u", "w", optional=True)],
            {"u": "U1", "v": "V0", "w": "W0"},
        ),
    ]


def cases_any_of() -> list[Case]:
    lib = [
        comp("U0", "u", [], [["a", "b"]]),
        comp("U1", "u", [], [["b", "c"], ["a"]]),
        comp("V0", "v", ["a"]),
        comp("V1", "v", ["b"]),
        comp("V2", "v", ["c"]),
    ]
    return [
        make(
            "either",
            lib,
            [("u", "u"), ("v", "v")],
            [Edge("u", "v", optional=True)],
            {"u": "U0", "v": "V2"},
        ),
        make(
            "two-providers",
            [*lib, comp("W0", "w", ["a"])],
            [("u", "u"), ("v", "v"), ("w", "w")],
            [Edge("u", "v", optional=True), Edge("u", "w", optional=True)],
            {"u": "U1", "v": "V0", "w": "W0"},
        ),
    ]


def cases_needs() -> list[Case]:
    needs = {
        "C0_0": {"needs": frozenset({"C2_1"})},
        "C1_1": {"needs": frozenset({"C0_1"})},
    }
    return [
        make("chain", chain(3, 2, **needs), chain_roles(3), chain_edges(3), same(0, 3)),
        make(
            "needed-failed",
            chain(2, 2, C0_0={"needs": frozenset({"C1_0"})}),
            chain_roles(2),
            chain_edges(2),
            {"r0": "C0_0", "r1": "C1_1"},
            failed=["C1_0"],
        ),
        make(
            "outside",
            [*chain(2, 2, C0_0={"needs": frozenset({"Spare"})}), comp("Spare", "spare")],
            chain_roles(2),
            chain_edges(2),
            same(0, 2),
        ),
    ]


def cases_excludes() -> list[Case]:
    excludes = {
        "C0_0": {"excludes": frozenset({"C2_0"})},
        "C2_1": {"excludes": frozenset({"C1_1"})},
    }
    return [
        make("both-ways", chain(3, 2, **excludes), chain_roles(3), chain_edges(3), same(0, 3)),
        make(
            "unrelated-roles",
            chain(2, 2, C1_0={"excludes": frozenset({"C0_0", "C0_1"})}),
            chain_roles(2),
            [Edge("r0", "r1", optional=True)],
            same(0, 2),
        ),
    ]


def cases_one_type_per_label() -> list[Case]:
    """Raw and compressed images under one label: alternatives, never chosen together."""
    cameras = [comp("RAW", "camera", ["image:Raw"]), comp("COMP", "camera", ["image:Comp"])]
    monitors = [comp("MON_RAW", "monitor", ["image:Raw"]), comp("MON_OFF", "monitor", ["st"])]
    twins = [
        comp("RAW1", "camera", ["image:Raw"]),
        comp("RAW2", "camera", ["image:Raw"]),
        comp("COMP1", "camera", ["image:Comp"]),
    ]
    return [
        make(
            "republisher",
            [*cameras, *monitors],
            [("camera", "camera"), ("monitor", "monitor")],
            [Edge("monitor", "camera", optional=True)],
            {"camera": "COMP", "monitor": "MON_RAW"},
        ),
        make(
            "two-cameras",
            twins,
            [("left", "camera"), ("right", "camera")],
            (),
            {"left": "RAW1", "right": "COMP1"},
            {"left": "COMP1", "right": "RAW2"},
        ),
    ]


def cases_optional_edge() -> list[Case]:
    """The mobile robot's pattern: a TEB planner does not read the laser DWB reads."""
    lib = [
        comp("DWB", "planner", ["cmd"], [["scan"], ["odom"]]),
        comp("TEB", "planner", ["cmd"], [["odom"]]),
        comp("Sick", "laser", ["scan"]),
        comp("Lidar3d", "laser", ["cloud"]),
        comp("Wheels", "odometry", ["odom"]),
    ]
    roles = [("planner", "planner"), ("laser", "laser"), ("odometry", "odometry")]
    return [
        make(
            "teb-ignores-laser",
            lib,
            roles,
            [Edge("planner", "laser", optional=True), Edge("planner", "odometry")],
            {"planner": "TEB", "laser": "Sick", "odometry": "Wheels"},
        ),
        make(
            "all-optional",
            lib,
            roles,
            [
                Edge("planner", "laser", optional=True),
                Edge("planner", "odometry", optional=True),
            ],
            {"planner": "TEB", "laser": "Lidar3d", "odometry": "Wheels"},
        ),
    ]


def cases_optional_role() -> list[Case]:
    """Issue 22: an add-on EKF, and a map server not needed under SLAM."""
    ekf_lib = [
        comp("Dwb", "planner", ["cmd"], [["odom_filtered", "odom"]]),
        comp("Teb", "planner", ["cmd"], [["odom_filtered"]]),  # only the EKF serves it
        comp("Wheels", "odometry", ["odom"]),
        comp("Ekf", "ekf", ["odom_filtered"], [["odom"]]),
        comp("Ukf", "ekf", ["odom_filtered"], [["odom"]]),
    ]
    ekf_roles = [("planner", "planner"), ("odometry", "odometry"), ("ekf", "ekf", True)]
    ekf_edges = [  # planner <- ekf is required: it binds only when the EKF is there
        Edge("planner", "odometry", optional=True),
        Edge("planner", "ekf"),
        Edge("ekf", "odometry"),
    ]
    map_lib = [
        comp("Amcl", "localization", ["pose"], [["map"], ["scan"]]),
        comp("Slam", "localization", ["pose", "slam_map"], [["scan"]]),
        comp("MapServer", "map_server", ["map"]),
        comp("Lidar", "laser", ["scan"]),
    ]
    map_roles = [("localization", "localization"), ("map", "map_server", True), ("laser", "laser")]
    map_edges = [Edge("localization", "map"), Edge("localization", "laser")]
    need_lib = [  # a component needing the optional role's component forces it filled
        comp("Viewer", "viewer", [], [["image"]], needs=frozenset({"Logger"})),
        comp("Glance", "viewer", [], [["image"]]),
        comp("Camera", "camera", ["image"]),
        comp("Logger", "logger", ["log"]),
    ]
    need_roles = [("viewer", "viewer"), ("camera", "camera"), ("logger", "logger", True)]
    return [
        make(
            "ekf-add-on",
            ekf_lib,
            ekf_roles,
            ekf_edges,
            {"planner": "Dwb", "odometry": "Wheels", "ekf": EMPTY},
        ),
        make(
            "map-server-under-slam",
            map_lib,
            map_roles,
            map_edges,
            {"localization": "Slam", "map": EMPTY, "laser": "Lidar"},
        ),
        make(
            "needed-add-on",
            need_lib,
            need_roles,
            [Edge("viewer", "camera"), Edge("viewer", "logger", optional=True)],
            {"viewer": "Glance", "camera": "Camera", "logger": EMPTY},
        ),
        make(
            "every-role-optional",
            ekf_lib,
            [(r[0], r[1], True) for r in ekf_roles],
            ekf_edges,
            {"planner": EMPTY, "odometry": EMPTY, "ekf": EMPTY},
            {"planner": EMPTY, "odometry": "Wheels", "ekf": EMPTY},
        ),
    ]


CASES: dict[str, Callable[[], list[Case]]] = {
    "complete": cases_complete,
    "available": cases_available,
    "abstraction": cases_abstraction,
    "in-schema": cases_in_schema,
    "one-role-each": cases_one_role_each,
    "edge-realised": cases_edge_realised,
    "edge-interfaces": cases_edge_interfaces,
    "requirement-met": cases_requirement_met,
    "any-of": cases_any_of,
    "needs": cases_needs,
    "excludes": cases_excludes,
    "one-type-per-label": cases_one_type_per_label,
    "optional-edge": cases_optional_edge,
    "optional-role": cases_optional_role,
}
"""Rule name -> its cases. Every rule of ``RULES`` needs an entry."""


def rule_cases() -> list[tuple[Rule, Case]]:
    """Return every (rule, case) pair, for parametrizing."""
    return [(r, c) for r in RULES if r.name in CASES for c in CASES[r.name]()]


PAIRS = rule_cases()
IDS = [f"{r.name}/{c.name}" for r, c in PAIRS]


def brute_force(case: Case, schema: InteroperabilitySchema | None = None) -> list[Configuration]:
    """Return the definition's configurations: every component tried in every role."""
    schema = schema or case.schema
    roles = schema.graph.roles
    names = [c.name for c in case.library]
    choices = [[*names, EMPTY] if r.optional else names for r in roles]
    out = []
    for combo in itertools.product(*choices):
        config = Configuration.of(
            schema.name, dict(zip([r.name for r in roles], combo, strict=True)), roles
        )
        if is_valid(config, case.library, schema, case.failed):
            out.append(config)
    return out


# --- the registry is complete ---------------------------------------------------------------


def _resolve(place: str) -> object:
    module, _, qualname = place.partition(":")
    target: object = importlib.import_module(module)
    for part in qualname.split("."):
        target = getattr(target, part)
    return target


@pytest.mark.parametrize("rule", RULES, ids=lambda r: r.name)
def test_rule_names_a_place_in_every_encoding(rule: Rule) -> None:
    assert set(rule.places) == set(Encoding), f"{rule.name} misses encodings"
    for encoding, places in rule.places.items():
        assert places, f"{rule.name}: no place named for {encoding}"
        for place in places:
            _resolve(place)  # AttributeError / ImportError: a place that does not exist


def test_rule_names_are_unique() -> None:
    assert len(RULE_NAMES) == len(RULES)


def test_every_rule_has_cases() -> None:
    assert set(CASES) == RULE_NAMES


def test_every_violation_code_belongs_to_a_rule() -> None:
    tree = ast.parse(inspect.getsource(validity))
    codes = {
        node.args[0].value
        for node in ast.walk(tree)
        if isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id == "Violation"
        and node.args
        and isinstance(node.args[0], ast.Constant)
    }
    assert codes, "no Violation(...) found in rosreconf.model.validity"
    assert codes == {code for r in RULES for code in r.codes}


def test_every_clingo_line_names_its_rules() -> None:
    tagged: set[str] = set()
    for line in PROGRAM.strip().splitlines():
        if line.startswith("#show"):
            continue
        code, _, tag = line.partition("% rule:")
        assert tag.split(), f"clingo line names no rule: {code.strip()}"
        tagged.update(tag.split())
    assert tagged <= RULE_NAMES, tagged - RULE_NAMES


def test_every_counting_table_names_its_rule() -> None:
    seen: set[str] = set()
    for _, case in PAIRS:
        inst = compile_instance(case.library, case.schema, case.failed)
        alive, _, _ = prune(inst)
        if all(alive):
            seen.update(f.rule for f in constraint_factors(inst, alive, 1))
    assert seen <= RULE_NAMES, seen - RULE_NAMES
    assert {
        "edge-realised",
        "requirement-met",
        "needs",
        "excludes",
        "one-role-each",
        "one-type-per-label",
    } <= seen


# --- each rule, each encoding ---------------------------------------------------------------


@pytest.mark.parametrize(("rule", "case"), PAIRS, ids=IDS)
def test_witness_breaks_this_rule_alone(rule: Rule, case: Case) -> None:
    for witness in case.witnesses:
        config = Configuration(case.schema.name, tuple(witness.items()))
        codes = {v.code for v in violations(config, case.library, case.schema, case.failed)}
        if rule.codes:
            assert codes, f"{witness} breaks nothing"
            assert codes <= set(rule.codes), f"{witness} also breaks {codes - set(rule.codes)}"
        else:  # a relaxing rule: valid with it, invalid without it
            assert not codes, codes
            assert case.without is not None
            assert not is_valid(config, case.library, case.without, case.failed)


@pytest.mark.parametrize(("rule", "case"), PAIRS, ids=IDS)
def test_clingo_enumerates_the_definitions_configurations(rule: Rule, case: Case) -> None:
    inst = compile_instance(case.library, case.schema, case.failed)
    listed = [c.assignment for c in ClingoEngine().configurations(inst)]
    assert sorted(listed) == sorted(c.assignment for c in brute_force(case))


@pytest.mark.parametrize(("rule", "case"), PAIRS, ids=IDS)
def test_counting_counts_the_definitions_configurations(rule: Rule, case: Case) -> None:
    inst = compile_instance(case.library, case.schema, case.failed)
    expected = brute_force(case)
    assert count(inst) == len(expected)
    alive, _, _ = prune(inst)  # pruning is sound: it keeps every valid configuration
    for config in expected:
        for u, (role, name) in enumerate(config.assignment):
            assert as_candidate(role, name) in alive[u]


@pytest.mark.parametrize(("rule", "case"), PAIRS, ids=IDS)
def test_elimination_reaches_the_definitions_optimum(rule: Rule, case: Case) -> None:
    """Optimise towards the last valid configuration and towards each witness.

    Staying with a witness (which breaks the rule) costs nothing, so an encoding without
    the rule would return it; the definition's optimum is a valid configuration.
    """
    inst = compile_instance(case.library, case.schema, case.failed)
    expected = brute_force(case)
    roles = {r.name for r in case.schema.graph.roles}
    currents = [dict(expected[-1].assignment) if expected else {}]
    currents += [w for w in case.witnesses if set(w) == roles]
    for current in currents:
        objective = Objective(current=current, weights={"cost": 1.0})
        for engine in (EliminationEngine(), ClingoEngine()):
            best = engine.best(inst, objective)
            if not expected:
                assert best is None, engine.name
                continue
            assert best is not None, engine.name
            assert is_valid(best, case.library, case.schema, case.failed), engine.name
            least = min(objective.cost(inst, c) for c in expected)
            assert objective.cost(inst, best) == least, engine.name


@pytest.mark.planner
@pytest.mark.parametrize(("rule", "case"), PAIRS, ids=IDS)
def test_pddl_plans_the_definitions_configurations(rule: Rule, case: Case) -> None:
    planned = plan_all(case.library, case.schema, tuple(sorted(case.failed)))
    assert planned == set(brute_force(case))


@pytest.mark.parametrize(
    ("rule", "case"), [p for p in PAIRS if p[1].without], ids=lambda x: getattr(x, "name", "")
)
def test_relaxed_edges_matter(rule: Rule, case: Case) -> None:
    """Each case with an optional edge or role has fewer configurations when it is required."""
    assert case.without is not None
    strict = brute_force(case, case.without)
    loose = brute_force(case)
    assert {c.assignment for c in strict} <= {c.assignment for c in loose}
    if rule.name in ("optional-edge", "optional-role"):
        assert len(strict) < len(loose)


# --- the bundled example that needs optional edges -------------------------------------------


def test_map_navigation_needs_its_optional_edges() -> None:
    """libraries/nav_robot.yaml has 36 configurations; with plain edges and roles it has none.

    24 fill the optional map role; the 12 that localise with SLAM may also leave it empty
    (issue 22: a map server not needed under SLAM), and AMCL never does.
    """
    loaded = load_bundled()
    library = loaded.library
    schema = next(s for s in loaded.schemas if s.name == "map_navigation")
    assert any(e.optional for e in schema.graph.edges) and schema.graph.role("map").optional
    inst = compile_instance(library, schema)
    listed = list(ClingoEngine().configurations(inst))
    assert len(listed) == count(inst) == 36
    assert all(is_valid(c, library, schema) for c in listed)
    teb = [c for c in listed if c.mapping["controller"] == "TEB_CONTROLLER"]
    assert len(teb) == 18  # TEB does not read the lidar, and is still chosen
    empty = [c for c in listed if c.mapping["map"] == EMPTY]
    assert len(empty) == 12 and {c.mapping["localisation"] for c in empty} == {"NAV_SLAM"}
    plain = replace(
        schema,
        graph=SystemGraph(
            tuple(replace(r, optional=False) for r in schema.graph.roles),
            tuple(replace(e, optional=False) for e in schema.graph.edges),
        ),
    )
    strict = compile_instance(library, plain)
    assert count(strict) == 0
    assert not any(is_valid(c, library, plain) for c in listed)
    filled = replace(schema, graph=replace(plain.graph, edges=schema.graph.edges))
    assert count(compile_instance(library, filled)) == 24  # the map role required again
    best = EliminationEngine().best(inst, Objective(weights={"cost": 1.0}))
    assert best is not None and is_valid(best, library, schema)


@pytest.mark.planner
def test_map_navigation_plans_with_fast_downward() -> None:
    """Role ``map`` and topic ``map`` share a name; PDDL still gets distinct objects."""
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "map_navigation")
    task = render(compile_instance(loaded.library, schema), Objective(weights={"cost": 1.0}))
    result = solve(FastDownward(), task.domain, task.problem, timeout=60, memory_limit_mb=1024)
    assert result.solved, result.message
    assert is_valid(chosen(task, result, schema), loaded.library, schema)
