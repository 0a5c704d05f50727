"""``rosreconf analyse``: orthogonality, redundancy, failure points and reliability."""

from __future__ import annotations

import json
from dataclasses import asdict
from typing import Annotated

import typer

from rosreconf.analysis.library import SchemaAnalysis, analyse
from rosreconf.cli.common import (
    FailOption,
    JsonOption,
    LibraryOption,
    OnlyOption,
    SchemaOption,
    select,
)
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode


def analyse_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    only: OnlyOption = None,
    samples: Annotated[
        int, typer.Option(min=100, help="Monte Carlo samples when exact is too large.")
    ] = 20_000,
    seed: Annotated[int, typer.Option(help="Monte Carlo seed.")] = 0,
    as_json: JsonOption = False,
) -> None:
    """Analyse orthogonality, redundancy, failure points and reliability of each schema.

    Orthogonality is Def. 8; redundancy per role is the paper's r; single points of failure and
    critical pairs are failures that leave no configuration; the reconfigurability probability
    is exact when the configurations can be listed, else Monte Carlo with its interval.

    Exit 0 when every schema has a configuration, 1 otherwise.
    """

    sel = select(library, schema, fail, only)
    results = [analyse(sel.library, s, sel.failed, samples=samples, seed=seed) for s in sel.schemas]
    if as_json:
        doc = {
            "failed": list(sel.failed),
            "files": sel.loaded.files,
            "schemas": [asdict(r) for r in results],
        }
        write_stdout(json.dumps(doc, indent=2) + "\n")
    else:
        write_stdout("".join(_text(r) for r in results))
    raise typer.Exit(ExitCode.FAILED if any(r.valid == 0 for r in results) else ExitCode.OK)


def _text(a: SchemaAnalysis) -> str:
    lines = [f"{a.title} ({a.schema})"]
    if a.orthogonal:
        lines.append(f"  orthogonal: yes (all {a.substitutions} substitutions are valid)")
    else:
        lines.append(
            f"  orthogonal: no ({a.valid} of {a.substitutions} label-respecting substitutions "
            "are valid)"
        )
        for ip in a.incompatible[:12]:
            lines.append(f"    {ip.first} x {ip.second}: {ip.reason}")
        if len(a.incompatible) > 12:
            lines.append(f"    ... and {len(a.incompatible) - 12} more incompatible pairs (--json)")
    lines.append("  redundancy per role (r = candidates; usable = in some valid configuration):")
    for r in a.redundancy:
        usable = "?" if r.usable is None else str(len(r.usable))
        lines.append(
            f"    {r.role:<18} r={len(r.candidates)} usable={usable}  {', '.join(r.candidates)}"
        )
    spof = ", ".join(a.single_points_of_failure) or "none"
    lines.append(f"  single points of failure: {spof}")
    if a.critical_pairs is None:
        lines.append("  critical pairs: too many components to check here (use rosreconf whatif)")
    else:
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
                "    assumed never to fail (no failure_probability): "
                + ", ".join(rel.assumed_reliable)
            )
    else:
        lines.append("  reconfigurability probability: 0 (no configuration)")
    return "\n".join(lines) + "\n\n"
