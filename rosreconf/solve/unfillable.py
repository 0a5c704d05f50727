"""Say why a schema has no configuration, and which schemas a library cannot fill at all.

``explain`` words it for ``enumerate``, ``plan`` and the solvers; ``validate`` warns with it.

Decided by ``rosreconf.solve.instance``'s pruning (local reasoning, no solver: ``validate``
stays fast and never loads clingo), and said in ``enumerate``'s words (``explain``). Pruning
is sound, not complete: a schema whose every role keeps candidates but whose candidates never
combine is left to ``enumerate``.
"""

from __future__ import annotations

from collections.abc import Iterable

from rosreconf.errors import Problem, Severity
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.instance import Instance, compile_instance, prune


def schemas_without_configuration(
    library: ComponentLibrary, schemas: Iterable[InteroperabilitySchema]
) -> list[Problem]:
    """Return a warning, at the schema, for each schema ``library`` cannot fill, saying why."""
    warnings = []
    for schema in schemas:
        inst = compile_instance(library, schema)
        if not prune(inst)[2]:
            continue
        warnings.append(
            Problem(
                schema.span,
                f"schema '{schema.name}' has no configuration over the library: {explain(inst)}",
                hint="rosreconf enumerate says the same; add or fix the components it names",
                code="no-configuration",
                severity=Severity.WARNING,
            )
        )
    return warnings


def explain(inst: Instance) -> str:
    """Say in plain words why the schema has no configuration (empty if pruning finds none)."""
    alive, why, emptied = prune(inst)
    title = inst.schema.display_name
    for u in emptied[:1]:
        role = inst.roles[u]
        label = _article(role.abstraction.replace("_", " "))
        if not why[u]:
            return (
                f"{title} needs {label} (role {role.name}), but no component in the library "
                f"carries the label '{role.abstraction}'"
            )
        reasons = "; ".join(why[u][n] for n in sorted(why[u]))
        only = len(why[u]) == 1
        lead = "its only candidate" if only else "every candidate is ruled out"
        return f"{title} needs {label} (role {role.name}); {lead}: {reasons}"
    return (
        f"{title}: every role keeps candidates ("
        + ", ".join(f"{r.name}: {'/'.join(alive[i])}" for i, r in enumerate(inst.roles))
        + "), but no combination of them satisfies all edges, requirements and couplings "
        "together"
    )


def _article(noun: str) -> str:
    return ("an " if noun[:1] in "aeiou" else "a ") + noun
