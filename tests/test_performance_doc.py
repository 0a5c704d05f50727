"""docs/PERFORMANCE.md shows what benchmarks/results.json holds, never a figure typed by hand.

Each measured section of the page sits between ``<!-- results: NAME -->`` markers and is
written by ``python benchmarks/docsections.py`` from the committed results. A page edited by
hand, or results measured anew without writing the page, fails here.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "benchmarks"))

import docsections  # noqa: E402

PAGE = REPO / "docs" / "PERFORMANCE.md"
RESULTS = json.loads((REPO / "benchmarks" / "results.json").read_text(encoding="utf-8"))


def test_every_measured_section_is_what_results_json_holds() -> None:
    stale = docsections.differing(PAGE.read_text(encoding="utf-8"), RESULTS)
    assert not stale, (
        f"docs/PERFORMANCE.md differs from benchmarks/results.json in {sorted(stale)}: run "
        "`python benchmarks/docsections.py` (never edit a marked section by hand)"
    )


def test_every_section_results_json_renders_is_on_the_page() -> None:
    marked = {m.group("name") for m in docsections.BLOCK.finditer(PAGE.read_text("utf-8"))}
    assert marked == set(docsections.SECTIONS), marked ^ set(docsections.SECTIONS)


def test_a_figure_edited_by_hand_is_found() -> None:
    page = PAGE.read_text(encoding="utf-8")
    rendered = docsections.SECTIONS["watch"](RESULTS)
    edited = page.replace(rendered, rendered.replace("replan ", "replan 1", 1))
    assert edited != page
    assert set(docsections.differing(edited, RESULTS)) == {"watch"}
