"""The tables ``run.py`` prints, and the Markdown of results.json that docs/PERFORMANCE.md shows.

``markdown`` reads results.json as written (``run.py --markdown``); the rich tables show the
rows of the run just made.
"""

from __future__ import annotations

from typing import Any

from largest import table as largest_table
from loading import markdown as loading_markdown
from recovery import table as recovery_table
from rich.table import Table
from rows import OK, GridRow, Measured, Pair


def markdown(doc: dict[str, Any]) -> str:
    """Render results.json's whole-process, growth and watch parts as Markdown tables."""
    out = [
        "| what (whole process) | ours, CPU s | reference, CPU s | ratio | goal | met | reference"
        " |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in [*doc["whole_process"], doc["import_floor"]]:
        if r["status"] != "ok":
            out.append(f"| {r['what']} | {r['status']} | | | | | |")
            continue
        goals = []
        if r.get("goal_ratio") is not None:
            goals.append(f"<= {r['goal_ratio']}x")
        if r.get("goal_seconds") is not None:
            goals.append(f"< {r['goal_seconds']} s")
        out.append(
            f"| `{r['what']}` | {r['cpu_seconds']:.2f} | {r['reference_cpu_seconds']:.2f} "
            f"| {r['ratio']:.2f}x | {', '.join(goals) or '-'} "
            f"| {('yes' if r['met'] else 'no') if goals else '-'} | {r['reference']} |"
        )
    grown = doc["growth"]
    out += ["", "| roles (x 10), in-process | count s | first s | optimal s | peak RSS MiB |"]
    out.append("| --- | --- | --- | --- | --- |")
    for r in grown["rows"]:
        if r["status"] != "ok":
            out.append(f"| {r['roles']} | {r['status']} | | | |")
            continue
        out.append(
            f"| {r['roles']:,} | {r['count']:.3f} | {r['first']:.3f} | {r['optimal']:.3f} "
            f"| {r['rss_kib'] / 1024:.0f} |"
        )
    fits = grown["exponent"]
    cells = [
        f"{fits[k]:.2f}" if fits[k] is not None else "n/a" for k in ("count", "first", "optimal")
    ]
    out.append(f"| fitted exponent | {' | '.join(cells)} | |")
    if "loading" in doc:
        out += ["", loading_markdown(doc["loading"])]
    if "largest" in doc:
        out += ["", largest_table(doc["largest"])]
    w = doc["watch"]
    out += [
        "",
        f"watch (in-process): replan {w['replan_seconds'] * 1000:.0f} ms, Fast Downward's own "
        f"time ({w['search']}) {w['fast_downward_seconds']:.2f} s; goal met: {w['met']}",
    ]
    if "recovery" in doc:
        out += ["", "recovery (whole process, real nodes, median seconds):", ""]
        out.append(recovery_table(doc["recovery"]))
    return "\n".join(out)


def whole_table(rows: list[Pair]) -> Table:
    """Show the whole-process pairs: CPU seconds, the reference's, ratio, goal, met."""
    table = Table(title="whole process, interleaved pairs (median CPU seconds)")
    for col in ["what", "ours", "reference", "ratio", "goal", "met", "reference is"]:
        table.add_column(col)
    for r in rows:
        if r.status != OK:
            table.add_row(r.what, r.status, "", "", "", "", "")
            continue
        goals = []
        if r.goal_ratio is not None:
            goals.append(f"<= {r.goal_ratio}x")
        if r.goal_seconds is not None:
            goals.append(f"< {r.goal_seconds} s")
        table.add_row(
            r.what,
            f"{r.cpu_seconds:.2f}",
            f"{r.reference_cpu_seconds:.2f}",
            f"{r.ratio:.2f}x" if r.ratio is not None else "n/a",
            ", ".join(goals),
            "yes" if r.met else "no",
            r.reference,
        )
    return table


def growth_table(grown: dict[str, Any]) -> Table:
    """Show in-process seconds per roles (x 10 candidates) and the fitted exponents."""
    table = Table(title="growth, in-process (seconds; peak RSS MiB of the process)")
    for col in ["roles", "count", "first", "optimal", "peak RSS"]:
        table.add_column(col)
    for r in grown["rows"]:
        if r["status"] != "ok":
            table.add_row(str(r["roles"]), r["status"], "", "", "")
            continue
        cells = [f"{r[k]:.2f}" for k in ("count", "first", "optimal")]
        table.add_row(str(r["roles"]), *cells, f"{r['rss_kib'] / 1024:.0f}")
    fits = grown["exponent"]
    table.add_row(
        "exponent",
        *[f"{fits[k]:.2f}" if fits[k] else "n/a" for k in ("count", "first", "optimal")],
        "",
    )
    return table


def fd_cell(m: Measured, first: Measured) -> str:
    """Show a Fast Downward cell: seconds, whether the plan is valid, ratio to our first."""
    if not m.ok:
        return m.status
    seconds = m.seconds or 0.0
    if m.planned != "solved":
        return f"{m.planned} {seconds:.1f} s"
    ratio = f", {seconds / first.seconds:.0f}x" if first.ok and first.seconds else ""
    return f"{seconds:.2f} ({'valid' if m.valid else 'INVALID'}{ratio})"


def grid_table(rows: list[GridRow], kinds: list[str]) -> Table:
    """Show the in-process grid: median seconds / peak RSS MiB per kind, Fast Downward's two."""
    table = Table(title="rosreconf benchmark, in-process (median seconds / peak RSS MiB)")
    for col in ["R x K", *kinds, "overhead", "FD first", "FD anytime"]:
        table.add_column(col)
    for row in rows:
        cells = [f"{row.roles}x{row.candidates}"]
        for kind in kinds:
            m = row.kinds[kind]
            seconds, rss = m.seconds or 0.0, (m.rss_kib or 0) / 1024
            cells.append(f"{seconds:.2f} / {rss:.0f}" if m.ok else m.status)
        f, c = row.kinds["first"], row.kinds["clingo"]
        ok = f.ok and c.ok and f.seconds is not None and bool(c.seconds)
        cells.append(f"{(f.seconds or 0.0) / (c.seconds or 1.0):.1f}x" if ok else "n/a")
        cells += [fd_cell(row.fast_downward[key], f) for key in ("first", "anytime")]
        table.add_row(*cells)
    return table
