"""Report ``rosreconf whatif``: a table per schema for people, one JSON document for programs.

The text is a rich ``Table`` (the CLI's console fits it to the terminal), the JSON a string;
both are built here from the ``SchemaReport``s, so the CLI only picks one and writes it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rich.table import Table

from rosreconf import jsonout
from rosreconf.analysis.whatif import SchemaReport


def table(report: SchemaReport, title: str, k: int) -> Table:
    """Return one schema's answer as a rich table (rich fits it to the terminal's width)."""
    table = Table(title=f"{title} ({report.schema})", title_justify="left", show_header=False)
    table.add_column("what")
    table.add_column("value", overflow="fold")
    table.add_row(
        "relevant components",
        f"{len(report.relevant)} of {report.components} (the others are in no valid "
        "configuration, so their failure changes nothing)",
    )
    table.add_row("critical components", ", ".join(report.critical) or "none")
    pairs = report.critical_pairs
    table.add_row("critical pairs", ", ".join(f"{{{a}, {b}}}" for a, b in pairs) or "none")
    for size in range(1, k + 1):
        alive, total = report.survived(size)
        table.add_row(f"survives {size} failure(s)", f"{alive / total:.2%} ({alive} of {total})")
    table.add_row("solver calls", f"{report.solver_calls} (the rest decided by pruning)")
    return table


def document(reports: Sequence[SchemaReport], k: int, context: dict[str, Any] | None = None) -> str:
    """Return the JSON document (output-whatif.schema.json), newline included.

    ``context`` is the ``context`` member (``reports.context``): its ruled-out components are
    unusable in every failure set, and in none of the sets swept.
    """
    out = []
    for r in reports:
        shares = []
        for size in range(1, k + 1):
            alive, total = r.survived(size)
            shares.append({"k": size, "survived": alive, "total": total, "share": alive / total})
        out.append(
            {
                "name": r.schema,
                "components": r.components,
                "relevant": list(r.relevant),
                "critical": r.critical,
                "critical_pairs": [list(p) for p in r.critical_pairs],
                "shares": shares,
                "solver_calls": r.solver_calls,
                "failure_sets": [
                    {
                        "failed": list(o.failed),
                        "survives": o.survives,
                        "configuration": list(o.configuration) if o.configuration else None,
                    }
                    for o in r.listed
                ],
                "failure_sets_complete": r.listed_all,
            }
        )
    doc: dict[str, Any] = {"max_failures": k, "schemas": out}
    if context is not None:
        doc["context"] = context
    return jsonout.dumps(doc) + "\n"
