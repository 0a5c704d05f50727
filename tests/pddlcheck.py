"""Enumerate configurations by planning, for the PDDL cross-checks against clingo."""

from __future__ import annotations

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.planning.pddl import PddlTask, render
from rosreconf.planning.planners import FastDownward, PlanResult, PlanStatus, solve
from rosreconf.solve.instance import compile_instance


def chosen(task: PddlTask, result: PlanResult, s: InteroperabilitySchema) -> Configuration:
    """Return the configuration a plan's choose steps build."""
    picks = {}
    for name, args in result.actions:
        step = task.names.step(name)
        assert step is not None and not args, name
        if step.kind == "choose":
            picks[step.role] = step.component
    return Configuration.of(s.name, picks, s.graph.roles)


def plan_all(
    library: ComponentLibrary,
    s: InteroperabilitySchema,
    failed: tuple[str, ...] = (),
    planner: FastDownward | None = None,
    most: int = 40,
) -> set[Configuration]:
    """Plan, forbid the configuration found, and repeat until the task is proven unsolvable."""
    inst = compile_instance(library, s, failed)
    found: list[Configuration] = []
    while True:
        task = render(inst, forbid=found)
        result = solve(
            planner or FastDownward(), task.domain, task.problem, timeout=30, memory_limit_mb=1024
        )
        if not result.solved:
            assert result.status is PlanStatus.UNSOLVABLE_PROVEN, result.message
            return set(found)
        config = chosen(task, result, s)
        assert config not in found
        found.append(config)
        assert len(found) <= most
