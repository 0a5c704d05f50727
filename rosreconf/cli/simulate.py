"""``rosreconf simulate``: will each valid configuration perform? The paper's M-solution."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.table import Table

from rosreconf.cli.common import (
    FailOption,
    JsonOption,
    LibraryOption,
    OnlyOption,
    SchemaOption,
    select,
)
from rosreconf.cli.console import stderr, stdout, write_stdout
from rosreconf.errors import ExitCode

if TYPE_CHECKING:  # importing the simulation imports python-control: ~2 s, only when used
    from rosreconf.analysis.simulate import SchemaSimulation, Sweep


def simulate_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    fail: FailOption = None,
    limit: Annotated[
        int | None,
        typer.Option(
            min=1, help="Simulate at most N configurations per schema.", show_default=False
        ),
    ] = None,
    pareto: Annotated[
        str | None,
        typer.Option(
            help="List only the Pareto front over these metrics (comma-separated; simulated: "
            "settling_time, steady_state_error, overshoot; or the library's metrics).",
            show_default=False,
        ),
    ] = None,
    plot: Annotated[
        Path | None,
        typer.Option(
            help="Draw the step responses (and the front) to FILE.svg or .png.", show_default=False
        ),
    ] = None,
    workers: Annotated[
        int | None,
        typer.Option(min=1, help="Worker processes. Default: one per core.", show_default=False),
    ] = None,
    cluster: Annotated[
        str | None,
        typer.Option(help="Simulate on a Dask scheduler at tcp://HOST:PORT.", show_default=False),
    ] = None,
    as_json: JsonOption = False,
) -> None:
    """Simulate every valid configuration's control loops; rank by settling time and error."""
    from rosreconf.analysis.simulate import sweep

    sel = select(library, schema, fail, only)
    metrics = tuple(m.strip() for m in (pareto or "").split(",") if m.strip())
    result = sweep(
        sel.library, sel.schemas, sel.failed, limit, metrics, workers, cluster, explicit=bool(only)
    )
    if plot is not None:
        from rosreconf.render.plots import draw_sweep

        draw_sweep(plot, sel.library, result)
    if as_json:
        write_stdout(json.dumps(_document(result)) + "\n")
    else:
        for note in result.notes:
            stderr.print(f"rosreconf: {note}", markup=False)
        for report in result.reports:
            stdout.print(_table(report))
    ok = all(any(p.meets_requirements for p in r.ranked) for r in result.reports)
    raise typer.Exit(ExitCode.OK if ok else ExitCode.FAILED)


def _number(value: float | None) -> float | None:
    """Return ``value`` for JSON: None (null) for undefined or non-finite figures."""
    return value if value is not None and math.isfinite(value) else None


def _fmt(value: float | None, unit: str = "") -> str:
    if value is None or not math.isfinite(value):
        return "-"
    return f"{value:.3g}{unit}"


def _table(report: SchemaSimulation) -> Table:
    schema = report.schema
    assert schema.simulation is not None
    shown = report.pareto if report.pareto_metrics else range(len(report.ranked))
    loop_roles = [r for loop in schema.simulation.loops for r in loop.roles]
    title = f"{schema.display_name} ({schema.name}): {len(report.ranked)} configuration(s)"
    if report.pareto_metrics:
        title += f", Pareto front over {', '.join(report.pareto_metrics)}: {len(shown)}"
    table = Table(title=title, title_justify="left")
    table.add_column("#", justify="right")
    table.add_column(
        "components in the loops (" + ", ".join(dict.fromkeys(loop_roles)) + ")", overflow="fold"
    )
    table.add_column("stable")
    table.add_column("settling", justify="right")
    table.add_column("error", justify="right")
    table.add_column("overshoot", justify="right")
    table.add_column("meets")
    for i in shown:
        p = report.ranked[i]
        mapping = p.configuration.mapping
        table.add_row(
            str(i + 1),
            ", ".join(mapping[r] for r in dict.fromkeys(loop_roles)),
            "yes" if p.stable else "NO",
            _fmt(p.figures["settling_time"], " s"),
            _fmt(p.figures["steady_state_error"]),
            _fmt(p.figures["overshoot"], " %"),
            "yes" if p.meets_requirements else "no",
        )
    limits = schema.simulation.requirements.limits()
    caption = ["requirements: " + (", ".join(f"{m} <= {v:g}" for m, v in limits.items()) or "none")]
    unity = sorted({r for p in report.ranked for o in p.loops for r in o.unity})
    if unity:
        caption.append("unity gain (no dynamics): " + ", ".join(unity))
    caption.append(
        f"{report.distinct_loops} distinct loop(s), {report.loops_simulated} simulated "
        "(each distinct loop once)"
    )
    table.caption = "; ".join(caption)
    table.caption_justify = "left"
    return table


def _document(result: Sweep) -> dict[str, Any]:
    schemas = []
    for report in result.reports:
        sim = report.schema.simulation
        assert sim is not None
        front = set(report.pareto)
        configs = []
        shown = report.pareto if report.pareto_metrics else range(len(report.ranked))
        for i in shown:
            p = report.ranked[i]
            configs.append(
                {
                    "rank": i + 1,
                    "assignment": p.configuration.mapping,
                    "meets_requirements": p.meets_requirements,
                    "stable": p.stable,
                    "pareto": i in front if report.pareto_metrics else None,
                    "figures": {m: _number(v) for m, v in sorted(p.figures.items())},
                    "loops": [
                        {
                            "name": o.loop,
                            "stable": o.result.stable,
                            "settling_time": _number(o.result.settling_time),
                            "steady_state_error": _number(o.result.steady_state_error),
                            "overshoot": _number(o.result.overshoot),
                            "final_value": _number(o.result.final_value),
                            "meets_requirements": o.meets_requirements,
                            "unity_gain_roles": list(o.unity),
                        }
                        for o in p.loops
                    ],
                }
            )
        schemas.append(
            {
                "name": report.schema.name,
                "title": report.schema.display_name,
                "reference": sim.reference,
                "duration": sim.duration,
                "requirements": sim.requirements.limits(),
                "configurations_simulated": len(report.ranked),
                "distinct_loops": report.distinct_loops,
                "loops_simulated": report.loops_simulated,
                "pareto_metrics": list(report.pareto_metrics),
                "configurations": configs,
            }
        )
    return {
        "failed": list(result.failed),
        "schemas": schemas,
        "skipped": [{"name": n, "reason": why} for n, why in result.skipped],
    }
