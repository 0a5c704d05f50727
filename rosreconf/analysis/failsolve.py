"""Solve a schema under failure sets: the unit of work of a what-if sweep, for any pool.

``evaluate_chunk`` is a pure function of a picklable ``Chunk`` (a ``Task``: the schema's
ASP program and name tables, no clingo objects, and some failure sets), so it runs in a
process pool here or on Dask/Ray workers unchanged (docs/whatif.md). It grounds the program
once per process and solves each set under assumptions (the failed components' atoms
false).
"""

from __future__ import annotations

import functools
from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass

import clingo

from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.emptyroles import as_chosen
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import PROGRAM, _facts

__all__ = ["Chunk", "Outcome", "Task", "evaluate", "evaluate_chunk", "make_task"]


@dataclass(frozen=True)
class Task:
    """Everything a worker needs to solve one schema under failures (plain, picklable data).

    Attributes:
        schema: the schema's name.
        program: the ASP program with the schema's ground facts.
        roles: role names, by role index.
        components: component names, by component id.
        atoms: component name -> the (role index, component id) pairs it may fill.
    """

    schema: str
    program: str
    roles: tuple[str, ...]
    components: tuple[str, ...]
    atoms: Mapping[str, tuple[tuple[int, int], ...]]


@dataclass(frozen=True)
class Chunk:
    """A unit of work: some failure sets of one task."""

    task: Task
    failure_sets: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class Outcome:
    """Whether a schema survives one failure set.

    Attributes:
        failed: the failed components, in library order.
        configuration: the surviving configuration's components in role order, or None
            when the schema has no configuration under these failures (a ``Swapped`` view
            of the first configuration when twins were swapped in: ``solve.swaps``).
        solved: True when the solver decided it, False when pruning did.
    """

    failed: tuple[str, ...]
    configuration: Sequence[str] | None
    solved: bool = True

    @property
    def survives(self) -> bool:
        """Tell whether the schema still has a configuration."""
        return self.configuration is not None


def make_task(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: Collection[str] = ()
) -> Task:
    """Compile ``schema`` over ``library`` into a worker's task description.

    ``failed`` components are gone from every task (what context rules out).
    """
    inst = compile_instance(library, schema, failed)
    # the instance's library: the library with each optional role's empty choice after it
    ids = {c.name: i for i, c in enumerate(inst.library.components)}
    atoms: dict[str, list[tuple[int, int]]] = {}
    for r, dom in enumerate(inst.domains):
        for c in dom:
            atoms.setdefault(c.name, []).append((r, ids[c.name]))
    return Task(
        schema.name,
        PROGRAM + _facts(inst),
        tuple(r.name for r in inst.roles),
        tuple(as_chosen(c.name) for c in inst.library.components),
        {name: tuple(pairs) for name, pairs in atoms.items()},
    )


def _control(task: Task, args: Sequence[str]) -> clingo.Control:
    ctl = clingo.Control(["--warn=none", *args])
    ctl.add("base", [], task.program)
    ctl.ground([("base", [])])
    return ctl


def evaluate_chunk(chunk: Chunk) -> list[Outcome]:
    """Solve every failure set of ``chunk``, one solve per set under assumptions.

    The ground program is kept for the task's next chunk in this process (``_grounded``):
    grounding 1000 roles x 10 candidates took 3.5 s, as long as 30 of the solves.
    """
    task = chunk.task
    ctl, table = _grounded(task)
    out = []
    for failed in chunk.failure_sets:
        off = [(table.atom[rc], False) for name in failed for rc in task.atoms.get(name, ())]
        found: list[tuple[str, ...]] = []
        ctl.solve(assumptions=off, on_model=functools.partial(_keep, task, table, found))
        out.append(Outcome(tuple(failed), found[0] if found else None))
    return out


@dataclass
class _Atoms:
    """A task's ``x(role, component id)`` atoms, both ways (reading a symbol's arguments
    cost five calls into clingo per atom, 20 s of 52 on 414 models of 1000 roles).
    """

    atom: dict[tuple[int, int], clingo.Symbol]
    pair: dict[clingo.Symbol, tuple[int, int]]


_GROUNDED: dict[str, tuple[clingo.Control, _Atoms]] = {}
"""The last task's program ground in this process (a worker's next chunk reuses it)."""


def _grounded(task: Task) -> tuple[clingo.Control, _Atoms]:
    """Return ``task``'s ground program and its atoms, grounding it once per process.

    Each solve forgets what earlier solves learnt and scored (``--forget-on-step``), so a
    set's answer never depends on which sets the process solved before it: the same
    configurations whatever the chunks and workers.
    """
    kept = _GROUNDED.get(task.program)
    if kept is None:
        _GROUNDED.clear()
        ctl = _control(task, ["--heuristic=Domain", "--models=1", "--forget-on-step=15"])
        table = _Atoms({}, {})
        for pairs in task.atoms.values():
            for rc in pairs:
                sym = clingo.Function("x", [clingo.Number(n) for n in rc])
                table.atom[rc], table.pair[sym] = sym, rc
        kept = _GROUNDED[task.program] = (ctl, table)
    return kept


def _keep(task: Task, table: _Atoms, found: list[tuple[str, ...]], model: clingo.Model) -> None:
    chosen = dict(table.pair[s] for s in model.symbols(shown=True))
    picked = (task.components[chosen[r]] for r in range(len(task.roles)))
    found.append(tuple(name for name in picked if name))  # an empty optional role: nothing


def evaluate(task: Task, failed: Iterable[str]) -> Outcome:
    """Solve one failure set (the single-set form of ``evaluate_chunk``)."""
    return evaluate_chunk(Chunk(task, (tuple(failed),)))[0]


def relevant_components(task: Task) -> frozenset[str]:
    """Return the components that appear in some valid configuration (brave consequences)."""
    ctl = _control(task, ["--enum-mode=brave", "--models=0"])
    last: list[str] = []

    def on_model(model: clingo.Model) -> None:
        picked = (task.components[s.arguments[1].number] for s in model.symbols(shown=True))
        last[:] = [name for name in picked if name]  # an empty optional role is no component

    result = ctl.solve(on_model=on_model)
    return frozenset(last) if result.satisfiable else frozenset()
