"""Tests for planning.pddl: names, golden files, parsers, VAL, and equivalence with clingo."""

from __future__ import annotations

import random
import subprocess
import sys
from pathlib import Path

import pddl
import pytest
from conftest import val_binary
from pddlcheck import plan_all

from rosreconf.formats.loader import load_checked
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
    SystemGraph,
)
from rosreconf.model.validity import is_valid
from rosreconf.planning.pddl import PddlNames, label, render
from rosreconf.planning.planners import FastDownward, solve
from rosreconf.planning.replan import write_task
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import Objective, configurations

GOLDEN = Path(__file__).parent / "golden"
EXAMPLE = load_checked()


def schema(name: str) -> InteroperabilitySchema:
    return next(s for s in EXAMPLE.schemas if s.name == name)


def normalise(text: str) -> list[str]:
    return [" ".join(line.split()) for line in text.splitlines() if line.strip()]


def test_labels_and_names_are_lower_case_and_collisions_get_a_prefix() -> None:
    assert label("/arm/cmd") == "root__arm__cmd"
    assert label("Camera_Image") == "camera_image"
    names = PddlNames()
    assert names.role("Camera") == "camera"
    assert names.component("NSM3") == "nsm3"
    assert names.component("CAMERA") == "component-camera"  # a role has the name: a prefix
    assert names.role("cAmera") == "role-camera"  # roles differing only in case
    assert names.role("CAMERA") == "role2-camera"
    assert names.component("CAMERA") == "component-camera"  # the same name, asked again
    assert names.objects["component-camera"] == ("component", "CAMERA")


@pytest.mark.parametrize("name", ["disc_loading", "indoor_navigation", "object_repositioning"])
def test_render_matches_the_golden_files(name: str, tmp_path: Path) -> None:
    s = schema(name)
    task = render(compile_instance(EXAMPLE.library, s), Objective(dict(s.nominal)))
    folder = write_task(task, tmp_path)
    for part in ("domain.pddl", "problem.pddl"):
        got = (folder / part).read_text(encoding="utf-8")
        assert normalise(got) == normalise((GOLDEN / name / part).read_text(encoding="utf-8"))


def test_the_pddl_parser_accepts_the_task(tmp_path: Path) -> None:
    s = schema("object_repositioning")
    inst = compile_instance(EXAMPLE.library, s, ["NSM3"])
    folder = write_task(render(inst, Objective(dict(s.nominal), {"cost": 1.0})), tmp_path)
    domain = pddl.parse_domain(folder / "domain.pddl")
    problem = pddl.parse_problem(folder / "problem.pddl")
    assert len(domain.actions) == len(render(inst).names.actions)
    assert problem.name == "rosreconf-object_repositioning-task"


@pytest.mark.planner
@pytest.mark.parametrize("failed", [["NSM3"], ["NCA1"], []])
def test_fast_downward_plans_map_back_and_val_accepts_them(
    failed: list[str], tmp_path: Path
) -> None:
    s = schema("object_repositioning")
    task = render(compile_instance(EXAMPLE.library, s, failed), Objective(dict(s.nominal)))
    result = solve(FastDownward(), task.domain, task.problem, timeout=30, memory_limit_mb=1024)
    assert result.solved, result.message
    steps = [task.names.step(name) for name, _ in result.actions]
    assert all(step is not None for step in steps)
    chosen = {st.role: st.component for st in steps if st is not None and st.kind == "choose"}
    config = Configuration.of(s.name, chosen, s.graph.roles)
    assert is_valid(config, EXAMPLE.library, s, failed)
    folder = write_task(task, tmp_path)
    plan = tmp_path / "plan"
    plan.write_text("".join(f"({name})\n" for name, _ in result.actions), encoding="utf-8")
    val = subprocess.run(
        [str(val_binary()), folder / "domain.pddl", folder / "problem.pddl", plan],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert val.returncode == 0, val.stdout + val.stderr
    assert "Plan valid" in val.stdout


def random_library(seed: int) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Build a small random library and schema with disjunctions, couplings and exclusions."""
    rng = random.Random(seed)
    ifaces = [Interface(InterfaceKind.TOPIC, f"t{i}", "m/T") for i in range(4)]
    roles = [Role(f"r{i}", f"a{i}") for i in range(3)]
    comps = []
    for i in range(3):
        for j in range(3):
            provides = frozenset(rng.sample(ifaces, rng.randint(1, 3)))
            requires = tuple(
                Requirement(tuple(rng.sample(ifaces, rng.randint(1, 2))))
                for _ in range(rng.randint(0, 1))
            )
            comps.append(Component(f"C{i}{j}", f"a{i}", provides, requires))
    names = [c.name for c in comps]
    coupled = []
    for c in comps:
        needs = frozenset(rng.sample(names, 1)) if rng.random() < 0.1 else frozenset()
        excludes = frozenset(rng.sample(names, 1)) if rng.random() < 0.2 else frozenset()
        coupled.append(
            Component(c.name, c.abstraction, c.provides, c.requires, needs=needs, excludes=excludes)
        )
    edges = tuple(
        Edge(f"r{u}", f"r{v}") for u in range(3) for v in range(3) if u != v and rng.random() < 0.5
    )
    lib = ComponentLibrary("random", tuple(coupled))
    return lib, InteroperabilitySchema("s", SystemGraph(tuple(roles), edges), "skill", "env")


@pytest.mark.planner
def test_planning_finds_exactly_the_configurations_clingo_finds() -> None:
    cases = [(EXAMPLE.library, schema("object_repositioning"))]
    randoms = [random_library(seed) for seed in range(40)]
    some = [c for c in randoms if next(configurations(*c), None) is not None][:5]
    none = [c for c in randoms if next(configurations(*c), None) is None][:1]
    cases += some + none
    for library, s in cases:
        expected = set(configurations(library, s))
        assert plan_all(library, s, planner=FastDownward("lama-first")) == expected, s.name


def test_a_component_failing_removes_its_actions() -> None:
    s = schema("disc_loading")
    task = render(compile_instance(EXAMPLE.library, s, ["NSM3"]))
    assert "(failed nsm3)" in task.problem
    assert not any("nsm3" in name for name in task.names.actions if name.startswith("choose"))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(pytest.main([__file__]))
