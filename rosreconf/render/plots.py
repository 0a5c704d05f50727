"""Draw simulated step responses and the Pareto front with matplotlib, as SVG or PNG.

A person choosing between configurations wants to *see* the difference the numbers describe:
one panel per control loop with one step response per configuration and the schema's
requirements drawn in (the settling-time limit, the steady-state error band, the overshoot
ceiling), and, when a Pareto front was asked for, one panel with every configuration's two
first metrics and the front highlighted.

matplotlib is an optional extra (``rosreconf[plot]``); it is imported only here, and only
its object-oriented API is used (no pyplot state, no display needed).
"""

from __future__ import annotations

import io
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rosreconf.analysis.performance import step_curve
from rosreconf.analysis.simulate import Sweep, loop_spec
from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.model import ComponentLibrary
from rosreconf.outfiles import write_atomic

FORMATS = {".svg": "svg", ".png": "png"}
"""Picture formats by file suffix."""

MAX_CURVES = 12
"""Curves drawn per loop panel: the best-ranked configurations; the legend says how many."""


@dataclass(frozen=True)
class Curve:
    """The step response of one assignment of a loop's roles (shared by configurations).

    Attributes:
        label: the configurations (by rank) and the loop's components, as the legend shows.
        time: the instants, seconds.
        output: the plant output at those instants (NaN for an ill-posed loop).
        stable: whether the loop is stable (unstable curves are drawn dashed).
    """

    label: str
    time: Sequence[float]
    output: Sequence[float]
    stable: bool


@dataclass(frozen=True)
class LoopPanel:
    """One loop of one schema: its curves and the requirements to draw.

    Attributes:
        title: the panel's title (schema and loop).
        reference: the reference step size.
        limits: metric -> maximum (the schema's requirements that are set).
        curves: one per distinct assignment of the loop's roles, best-ranked first.
        total: how many distinct assignments there were (the title says when not all are
            drawn).
    """

    title: str
    reference: float
    limits: Mapping[str, float]
    curves: Sequence[Curve]
    total: int


@dataclass(frozen=True)
class FrontPanel:
    """Every configuration on two metrics, the Pareto front highlighted.

    Attributes:
        title: the panel's title.
        metrics: the two metrics on the axes (x, y).
        points: per configuration, its (x, y) figures (non-finite ones are left out).
        front: indices into ``points`` of the Pareto front.
        labels: per configuration, a short label (front points are annotated).
    """

    title: str
    metrics: tuple[str, str]
    points: Sequence[tuple[float, float]]
    front: Sequence[int]
    labels: Sequence[str]


def format_of(path: Path) -> str:
    """Return the picture format for ``path`` from its suffix.

    Raises:
        UsageError: the suffix is neither .svg nor .png.
    """
    fmt = FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise UsageError(f"{path}: cannot tell the picture format (name the file .svg or .png)")
    return fmt


def draw(path: Path, loops: Sequence[LoopPanel], fronts: Sequence[FrontPanel] = ()) -> None:
    """Draw ``loops`` and ``fronts`` into one picture at ``path`` (atomically).

    Raises:
        UsageError: unknown suffix, or the file cannot be written.
        ExternalToolError: matplotlib is not installed.
    """
    fmt = format_of(path)
    try:
        import matplotlib

        matplotlib.use("Agg")
        from matplotlib.figure import Figure
    except ImportError:
        raise ExternalToolError(
            "matplotlib is not installed (pip install 'rosreconf[plot]' to draw --plot)"
        ) from None
    panels = len(loops) + len(fronts)
    fig = Figure(figsize=(9, 4.2 * max(panels, 1)), layout="constrained")
    axes = fig.subplots(max(panels, 1), 1, squeeze=False)[:, 0]
    for ax, loop in zip(axes, loops, strict=False):
        _draw_loop(ax, loop)
    for ax, front in zip(axes[len(loops) :], fronts, strict=False):
        _draw_front(ax, front)
    buffer = io.BytesIO()
    metadata: dict[str, Any] = {"Date": None} if fmt == "svg" else {}
    with matplotlib.rc_context({"svg.hashsalt": "rosreconf", "svg.fonttype": "none"}):
        fig.savefig(buffer, format=fmt, dpi=110, metadata=metadata)
    write_atomic(path, buffer.getvalue())


def _draw_loop(ax: Any, panel: LoopPanel) -> None:
    ref = panel.reference
    shown = panel.curves[:MAX_CURVES]
    for curve in shown:
        style = "-" if curve.stable else "--"
        label = curve.label if curve.stable else f"{curve.label} (unstable)"
        ax.plot(curve.time, curve.output, style, linewidth=1.4, label=label)
    end = max((c.time[-1] for c in shown if len(c.time)), default=1.0)
    settle = panel.limits.get("settling_time")
    error = panel.limits.get("steady_state_error")
    overshoot = panel.limits.get("overshoot")
    if error is not None:
        start = settle if settle is not None else 0.0
        ax.fill_between(
            [start, end],
            ref * (1 - error),
            ref * (1 + error),
            color="tab:green",
            alpha=0.15,
            label=f"steady-state error <= {error:g}",
        )
    if settle is not None:
        ax.axvline(settle, color="tab:red", linestyle=":", label=f"settling time <= {settle:g} s")
    if overshoot is not None:
        ax.axhline(
            ref * (1 + overshoot / 100),
            color="tab:orange",
            linestyle=":",
            label=f"overshoot <= {overshoot:g} %",
        )
    ax.axhline(ref, color="grey", linewidth=0.8)
    # Keep diverging curves from flattening the picture: clip the view near the reference.
    finite = [
        v for c in shown if c.stable for v in c.output if isinstance(v, float) and math.isfinite(v)
    ]
    top = max([ref * 1.6, *finite]) if finite else ref * 2
    ax.set_ylim(min(-0.1 * abs(ref), *finite) if finite else -abs(ref), min(top, 3 * abs(ref)))
    ax.set_xlim(0, end)
    note = "" if len(shown) == panel.total else f" (best {len(shown)} of {panel.total})"
    ax.set_title(panel.title + note)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("plant output")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small", loc="best")


def _draw_front(ax: Any, panel: FrontPanel) -> None:
    keep = [i for i, (x, y) in enumerate(panel.points) if math.isfinite(x) and math.isfinite(y)]
    ax.scatter(
        [panel.points[i][0] for i in keep],
        [panel.points[i][1] for i in keep],
        color="lightgrey",
        edgecolor="grey",
        label="configuration",
    )
    front = [i for i in panel.front if i in set(keep)]
    front.sort(key=lambda i: panel.points[i])
    ax.plot(
        [panel.points[i][0] for i in front],
        [panel.points[i][1] for i in front],
        "o-",
        color="tab:blue",
        label="Pareto front",
    )
    for i in front:
        ax.annotate(
            panel.labels[i],
            panel.points[i],
            fontsize="x-small",
            xytext=(4, 4),
            textcoords="offset points",
        )
    ax.set_xlabel(panel.metrics[0])
    ax.set_ylabel(panel.metrics[1])
    ax.set_title(panel.title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")


def draw_sweep(path: Path, library: ComponentLibrary, result: Sweep) -> None:
    """Draw every simulated schema's loops (best-ranked curves) and Pareto fronts to ``path``.

    Raises:
        UsageError: unknown suffix, or the file cannot be written.
        ExternalToolError: matplotlib is not installed.
    """
    format_of(path)  # refuse a bad name before simulating curves
    loops: list[LoopPanel] = []
    fronts: list[FrontPanel] = []
    for report in result.reports:
        sim = report.schema.simulation
        assert sim is not None
        chosen = report.pareto if report.pareto_metrics else range(len(report.ranked))
        for loop in sim.loops:
            # Configurations that agree on the loop's roles share one curve.
            groups: dict[tuple[str, ...], list[int]] = {}
            for i in chosen:
                mapping = report.ranked[i].configuration.mapping
                groups.setdefault(tuple(mapping[r] for r in loop.roles), []).append(i)
            curves = []
            for components, ranks in list(groups.items())[:MAX_CURVES]:
                p = report.ranked[ranks[0]]
                spec, _ = loop_spec(library, sim, loop, p.configuration.mapping)
                t, y = step_curve(spec)
                outcome = next(o for o in p.loops if o.loop == loop.name)
                label = f"{_ranks(ranks)}: {', '.join(components)}"
                curves.append(Curve(label, list(t), list(y), outcome.result.stable))
            loops.append(
                LoopPanel(
                    f"{report.schema.display_name}: loop {loop.name} ({', '.join(loop.roles)})",
                    sim.reference,
                    sim.requirements.limits(),
                    curves,
                    len(groups),
                )
            )
        if len(report.pareto_metrics) >= 2:
            mx, my = report.pareto_metrics[:2]
            fronts.append(
                FrontPanel(
                    f"{report.schema.display_name}: Pareto front over "
                    + ", ".join(report.pareto_metrics),
                    (mx, my),
                    [(p.figures.get(mx, 0.0), p.figures.get(my, 0.0)) for p in report.ranked],
                    report.pareto,
                    [f"#{i + 1}" for i in range(len(report.ranked))],
                )
            )
    draw(path, loops, fronts)


def _ranks(ranks: list[int]) -> str:
    """Say which configurations (by rank) a curve stands for: "#1", "#1, #3", "#1 and 5 more"."""
    shown = [f"#{i + 1}" for i in ranks]
    if len(shown) <= 3:
        return ", ".join(shown)
    return f"{shown[0]} and {len(shown) - 1} more"
