"""Report ``rosreconf simulate``: a ranked table per schema, one JSON document for programs.

Built from the ``SchemaSimulation``s of ``rosreconf.analysis.simulate``; undefined figures
(unstable loops, responses that never settle) are ``-`` in the table and ``null`` in JSON,
never ``Infinity``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from typing import Any

from rich.table import Table

from rosreconf.analysis.simulate import SchemaSimulation, Sweep
from rosreconf.model import shown_text


def _number(value: float | None) -> float | None:
    """Return ``value`` for JSON: None (null) for undefined or non-finite figures."""
    return value if value is not None and math.isfinite(value) else None


def _fmt(value: float | None, unit: str = "") -> str:
    if value is None or not math.isfinite(value):
        return "-"
    return f"{value:.3g}{unit}"


TOP = 20
"""Rows of the text table by default: the best-ranked configurations (``simulate --top``)."""


def table(report: SchemaSimulation, top: int = TOP) -> Table:
    """Return one schema's best ``top`` configurations as a rich table (0: all of them).

    With --pareto, the front's. A table of every configuration of a large sweep is unread
    and slow (14,096 rows took 22 CPU seconds to lay out); the caption says how many were
    left out, and ``--json`` lists them all.
    """
    schema = report.schema
    assert schema.simulation is not None
    listed = report.pareto if report.pareto_metrics else range(len(report.ranked))
    shown = listed if top == 0 else listed[:top]
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
            ", ".join(shown_text(mapping[r]) for r in dict.fromkeys(loop_roles)),
            "yes" if p.stable else "NO",
            _fmt(p.figures["settling_time"], " s"),
            _fmt(p.figures["steady_state_error"]),
            _fmt(p.figures["overshoot"], " %"),
            "yes" if p.meets_requirements else "no",
        )
    limits = schema.simulation.requirements.limits()
    caption = ["requirements: " + (", ".join(f"{m} <= {v:g}" for m, v in limits.items()) or "none")]
    unity = report.unity_roles()
    if unity:
        caption.append("unity gain (no dynamics): " + ", ".join(unity))
    caption.append(
        f"{report.distinct_loops} distinct loop(s), {report.loops_simulated} simulated "
        "(each distinct loop once)"
    )
    if report.limited:
        caption.append(
            f"only the first {len(report.configurations)} valid configurations were simulated "
            "(--limit N; there are more): the ranking is over those"
        )
    if len(shown) < len(listed):
        caption.append(
            f"the best {len(shown)} of {len(listed)} shown (--top N, --top 0 for all, --json)"
        )
    out.caption = "; ".join(caption)
    out.caption_justify = "left"
    return out


def document(result: Sweep, context: dict[str, Any] | None = None) -> Iterator[str]:
    """Yield the JSON document (output-simulate.schema.json) in pieces, newline included.

    A sweep can list tens of thousands of configurations that share a few hundred loops, so
    each loop's entry is encoded once and each configuration is one piece of encoded parts
    (every part by ``json.dumps`` with ``allow_nan=False``, so the whole is valid JSON). The
    pieces are yielded one configuration at a time for the caller to write as they come: the
    document as one string (and the list of its configurations before the join) held it
    three times over, 2.1 GB for ``--limit 10000`` of 1,000 roles, and ``--limit 30000`` ran
    out of memory in the join. ``context`` is the ``context`` member (``reports.context``).
    """
    failed = _dumps(list(result.failed))
    said = "" if context is None else f'"context": {_dumps(context)}, '
    yield f'{{{said}"failed": {failed}, "schemas": ['
    for n, report in enumerate(result.reports):
        sim = report.schema.simulation
        assert sim is not None
        head = {
            "name": report.schema.name,
            "title": report.schema.display_name,
            "reference": sim.reference,
            "duration": sim.duration,
            "requirements": sim.requirements.limits(),
            "configurations_simulated": len(report.configurations),
            "limited": report.limited,
            "distinct_loops": report.distinct_loops,
            "loops_simulated": report.loops_simulated,
            "pareto_metrics": list(report.pareto_metrics),
        }
        yield (", " if n else "") + _dumps(head)[:-1] + ', "configurations": ['
        for k, config in enumerate(_configurations(report)):
            yield ("," if k else "") + config
        yield "]}"
    skipped = _dumps([{"name": n, "reason": why} for n, why in result.skipped])
    yield f'], "skipped": {skipped}}}\n'


_ENCODER = json.JSONEncoder(allow_nan=False)


def _dumps(value: object) -> str:
    return _ENCODER.encode(value)


def _float(value: float) -> str:
    """Encode a figure as json does (``float.__repr__``); null when undefined or non-finite."""
    return repr(value) if math.isfinite(value) else "null"


def _configurations(report: SchemaSimulation) -> Iterator[str]:
    """Yield each shown configuration's JSON object, by rank."""
    loops = [
        [
            _dumps(
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
            )
            for o in outcomes
        ]
        for outcomes in report.outcomes
    ]
    stable = [[o.result.stable for o in outcomes] for outcomes in report.outcomes]
    order = sorted(range(len(report.metrics)), key=lambda k: report.metrics[k])
    names = [_dumps(report.metrics[k]) + ": " for k in order]
    pairs: dict[tuple[str, str], str] = {}  # (role, component) -> '"role": "component"'
    front = set(report.pareto)
    shown = report.pareto if report.pareto_metrics else range(len(report.order))
    figures_of = report.figures.tolist()
    rows_of = report.rows.tolist()
    for rank in shown:
        i = int(report.order[rank])
        row = rows_of[i]
        values = figures_of[i]
        figures = ", ".join(
            name + _float(values[k])
            for name, k in zip(names, order, strict=True)
            if not math.isnan(values[k])
        )
        assignment = ", ".join(
            pairs.get(pair) or pairs.setdefault(pair, f"{_dumps(pair[0])}: {_dumps(pair[1])}")
            for pair in report.configurations[i].assignment
        )
        pareto = ("true" if rank in front else "false") if report.pareto_metrics else "null"
        is_stable = all(s[j] for s, j in zip(stable, row, strict=True))
        yield (
            f'{{"rank": {rank + 1}, "assignment": {{{assignment}}}, '
            f'"meets_requirements": {"true" if report.meets[i] else "false"}, '
            f'"stable": {"true" if is_stable else "false"}, "pareto": {pareto}, '
            f'"figures": {{{figures}}}, '
            f'"loops": [{", ".join(per[j] for per, j in zip(loops, row, strict=True))}]}}'
        )
