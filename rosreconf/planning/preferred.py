"""Hold a planner's plan to rosreconf's preference, so that ``plan`` chooses what ``watch`` does.

A planner returns some plan: ``ff-first`` ignores action costs, an anytime search stops at
its time limit, and an optimal one settles a tie its own way. The configuration that should
run is the preference's (``rosreconf.solve.objective.PREFERENCE``: fewest changes, then
fewest replaced, then the metric sum, then enumeration order), the one the in-process
solvers prove and ``watch`` applies. When the planner's plan is another configuration,
``plan`` says why it was set aside (``set_aside``) and asks the planner again for the
preferred one alone (``pinned``: each role's candidates cut to its component), so the steps
shown are still the planner's and still checked against the rules of validity.
"""

from __future__ import annotations

import dataclasses

from rosreconf.model import Configuration, shown_text
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import Instance
from rosreconf.solve.objective import Objective


def pinned(inst: Instance, config: Configuration) -> Instance:
    """Return ``inst`` with each role's candidates cut to ``config``'s: its plans are for it.

    The tables are cut with the domains (which provider meets which requirement, which
    pairs realise an edge), so the task names only what the cut domains hold.
    """
    chosen = [as_candidate(r.name, config.mapping[r.name]) for r in inst.roles]
    return dataclasses.replace(
        inst,
        domains=[[c for c in dom if c.name == chosen[r]] for r, dom in enumerate(inst.domains)],
        meets={
            (u, cu, i): [(v, cv) for v, cv in pairs if cv == chosen[v]]
            for (u, cu, i), pairs in inst.meets.items()
            if cu == chosen[u]
        },
        partners=[
            {
                cu: {cv for cv in mates if cv == chosen[v]}
                for cu, mates in table.items()
                if cu == chosen[u]
            }
            for (u, v), table in zip(inst.edges, inst.partners, strict=True)
        ],
    )


WHY = (
    "it needs more changes",
    "it replaces more components, where a restart of a kept node would do",
    "its weighted metric sum is higher",
    "it ties, and the first in enumeration order is chosen (roles in schema order, "
    "candidates in library order)",
)
"""Why a plan is set aside, by the first level of ``Objective.key`` where it is worse."""


def set_aside(
    inst: Instance, objective: Objective, planned: Configuration, best: Configuration
) -> str:
    """Say why the planner's own plan was set aside for ``best`` (``objective.PREFERENCE``)."""
    theirs, ours = objective.key(inst, planned), objective.key(inst, best)
    level = next(i for i, (a, b) in enumerate(zip(theirs, ours, strict=True)) if a != b)
    roles = "; ".join(
        f"{r}: {shown_text(c)} instead of {shown_text(best.mapping[r])}"
        for r, c in planned.assignment
        if c != best.mapping[r]
    )
    return (
        f"The planner's own plan chose {roles} ({theirs[0]} change(s)), set aside: "
        f"{WHY[min(level, len(WHY) - 1)]}. The configuration below is the one watch applies "
        "(rosreconf's one preference), and the plan shown is the planner's for it."
    )
