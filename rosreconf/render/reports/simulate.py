"""Report ``rosreconf simulate``: a ranked table per schema, one JSON document for programs.

Built from the ``SchemaSimulation``s of ``rosreconf.analysis.simulate``; undefined figures
(unstable loops, responses that never settle) are ``-`` in the table and ``null`` in JSON,
never ``Infinity``.
"""

from __future__ import annotations

import json
import math

from rich.table import Table

from rosreconf.analysis.simulate import SchemaSimulation, Sweep


def _number(value: float | None) -> float | None:
    """Return ``value`` for JSON: None (null) for undefined or non-finite figures."""
    return value if value is not None and math.isfinite(value) else None


def _fmt(value: float | None, unit: str = "") -> str:
    if value is None or not math.isfinite(value):
        return "-"
    return f"{value:.3g}{unit}"


def table(report: SchemaSimulation) -> Table:
    """Return one schema's ranked configurations as a rich table (the front with --pareto)."""
    schema = report.schema
    assert schema.simulation is not None
    shown = report.pareto if report.pareto_metrics else range(len(report.ranked))
    loop_roles = [r for loop in schema.simulation.loops for r in loop.roles]
    title = f"{schema.display_name} ({schema.name}): {len(report.ranked)} configuration(s)"
    if report.pareto_metrics:
        title += f", Pareto front over {', '.join(report.pareto_metrics)}: {len(shown)}"
    out = Table(title=title, title_justify="left")
    out.add_column("#", justify="right")
    out.add_column(
        "components in the loops (" + ", ".join(dict.fromkeys(loop_roles)) + ")", overflow="fold"
    )
    out.add_column("stable")
    out.add_column("settling", justify="right")
    out.add_column("error", justify="right")
    out.add_column("overshoot", justify="right")
    out.add_column("meets")
    for i in shown:
        p = report.ranked[i]
        mapping = p.configuration.mapping
        out.add_row(
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
    out.caption = "; ".join(caption)
    out.caption_justify = "left"
    return out


def document(result: Sweep) -> str:
    """Return the JSON document (output-simulate.schema.json), newline included."""
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
    doc = {
        "failed": list(result.failed),
        "schemas": schemas,
        "skipped": [{"name": n, "reason": why} for n, why in result.skipped],
    }
    return json.dumps(doc, allow_nan=False) + "\n"
