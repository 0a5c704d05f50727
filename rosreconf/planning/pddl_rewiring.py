"""Compile the wiring model's restarts into the PDDL task's literals (``rosreconf.planning.pddl``).

A kept component restarts when what it is wired to changes (``rosreconf.model.wiring``). In
the pre-grounded task every choose action of a provider candidate adds, for each kept
consumer it wires, ``(wire-U-K)`` for each thing K it wires the consumer to as now, and
``(rewired U)`` for anything else; the plain finish of the kept component needs every
``(wire-U-K)`` and no ``(rewired U)``, and ``restart-U-C`` finishes it instead for the price
of one change. So the planner's cost is the solvers' count, restarts included.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import Instance
from rosreconf.solve.objective import Objective


@dataclass
class Rewiring:
    """``Objective.restarts`` as literals: what each choice adds, what a kept role needs.

    Attributes:
        adds: (provider role, candidate) -> the literals choosing it adds: ``(wire-U-K)`` for
            each thing it wires the kept component of role U to that it is wired to now,
            ``(rewired U)`` for anything else.
        needs: consumer role -> the ``(wire-U-K)`` its kept component needs to stay as it is.
    """

    adds: dict[tuple[int, str], list[str]] = field(default_factory=dict)
    needs: dict[int, list[str]] = field(default_factory=dict)

    @property
    def flags(self) -> list[str]:
        """Return the 0-ary predicates the domain declares for it."""
        return [f[1:-1] for fs in self.needs.values() for f in fs]


def rewiring(inst: Instance, roles: list[str], objective: Objective) -> Rewiring:
    """Compile ``Objective.restarts`` for the choose and finish actions.

    ``roles``: the PDDL names of the instance's roles, in order.
    """
    index, table, out = inst.role_index, objective.restarts, Rewiring()
    number: dict[int, dict[object, int]] = {}
    for u, was in sorted(table.wired.items()):
        if u in index:
            number[index[u]] = {w: k for k, w in enumerate(sorted(was))}
            out.needs[index[u]] = [f"(wire-{roles[index[u]]}-{k})" for k in range(len(was))]
    for (u, v), offer in sorted(table.offers.items()):
        if u not in index or v not in index:
            continue
        ui, known = index[u], number.get(index[u], {})
        for name, pairs in offer.items():
            adds = out.adds.setdefault((index[v], as_candidate(v, name)), [])
            for w in sorted(pairs):
                k = known.get(w)
                adds.append(f"(rewired {roles[ui]})" if k is None else f"(wire-{roles[ui]}-{k})")
    return out
