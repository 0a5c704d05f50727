"""Report ``rosreconf analyse``: orthogonality, redundancy, failure points, reliability."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict
from typing import Protocol

from rosreconf import jsonout
from rosreconf.analysis.library import SchemaAnalysis
from rosreconf.analysis.thresholds import Thresholds
from rosreconf.formats.selection import Selection
from rosreconf.render.reports import Output
from rosreconf.render.reports.context import (
    context_doc,
    context_text,
    thresholds_doc,
    thresholds_text,
)


class AnalyseReporter(Protocol):
    """Render the analyses of the selected schemas."""

    def render(
        self,
        sel: Selection,
        results: Sequence[SchemaAnalysis],
        tables: Sequence[Thresholds] = (),
    ) -> str:
        """Return the whole report; ``tables``: the context thresholds of each schema."""
        ...


class TextReporter:
    """One block per schema; long lists are cut (the JSON has them whole)."""

    def render(
        self,
        sel: Selection,
        results: Sequence[SchemaAnalysis],
        tables: Sequence[Thresholds] = (),
    ) -> str:
        """Return one block per schema, then the context thresholds."""
        blocks = "".join(_text(r) for r in results)
        return context_text(sel) + blocks + thresholds_text(tables)


class JsonReporter:
    """One JSON document: the failures assumed, the files and every analysis in full."""

    def render(
        self,
        sel: Selection,
        results: Sequence[SchemaAnalysis],
        tables: Sequence[Thresholds] = (),
    ) -> str:
        """Return the JSON document; the thresholds are in ``context``."""
        doc: dict[str, object] = {
            "failed": list(sel.failed),
            "files": sel.loaded.files,
            "schemas": [asdict(r) for r in results],
        }
        said = context_doc(sel)
        if said is not None:
            doc["context"] = {**said, "thresholds": thresholds_doc(tables)}
        return jsonout.dumps(doc, indent=2) + "\n"


REPORTERS: dict[Output, AnalyseReporter] = {
    Output.TEXT: TextReporter(),
    Output.JSON: JsonReporter(),
}


def _text(a: SchemaAnalysis) -> str:
    lines = [f"{a.title} ({a.schema})"]
    if a.orthogonal:
        lines.append(f"  orthogonal: yes (all {a.substitutions} substitutions are valid)")
    else:
        lines.append(
            f"  orthogonal: no ({a.valid} of {a.substitutions} label-respecting substitutions "
            "are valid)"
        )
        for un in a.unusable[:12]:
            lines.append(f"    {un.component} (in no configuration): {un.reason}")
        if len(a.unusable) > 12:
            lines.append(
                f"    ... and {len(a.unusable) - 12} more components in no configuration (--json)"
            )
        for ip in a.incompatible[:12]:
            lines.append(f"    {ip.first} x {ip.second}: {ip.reason}")
        if len(a.incompatible) > 12:
            lines.append(f"    ... and {len(a.incompatible) - 12} more incompatible pairs (--json)")
        if not a.counterexamples_complete:
            lines.append(
                "    (a sample: some substitutions fail only through three or more components "
                "together, when a requirement can be met from several roles)"
            )
    lines.append("  redundancy per role (r = candidates; usable = in some valid configuration):")
    for r in a.redundancy:
        usable = "?" if r.usable is None else str(len(r.usable))
        empty = "  (optional: may stay empty)" if r.may_stay_empty else ""
        lines.append(
            f"    {r.role:<18} r={len(r.candidates)} usable={usable}  {_few(r.candidates)}{empty}"
        )
    if a.valid == 0:
        lines.append("  single points of failure: not applicable (no configuration to lose)")
        lines.append("  critical pairs: not applicable (no configuration to lose)")
    elif a.critical_pairs is None:
        lines.append(f"  single points of failure: {_spof(a)}")
        lines.append("  critical pairs: too many components to check here (use rosreconf whatif)")
    else:
        lines.append(f"  single points of failure: {_spof(a)}")
        pairs = ", ".join(f"{{{x}, {y}}}" for x, y in a.critical_pairs[:15])
        more = f" ... ({len(a.critical_pairs)} in all)" if len(a.critical_pairs) > 15 else ""
        lines.append(
            f"  critical pairs (kill it though neither alone does): {pairs or 'none'}{more}"
        )
    if a.reliability is not None:
        rel = a.reliability
        interval = "" if rel.low == rel.high else f" (95 % interval {rel.low:.6f}-{rel.high:.6f})"
        lines.append(f"  reconfigurability probability: {rel.probability:.6f}{interval}")
        lines.append(f"    method: {rel.method}")
        if rel.assumed_reliable:
            lines.append(
                "    assumed never to fail (no failure_probability): " + _few(rel.assumed_reliable)
            )
    else:
        lines.append("  reconfigurability probability: 0 (no configuration)")
    return "\n".join(lines) + "\n\n"


FEW = 10
"""Names a text line shows of a long list before it says how many more (the JSON has all)."""


def _few(names: Sequence[str]) -> str:
    """Join up to ``FEW`` names; say how many more there are and where to get them all."""
    if len(names) <= FEW:
        return ", ".join(names)
    return (
        ", ".join(names[:FEW]) + f" ... and {len(names) - FEW} more ({len(names)} in all; --json)"
    )


def _spof(a: SchemaAnalysis) -> str:
    """List the single points of failure of a schema that has a configuration."""
    return ", ".join(a.single_points_of_failure) or "none"
