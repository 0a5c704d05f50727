"""Say which schemas a library cannot fill at all, for ``validate``'s warnings.

Decided by ``rosreconf.solve.instance``'s pruning (local reasoning, no solver: ``validate``
stays fast and never loads clingo), and said in ``enumerate``'s words (``explain``). Pruning
is sound, not complete: a schema whose every role keeps candidates but whose candidates never
combine is left to ``enumerate``.
"""

from __future__ import annotations

from collections.abc import Iterable

from rosreconf.errors import Problem, Severity
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.instance import compile_instance, explain, prune


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
