"""Write docs/PERFORMANCE.md's measured figures from benchmarks/results.json, never by hand.

Each measured section of the page sits between two markers::

    <!-- results: NAME -->
    ...rendered from results.json...
    <!-- /results: NAME -->

``python benchmarks/docsections.py`` renders every marked section from the committed
results.json and writes the page; ``--check`` only says which differ (exit 1).
tests/test_performance_doc.py runs the same comparison, so a figure edited by hand, or a
results.json measured anew without the page, fails the suite. What the page says outside the
markers is prose; a figure measured by hand says so there, with its date.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))  # run as a script or imported by the tests: its siblings

from context_change import context_table  # noqa: E402
from largest import table as largest_table  # noqa: E402
from loading import markdown as loading_markdown  # noqa: E402
from recovery import table as recovery_table  # noqa: E402
from switching import table as switching_table  # noqa: E402

RESULTS = HERE / "results.json"
PAGE = HERE.parent / "docs" / "PERFORMANCE.md"
BLOCK = re.compile(
    r"(<!-- results: (?P<name>[a-z_]+) -->\n)(?P<body>.*?)(\n<!-- /results: (?P=name) -->)",
    re.S,
)
GRID_KINDS = ("count", "first", "optimal", "clingo_optimal", "clingo", "whatif")


def _pairs(rows: list[dict[str, Any]]) -> str:
    """Interleaved whole-process pairs: ours, the reference, ratio, goal, met."""
    out = [
        "| what (whole process) | ours, CPU s | reference, CPU s | ratio | goal | met "
        "| reference |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
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
    return "\n".join(out)


def whole_process(doc: dict[str, Any]) -> str:
    """The whole-process rows of the last full run, and the import floor."""
    return _pairs([*doc["whole_process"], doc["import_floor"]])


def reading_rows(doc: dict[str, Any]) -> str:
    """The reading rows measured alone (``run.py --reading-rows``), with their load."""
    r = doc["reading_rows"]
    load = r["load_average"]
    start, end = load["start"][0], load["end"][0]
    said = f"Load average (1 min) {start:.1f} at the start, {end:.1f} at the end."
    return _pairs(r["rows"]) + "\n\n" + said


def growth(doc: dict[str, Any]) -> str:
    """Count, first and optimum from 10 to 10,000 roles (in-process), and the fitted exponent."""
    grown = doc["growth"]
    out = ["| roles (x 10), in-process | count s | first s | optimal s | peak RSS MiB |"]
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
    return "\n".join(out)


def watch(doc: dict[str, Any]) -> str:
    """The watcher's replan against Fast Downward's own time (in-process)."""
    w = doc["watch"]
    return (
        f"In-process: replan {w['replan_seconds'] * 1000:.0f} ms, Fast Downward's own time "
        f"({w['search']}) {w['fast_downward_seconds']:.2f} s; goal met: {w['met']}."
    )


def _grid_cell(m: dict[str, Any]) -> str:
    if m["status"] != "ok":
        return str(m["status"])
    return f"{m['seconds']:.2f} / {m['rss_kib'] / 1024:.0f}"


def _fd_cell(m: dict[str, Any], first: dict[str, Any]) -> str:
    if m["status"] != "ok":
        return str(m["status"])
    if m["planned"] != "solved":
        return f"{m['planned']} {m['seconds']:.1f} s"
    ok = first["status"] == "ok" and first["seconds"]
    ratio = f", {m['seconds'] / first['seconds']:.0f}x" if ok else ""
    return f"{m['seconds']:.2f} ({'valid' if m['valid'] else 'INVALID'}{ratio})"


def grid(doc: dict[str, Any]) -> str:
    """The solvers over the R x K grid: median seconds / peak RSS MiB per column."""
    head = ["R x K", *GRID_KINDS, "overhead", "FD first", "FD anytime"]
    out = ["| " + " | ".join(head) + " |", "| --- " * len(head) + "|"]
    for row in doc["grid"]:
        cells = [f"{row['roles']}x{row['candidates']}"]
        cells += [_grid_cell(row[k]) for k in GRID_KINDS]
        f, c = row["first"], row["clingo"]
        ok = f["status"] == "ok" and c["status"] == "ok" and c["seconds"]
        cells.append(f"{f['seconds'] / c['seconds']:.1f}x" if ok else "n/a")
        cells += [_fd_cell(row["fast_downward"][k], f) for k in ("first", "anytime")]
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def streaming(doc: dict[str, Any]) -> str:
    """The listing's peak RSS at two sizes: it streams when they are alike."""
    kib = doc["streaming_rss_kib"]
    sizes = " and ".join(f"{int(n):,}" for n in kib)
    peaks = " and ".join(f"{v:,}" for v in kib.values())
    return (
        f"Streaming (in-process): listing {sizes} configurations of {doc['streaming_instance']} "
        f"peaked at {peaks} KiB."
    )


def soak(doc: dict[str, Any]) -> str:
    """Watch's resident set over many repairs (whole process)."""
    s = doc["soak"]
    if "rss_first_kib" not in s:
        return f"soak: {s.get('status')}"
    mib = [v / 1024 for v in s["samples_kib"]]
    return "\n".join(
        [
            "| repairs | RSS first `conformant` MiB | after the first repair | after the last "
            "| peak | KiB per repair (from the first / last half) | open fds (first, last) |",
            "| --- | --- | --- | --- | --- | --- | --- |",
            f"| {s['repairs']} | {mib[0]:.1f} | {mib[1]:.1f} | {mib[-1]:.1f} "
            f"| {s['rss_peak_kib'] / 1024:.1f} | {s['slope_kib_per_repair']:.1f} / "
            f"{s['slope_last_half_kib_per_repair']:.1f} | {s['fds_first']}, {s['fds_last']} |",
        ]
    )


SECTIONS: dict[str, Callable[[dict[str, Any]], str]] = {
    "whole_process": whole_process,
    "reading_rows": reading_rows,
    "growth": growth,
    "loading": lambda doc: loading_markdown(doc["loading"]),
    "largest": lambda doc: largest_table(doc["largest"]),
    "watch": watch,
    "recovery": lambda doc: recovery_table(doc["recovery"]),
    "switching": lambda doc: switching_table(doc["switching"]),
    "context": lambda doc: context_table(doc.get("context", {"status": "not measured yet"})),
    "grid": grid,
    "streaming": streaming,
    "soak": soak,
}
"""Each section a marker may name, and how results.json renders it."""


def markdown(doc: dict[str, Any]) -> str:
    """Render every section (``run.py --markdown``)."""
    return "\n\n".join(render(doc) for render in SECTIONS.values())


def differing(page: str, doc: dict[str, Any]) -> dict[str, tuple[str, str]]:
    """Return the marked sections of ``page`` that differ from results.json: name -> (was, is)."""
    found = {}
    for m in BLOCK.finditer(page):
        name, body = m.group("name"), m.group("body")
        if name not in SECTIONS:
            found[name] = (body, f"(no such section; known: {', '.join(SECTIONS)})")
            continue
        rendered = SECTIONS[name](doc)
        if body != rendered:
            found[name] = (body, rendered)
    return found


def written(page: str, doc: dict[str, Any]) -> str:
    """Return ``page`` with every marked section rendered from ``doc`` anew."""
    return BLOCK.sub(lambda m: m.group(1) + SECTIONS[m.group("name")](doc) + m.group(4), page)


def main() -> int:
    """Write the page's sections (or, with ``--check``, say which differ)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    doc = json.loads(RESULTS.read_text(encoding="utf-8"))
    page = PAGE.read_text(encoding="utf-8")
    stale = differing(page, doc)
    if args.check:
        for name in stale:
            print(f"{PAGE}: section {name!r} differs from {RESULTS}")
        return 1 if stale else 0
    PAGE.write_text(written(page, doc), encoding="utf-8")
    print(f"{PAGE}: {len(stale)} section(s) written anew from {RESULTS}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
