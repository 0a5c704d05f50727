"""The watcher's "the fewest possible" is a checked claim, not a number compared with itself.

An earlier watcher passed its own change count as the optimum to ``explain_replan``, which
then said "N part(s) change: the fewest possible" whatever N was. The claim must come from
the exact optimum and be true: here it is checked against the brute-force minimum over
every valid configuration, and no line may repeat the self-comparison.
"""

from __future__ import annotations

import itertools
from pathlib import Path

from rosreconf.formats.loader import load_bundled
from rosreconf.model import Configuration, VertexKind
from rosreconf.model.validity import is_valid, ros_graph
from rosreconf.ros.ros1.source import MasterSource
from rosreconf.ros.watcher import Event, Watcher

SCHEMA = "object_repositioning"


def _wired_to(watcher: Watcher, config: Configuration) -> dict[str, set[tuple[str, str]]]:
    """Return per component the (label, name its provider really uses) it consumes.

    Read off the ROS-graph (Def. 1) and the library's remappings, as a launch file wires a
    consumer: what a process is started with, which ROS 2 fixes until it restarts.
    """
    g = ros_graph(config, watcher.library, watcher.schema)
    out: dict[str, set[tuple[str, str]]] = {c: set() for c in config.components}
    for (kind, name), data in g.nodes(data=True):
        if kind is VertexKind.NODE:
            continue
        label = str(data["label"])
        for (_, provider), _ in g.in_edges((kind, name)):
            launch = watcher.library[provider].launch
            real = launch.remappings.get(label, label) if launch else label
            for _, (_, consumer) in g.out_edges((kind, name)):
                out[consumer].add((label, real))
    return out


def _fewest_by_brute_force(watcher: Watcher, old: dict[str, str], failed: frozenset[str]) -> int:
    """Return the fewest changes of any valid configuration from ``old``, by trying them all.

    A change is a role that changes component, or a kept component whose wiring (what its
    providers are called) changes: ROS names are fixed when a node starts, so it restarts.
    """
    roles = watcher.schema.graph.roles
    doms = [[c.name for c in watcher.library.candidates(r.abstraction)] for r in roles]
    before = _wired_to(watcher, Configuration.of(watcher.schema.name, old, roles))
    best: int | None = None
    for combo in itertools.product(*doms):
        mapping = dict(zip([r.name for r in roles], combo, strict=True))
        config = Configuration.of(watcher.schema.name, mapping, roles)
        if is_valid(config, watcher.library, watcher.schema, failed):
            after = _wired_to(watcher, config)
            n = sum(old[r] != c or before[c] != after[c] for r, c in mapping.items())
            best = n if best is None else min(best, n)
    assert best is not None
    return best


def test_the_fewest_possible_is_the_brute_force_minimum_and_said_once(tmp_path: Path) -> None:
    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == SCHEMA)
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    events: list[Event] = []
    # No step() runs, so the master at this address is never called: _replan is pure.
    watcher = Watcher(
        MasterSource("http://127.0.0.1:9"), bundle.library, schema, nominal, tmp_path, {},
        events.append,
    )  # fmt: skip
    tried = 0
    for comp in sorted(set(nominal.components)):
        events.clear()
        watcher.current = nominal
        watcher.failed = {comp}
        watcher._hopeless = None
        watcher._replan()
        found = [e for e in events if e.kind == "replanned"]
        if not found:  # the schema cannot do without it
            continue
        tried += 1
        (replanned,) = found
        n = len(replanned.data["changes"])  # type: ignore[arg-type]
        assert n == _fewest_by_brute_force(watcher, dict(nominal.mapping), frozenset({comp})), comp
        assert f"{n} change(s), the fewest possible (exact optimum)" in replanned.message
        claims = [e.message for e in events if "fewest possible" in e.message]
        assert claims == [replanned.message], claims  # no "N part(s) change: the fewest ..."
    assert tried >= 2
