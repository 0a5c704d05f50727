"""Re-plan one schema after failures: render PDDL, run a planner, read the plan back, check it.

``plan`` joins the stages: ``instance`` (static tables) -> ``pddl`` (text and names) ->
``planners.solve`` (an external planner) -> back through ``PddlNames`` to a Configuration,
which is accepted only if ``validity.violations`` finds nothing wrong with it. The solver
answers first (``solve.solver.optimise``: exact min-plus elimination, clingo only when a
table would be too big; clingo's first model when there is no current configuration)
whether any configuration exists at all, so that an impossible task gets its why-not text
instead of a planner's bare "unsolvable", and how few changes are possible, so that the
report can say whether the planner's plan is a minimal change. Its optimum is the
configuration ``watch`` would apply (``rosreconf.solve.objective.PREFERENCE``): a plan for
another one is set aside and the planner asked again for that one
(``rosreconf.planning.preferred``).
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

from rosreconf.model import EMPTY, ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.validity import violations
from rosreconf.model.wiring import Wire
from rosreconf.outfiles import output_folder, write_files_atomic
from rosreconf.planning.narrative import Change, changes, explain_impossible, explain_replan
from rosreconf.planning.pddl import PddlTask, render
from rosreconf.planning.pddl_names import Step
from rosreconf.planning.planners import Planner, PlanResult, PlanStatus, solve
from rosreconf.planning.preferred import pinned, set_aside
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.running import change_objective
from rosreconf.solve.search import Budget
from rosreconf.solve.solver import ClingoEngine, optimise
from rosreconf.solve.unfillable import explain


@dataclass(frozen=True)
class ReplanResult:
    """The answer for one schema.

    Attributes:
        schema: the schema.
        status: SOLVED, UNSOLVABLE_PROVEN (no configuration exists: see ``why_not``) or the
            planner's failure (TIMEOUT, PLANNER_ERROR, ...).
        current: the running configuration it started from (role -> component; may be empty).
        configuration: the new configuration (None unless SOLVED).
        steps: the plan's steps in plain words, in order (Figure 8 style).
        actions: the plan's PDDL action names, in order.
        changes: per role, keep / replace / start.
        explanation: sentences for the operator.
        why_not: why no configuration exists (empty unless UNSOLVABLE_PROVEN).
        message: how the planner run went, or what was wrong with its plan.
        fewest_changes: the fewest role changes any valid configuration needs (the optimum's proof).
        planner: the planner's result (None when no planner ran).
        unaffected: why no planner ran because the running configuration stays valid (no
            failed component in it); empty when the schema was re-planned.
    """

    schema: InteroperabilitySchema
    status: PlanStatus
    current: Mapping[str, str]
    configuration: Configuration | None = None
    steps: tuple[str, ...] = ()
    actions: tuple[str, ...] = ()
    changes: tuple[Change, ...] = ()
    explanation: tuple[str, ...] = ()
    why_not: str = ""
    message: str = ""
    fewest_changes: int | None = None
    planner: PlanResult | None = field(default=None, repr=False)
    unaffected: str = ""


def plan(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
    planner: Planner,
    *,
    weights: Mapping[str, float] | None = None,
    timeout: float = 60.0,
    memory_limit_mb: int = 2048,
    keep_pddl: Path | None = None,
    budget: Budget | None = None,
    wired: Mapping[str, frozenset[Wire]] | None = None,
) -> ReplanResult:
    """Plan ``schema``'s new configuration after ``failed`` went down, from ``current``.

    A schema whose running configuration holds no failed component and is still valid keeps
    running as it is: no planner runs for it (a planner would only prove "change nothing").
    ``wired`` (``change_objective``): what the running components are wired to now when they
    run under another schema, for a task switch (``rosreconf.planning.switch``); then the
    planner always runs, since a valid ``current`` may still need restarts.
    """
    kept = unaffected(library, schema, failed, current) if wired is None else None
    if kept is not None:
        config, reason = kept
        return ReplanResult(
            schema,
            PlanStatus.SOLVED,
            current,
            configuration=config,
            changes=tuple(changes(library, schema, current, config)),
            explanation=tuple(explain_replan(library, schema, failed, current, config, 0)),
            message="unaffected: no planner run",
            fewest_changes=0,
            unaffected=reason,
        )
    inst = compile_instance(library, schema, failed)
    objective = change_objective(library, schema, current, weights, wired)
    best = optimise(inst, objective).configuration if current else ClingoEngine().first(inst)
    if best is None:
        why = explain(inst)
        lines = explain_impossible(schema, inst.failed, current, why)
        return ReplanResult(
            schema, PlanStatus.UNSOLVABLE_PROVEN, current, why_not=why, explanation=tuple(lines)
        )
    passed: list[Configuration] = []
    notes: list[str] = []
    if schema.simulation is not None:
        target, passed, notes = _performing(
            library, schema, inst.failed, current, weights, best, budget
        )
        if target is None:
            why = notes[-1]
            lines = [*explain_impossible(schema, inst.failed, current, why)]
            return ReplanResult(
                schema, PlanStatus.UNSOLVABLE_PROVEN, current, why_not=why, explanation=tuple(lines)
            )
        best = target
    fewest = objective.score(inst, best)[0] if current else None
    if passed:  # pin the planner to the performing target: its components are all it may choose
        rest = {c.name for c in library.components} - set(best.components)
        task = render(compile_instance(library, schema, set(inst.failed) | rest), objective)
    else:
        task = render(inst, objective)
    if keep_pddl is not None:
        write_task(task, keep_pddl)
    run = solve(
        planner, task.domain, task.problem, timeout=timeout, memory_limit_mb=memory_limit_mb
    )
    if not run.solved:
        message = run.message
        if run.status is PlanStatus.UNSOLVABLE_PROVEN:  # clingo found one: the task is wrong
            message = f"the planner found no plan, yet a configuration exists ({run.message})"
            return ReplanResult(
                schema, PlanStatus.PLANNER_ERROR, current, message=message, planner=run
            )
        return ReplanResult(schema, run.status, current, message=message, planner=run)
    result = _read_back(library, schema, inst.failed, current, task, run, fewest)
    if current and result.configuration is not None and result.configuration != best:
        # the planner may stop at any plan (ff-first ignores costs) or break a tie its own
        # way: the configuration is the preference's, the one watch applies, always
        notes.append(set_aside(inst, objective, result.configuration, best))
        task = render(pinned(inst, best), objective)
        run = solve(
            planner, task.domain, task.problem, timeout=timeout, memory_limit_mb=memory_limit_mb
        )
        if not run.solved:
            message = f"planning again for the preferred configuration: {run.message}"
            return ReplanResult(schema, run.status, current, message=message, planner=run)
        result = _read_back(library, schema, inst.failed, current, task, run, fewest)
    return replace(result, explanation=(*notes, *result.explanation)) if notes else result


def _performing(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
    weights: Mapping[str, float] | None,
    fewest: Configuration,
    budget: Budget | None = None,
) -> tuple[Configuration | None, list[Configuration], list[str]]:
    """Return the target that meets the performance requirements, what it passed over, and notes.

    When the plain optimum ``fewest`` performs (and no simulated metric is weighted) it
    stands and nothing is passed over. Otherwise the planner is pinned to the chosen target:
    its task offers only the target's components (the caller's ``render`` of an instance
    without the others). Forbidding every other valid configuration in the task instead
    stopped at 2000 of them (1000 roles x 10 candidates have 10^900), and a note
    says why the fewest-change configuration was passed over.
    """
    from rosreconf.analysis.choice import choose, shortfall  # imports numpy

    choice = choose(library, schema, fewest, current, dict(weights or {}), failed, budget=budget)
    notes: list[str] = []
    if choice.passed_over_performance is not None:
        notes.append(
            "The fewest-change configuration was passed over: it fails the schema's "
            f"performance requirements ({shortfall(schema, choice.passed_over_performance)})."
        )
    if choice.configuration is None:
        notes.append(
            "every valid configuration fails the schema's performance requirements "
            f"({choice.tried} simulated to prove it; rosreconf simulate shows by how much)"
        )
        return None, [], notes
    if choice.configuration == fewest:
        return fewest, [], notes
    return choice.configuration, [fewest], notes


def unaffected(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
) -> tuple[Configuration, str] | None:
    """Return the running configuration and why it keeps running, or None if it must change.

    It keeps running when it fills every role, none of its components failed, and it is
    still a valid configuration with those components gone (Definition 5 checked again by
    ``validity.violations``, so a failure that breaks it indirectly is never missed).
    """
    roles = schema.graph.roles
    if not current or any(r.name not in current for r in roles if not r.optional):
        return None
    down = set(failed)
    if down & set(current.values()):
        return None
    config = Configuration.of(schema.name, dict(current), roles)
    if violations(config, library, schema, failed):
        return None
    names = ", ".join(sorted(down))
    return config, f"none of its running components failed ({names} not among them)"


def _read_back(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    current: Mapping[str, str],
    task: PddlTask,
    run: PlanResult,
    fewest: int | None,
) -> ReplanResult:
    """Map the plan's actions back onto the model and accept only a valid configuration."""
    steps: list[Step] = []
    for name, args in run.actions:
        step = task.names.step(name)
        if step is None or args:
            shown = f"({' '.join([name, *args])})"
            message = f"plan names unknown action {shown}"
            return ReplanResult(
                schema, PlanStatus.PLANNER_ERROR, current, message=message, planner=run
            )
        steps.append(step)
    chosen = {s.role: s.component for s in steps if s.kind == "choose"}
    roles = schema.graph.roles
    missing = [r.name for r in roles if r.name not in chosen]
    if missing:
        message = f"the plan leaves {', '.join(missing)} unfilled"
        return ReplanResult(schema, PlanStatus.PLANNER_ERROR, current, message=message, planner=run)
    # A connect step names the provider role; the provider is whatever the plan chose there.
    steps = [
        replace(s, component=chosen[s.provider_role])
        if s.kind == "connect" and s.provider_role in chosen
        else s
        for s in steps
    ]
    # a restart step stands after its role's choice: the operator reads "keep, then restart"
    restarted = {s.role for s in steps if s.kind == "restart"}
    config = Configuration.of(schema.name, chosen, roles)
    wrong = violations(config, library, schema, failed)
    if wrong:
        message = "the plan is not a valid configuration: " + "; ".join(map(str, wrong))
        return ReplanResult(schema, PlanStatus.PLANNER_ERROR, current, message=message, planner=run)
    lines = explain_replan(library, schema, failed, current, config, fewest)
    return ReplanResult(
        schema,
        PlanStatus.SOLVED,
        current,
        configuration=config,
        steps=tuple(
            _step_text(s, current, chosen, restarted)
            for s in steps
            if s.kind in ("choose", "connect")
        ),
        actions=tuple(name for name, _ in run.actions),
        changes=tuple(changes(library, schema, current, config)),
        explanation=tuple(lines),
        message=run.message,
        fewest_changes=fewest,
        planner=run,
    )


def _step_text(
    step: Step, current: Mapping[str, str], chosen: Mapping[str, str], restarted: set[str]
) -> str:
    """Say one plan step the way Figure 8 of the paper lists them."""
    if step.kind == "choose":
        before = current.get(step.role)
        if before and step.role in restarted:
            return f"restart {step.component} as {step.role} (rewired)"
        if (before or EMPTY) == step.component:
            return f"keep {step.component} as {step.role}" if before else f"keep {step.role} empty"
        if step.component == EMPTY:  # rule optional-role
            return f"stop {before}, leave {step.role} empty"
        if not before:
            return f"start {step.component} as {step.role}"
        return f"stop {before}, start {step.component} as {step.role}"
    assert step.requirement is not None and step.provider_role is not None
    labels = " or ".join(o.label for o in step.requirement.options)
    return (
        f"connect {chosen[step.role]} ({step.role}) to {step.component} "
        f"({step.provider_role}) for {labels}"
    )


def write_task(task: PddlTask, folder: Path) -> Path:
    """Write ``folder/<schema>/domain.pddl`` and ``problem.pddl`` as one pair.

    The pair moves into place in one step (``write_files_atomic``), so two runs writing into
    one folder never leave a domain of one beside a problem of the other.
    """
    files = {"domain.pddl": task.domain, "problem.pddl": task.problem}
    return write_files_atomic(output_folder(folder) / task.schema, files)


def replan_all(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    failed: Collection[str],
    running: Mapping[str, Mapping[str, str]],
    planner: Planner,
    *,
    weights: Mapping[str, float] | None = None,
    timeout: float = 60.0,
    keep_pddl: Path | None = None,
    budget: Budget | None = None,
) -> list[ReplanResult]:
    """Plan every schema after ``failed`` from what runs (``rosreconf.solve.running``).

    One schema's failure (no configuration, a planner timeout) does not stop the others.
    """
    return [
        plan(
            library,
            s,
            failed,
            running[s.name],
            planner,
            weights=weights,
            timeout=timeout,
            keep_pddl=keep_pddl,
            budget=budget,
        )
        for s in schemas
    ]


def write_tasks(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    failed: Collection[str],
    running: Mapping[str, Mapping[str, str]],
    weights: Mapping[str, float],
    folder: Path,
) -> list[Path]:
    """Write every schema's PDDL task under ``folder``; return the files written, in order."""
    written: list[Path] = []
    for s in schemas:
        objective = change_objective(library, s, running[s.name], weights)
        task = render(compile_instance(library, s, failed), objective)
        where = write_task(task, folder)
        written += [where / "domain.pddl", where / "problem.pddl"]
    return written
