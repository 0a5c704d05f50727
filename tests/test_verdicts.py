"""The watcher's verdict on each component of the configuration, from one real comparison.

Each row puts the bundled example's nominal configuration live with NSM3 in one state, compares
it (``conformance.compare``, the watcher's own reading), and asks ``verdicts.judge`` what NSM3
is: failed (and why), missing, or seen. The reference is the table in ``rosreconf.ros.verdicts``
read as a person would: a registered node that does not answer is failed; a node gone that this
watcher saw is failed; one never seen may still be starting; one judged elsewhere is passed over.
"""

from __future__ import annotations

from datetime import UTC, datetime

import pytest

from rosreconf.formats.loader import load_bundled
from rosreconf.model import Configuration
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.conformance import compare
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.ros1.standins import standin_spec
from rosreconf.ros.verdicts import judge

BUNDLE = load_bundled()
LIB = BUNDLE.library
SCHEMA = next(s for s in BUNDLE.schemas if s.name == "object_repositioning")
NOMINAL = Configuration.of(SCHEMA.name, SCHEMA.nominal, SCHEMA.graph.roles)


def _graph(nsm3: str) -> LiveGraph:
    """Return the nominal configuration live, NSM3 ``running``, ``dead`` or ``absent``."""
    nodes = []
    for c in NOMINAL.components:
        serves = tuple(s["service"] for s in standin_spec(LIB[c])["serve"])
        node = LiveNode(node_live_name(LIB[c]), "http://127.0.0.1:1/", 1, (), (), serves)
        if c == "NSM3" and nsm3 == "absent":
            continue
        if c == "NSM3" and nsm3 == "dead":  # registered, its API does not answer
            node = LiveNode(node.name, node.uri, None, (), (), serves)
        nodes.append(node)
    return LiveGraph("http://127.0.0.1:11311/", datetime(2026, 1, 1, tzinfo=UTC), tuple(nodes), {})


@pytest.mark.parametrize(
    ("nsm3", "seen_before", "elsewhere", "verdict"),
    [
        ("running", False, False, "seen"),
        ("dead", False, False, "failed: registered but not answering"),
        ("dead", True, False, "failed: registered but not answering"),
        ("absent", True, False, "failed: gone"),
        ("absent", False, False, "missing"),  # never seen: it may still be starting
        ("absent", True, True, "passed over"),  # a person restarts it, or a clash judges it
        ("dead", False, True, "passed over"),
    ],
)
def test_each_component_is_failed_missing_seen_or_passed_over_as_the_table_says(
    nsm3: str, seen_before: bool, elsewhere: bool, verdict: str
) -> None:
    check = compare(NOMINAL, LIB, SCHEMA, _graph(nsm3))
    out = judge(check, NOMINAL.components, {"NSM3"} if seen_before else set(),
                {"NSM3"} if elsewhere else set())  # fmt: skip
    said = (
        f"failed: {out.failed['NSM3']}" if "NSM3" in out.failed
        else "missing" if "NSM3" in out.missing
        else "seen" if "NSM3" in out.seen
        else "passed over"
    )  # fmt: skip
    assert said == verdict
    others = set(NOMINAL.components) - {"NSM3"}
    assert others <= out.seen  # the rest run as they should, whatever NSM3 is
