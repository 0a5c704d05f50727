"""Context read live: the dwell, silence and what is said (``rosreconf.ros.livecontext``).

Times are given, not read off the clock: each case is a table of readings and looks. The
property tests hold every run of readings to the rule the docs state, computed here from
the readings alone: a usability said without a break for the dwell before a look counts at
that look, and two changes of one component are never nearer than the dwell.
"""

from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_paths
from rosreconf.model import Configuration
from rosreconf.ros.facestate import context_rows
from rosreconf.ros.livecontext import LiveContext
from rosreconf.ros.preference import Preference

EXAMPLE = Path(__file__).resolve().parent.parent / "docs" / "examples" / "suave"
LIBRARY = load_paths([EXAMPLE / "library.yaml"]).library
HIGH = 3.25  # spiral_high's least visibility


class Said:
    """Collects what ``assess`` says."""

    def __init__(self) -> None:
        self.events: list[tuple[str, str, dict[str, Any]]] = []

    def __call__(self, kind: str, message: str, **data: Any) -> None:
        self.events.append((kind, message, data))

    def kinds(self) -> list[str]:
        return [k for k, _, _ in self.events]


def _context(**kw: Any) -> LiveContext:
    return LiveContext(LIBRARY, **{"dwell": 2.0, "silence": 5.0, "begun": 0.0, **kw})


def test_a_reading_below_the_bound_rules_out_only_after_the_dwell() -> None:
    ctx, said = _context(), Said()
    ctx.heard("battery", 0.9, at=0.0)
    ctx.heard("visibility", 4.0, at=0.0)
    assert ctx.assess(said, now=0.5) == {}
    ctx.heard("visibility", 3.0, at=1.0)
    assert ctx.assess(said, now=2.9) == {}  # 1.9 s below: not yet
    assert ctx.next_due() == pytest.approx(3.0)
    ruled = ctx.assess(said, now=3.0)
    assert ruled == {"spiral_high": "spiral_high needs visibility >= 3.25; it is 3.0"}
    (kind, message, data) = said.events[-1]
    assert kind == "context" and data["component"] == "spiral_high" and not data["usable"]
    assert data["values"] == {"visibility": 3.0} and data["conditions"] == ["visibility >= 3.25"]
    assert "is ruled out: spiral_high needs visibility >= 3.25; it is 3.0" in message
    assert ctx.assess(said, now=4.0) == ruled and said.kinds().count("context") == 1  # once
    ctx.heard("visibility", 3.5, at=5.0)
    assert ctx.assess(said, now=6.9) == ruled
    assert ctx.assess(said, now=7.0) == {}
    assert said.events[-1][2]["usable"] and "usable again" in said.events[-1][1]


def test_a_dip_between_two_looks_breaks_the_run() -> None:
    """Readings are judged as they come: a look never sees the dip, but it resets the wait."""
    ctx, said = _context(), Said()
    ctx.heard("visibility", 2.0, at=0.0)
    ctx.heard("visibility", 4.0, at=1.5)  # back above, unseen by any look
    ctx.heard("visibility", 2.0, at=1.6)
    assert ctx.assess(said, now=2.5) == {}  # below since 1.6 only
    assert "spiral_high" in ctx.assess(said, now=3.6)


def test_noise_across_the_bound_faster_than_the_dwell_changes_nothing() -> None:
    ctx, said = _context(), Said()
    t = 0.0
    while t < 30.0:
        ctx.heard("visibility", HIGH - 0.5 if int(t / 0.7) % 2 else HIGH + 0.5, at=t)
        ctx.assess(said, now=t)
        t += 0.1
    assert "context" not in said.kinds()


def test_a_silent_topic_is_said_once_and_its_last_value_kept() -> None:
    ctx, said = _context(), Said()
    ctx.heard("visibility", 2.0, at=0.0)
    ctx.assess(said, now=4.9)
    assert "context-lost" not in said.kinds()
    ruled = ctx.assess(said, now=5.5)
    lost = [e for e in said.events if e[0] == "context-lost"]
    assert [e[2]["name"] for e in lost] == ["visibility", "battery"]  # battery never heard
    assert "last value 2.0 is kept" in lost[0][1] and "taken to hold" in lost[1][1]
    assert "spiral_high" in ruled and "controller_fast" not in ruled
    ctx.assess(said, now=20.0)
    assert said.kinds().count("context-lost") == 2  # said once each
    ctx.heard("visibility", 2.5, at=21.0)
    ctx.assess(said, now=21.0)
    assert said.kinds().count("context-back") == 1


def test_with_fail_a_silent_topic_rules_out_what_needs_it_after_the_dwell() -> None:
    ctx, said = _context(lost_fails=True), Said()
    ctx.heard("visibility", 4.0, at=0.0)
    ctx.heard("battery", 0.9, at=0.0)
    ctx.heard("battery", 0.9, at=4.0)
    assert ctx.assess(said, now=5.0) == {}  # visibility silent now: the dwell starts
    ruled = ctx.assess(said, now=7.0)
    assert set(ruled) == {"spiral_high", "spiral_medium", "spiral_low"}
    assert "visibility is silent" in ruled["spiral_high"]
    ctx.heard("visibility", 4.0, at=8.0)  # heard again: usable after the dwell
    assert set(ctx.assess(said, now=9.0)) == set(ruled)
    assert ctx.assess(said, now=10.0) == {}


def test_the_rows_show_values_and_what_they_rule_out() -> None:
    ctx, said = _context(), Said()
    ctx.heard("visibility", 3.0, at=0.0)
    ctx.assess(said, now=2.0)
    rows = {r["name"]: r for r in context_rows(ctx.states())}
    vis, bat = rows["rosreconf: context/visibility"], rows["rosreconf: context/battery"]
    assert vis["level"] == 0 and vis["message"] == "visibility = 3.0; rules out spiral_high"
    assert ["rules out spiral_high", "spiral_high needs visibility >= 3.25; it is 3.0"] in vis[
        "values"
    ]
    assert bat["level"] == 1 and "not heard yet" in bat["message"]


READINGS = st.lists(
    st.tuples(st.floats(0.01, 0.8), st.sampled_from([HIGH - 1.0, HIGH, HIGH + 1.0])),
    min_size=1,
    max_size=60,
)


@settings(max_examples=200, deadline=None)
@given(READINGS, st.floats(0.05, 0.5))
def test_the_dwell_rule_against_the_readings(
    readings: list[tuple[float, float]], look: float
) -> None:
    """At every look: below the bound for the whole dwell -> ruled out; at or above it for
    the whole dwell -> usable; two changes of spiral_high are a dwell apart at least."""
    dwell = 1.0
    ctx, said = _context(dwell=dwell, silence=1e9), Said()
    times, t = [], 0.0
    for gap, value in readings:
        t += gap
        times.append((t, value >= HIGH))
    end, now, i = t + 2 * dwell, 0.0, 0
    changes: list[float] = []
    while now <= end:
        while i < len(times) and times[i][0] <= now:
            ctx.heard("visibility", readings[i][1], at=times[i][0])
            i += 1
        before = len(said.events)
        ruled = "spiral_high" in ctx.assess(said, now=now)
        if any(k == "context" for k, _, _ in said.events[before:]):
            changes.append(now)
        # the readings' own verdict over [now - dwell, now]: the last reading at or before
        # its start, and every reading inside it
        inside = [ok for at, ok in times if now - dwell < at <= now]
        start = [ok for at, ok in times if at <= now - dwell]
        run = ([start[-1]] if start else [True]) + inside  # unheard: taken to hold
        if all(not ok for ok in run):
            assert ruled, (now, run)
        if all(run):
            assert not ruled, (now, run)
        now += look
    assert all(b - a >= dwell - 1e-9 for a, b in itertools.pairwise(changes))


def _config(search: str, control: str = "controller_fast") -> Configuration:
    chosen = (("search", search), ("control", control), ("thrusters", "thrusters"))
    return Configuration("pipeline_inspection", chosen)


def _brute_best(unavailable: set[str]) -> tuple[float, set[tuple[tuple[str, str], ...]]]:
    """The least cost sum over every valid configuration without ``unavailable`` (and all
    configurations reaching it), from ``enumerate --json`` alone."""
    result = CliRunner().invoke(app, ["enumerate", "-l", str(EXAMPLE / "library.yaml"), "-s",
                                      str(EXAMPLE / "schema.yaml"), "--json",
                                      "--ignore-context"])  # fmt: skip
    assert result.exit_code == 0, result.output
    cost = {c["name"]: c["metrics"]["cost"] for c in yaml.safe_load(
        (EXAMPLE / "library.yaml").read_text())["components"]}  # fmt: skip
    sums = {}
    for entry in json.loads(result.stdout)["schemas"][0]["configurations"]:
        chosen = tuple(sorted(entry["assignment"].items()))
        if not {c for _, c in chosen} & unavailable:
            sums[chosen] = sum(cost[c] for _, c in chosen)
    least = min(sums.values())
    return least, {k for k, v in sums.items() if v == least}


@pytest.mark.parametrize(
    ("running", "unavailable"),
    [
        (_config("spiral_medium"), set()),
        (_config("spiral_medium"), {"spiral_high"}),
        (_config("spiral_low", "controller_slow"), {"spiral_high"}),
        (_config("spiral_high"), set()),
        (_config("spiral_low", "controller_slow"), {"controller_fast"}),
    ],
)
def test_prefer_moves_only_to_a_strictly_better_configuration(
    running: Configuration, unavailable: set[str]
) -> None:
    said = Said()
    prefer = Preference(said, weights=(("cost", 1.0),))
    schema = load_paths([EXAMPLE / "schema.yaml", EXAMPLE / "library.yaml"]).schemas[0]
    found = prefer.better(LIBRARY, schema, running, unavailable)
    least, best = _brute_best(unavailable)
    cost = {c.name: c.metrics["cost"] for c in LIBRARY}
    now = sum(cost[c] for c in running.components)
    if now <= least:
        assert found is None and not said.events
        return
    assert found is not None
    new, changes = found
    assert tuple(sorted(new.mapping.items())) in best
    assert said.kinds() == ["prefer"] and said.events[0][2]["metric"] == least
    assert [(r, a, b) for r, a, b in changes] == [
        (r, running.mapping[r], c) for r, c in new.assignment if running.mapping[r] != c
    ]
    # once there, never back: the best is not better than itself
    assert prefer.better(LIBRARY, schema, new, unavailable) is None
