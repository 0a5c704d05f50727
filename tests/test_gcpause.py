"""The collector's pause: what it freezes, and that a process that runs on freezes no more."""

from __future__ import annotations

import gc
import weakref

import pytest

from rosreconf import gcpause
from rosreconf.gcpause import paused_gc, stop_freezing


class _Node:
    """An object that can refer to itself (a reference cycle, as a networkx graph is)."""

    me: _Node | None = None


def _cycle_made_in_a_pause() -> weakref.ref[_Node]:
    """Make a reference cycle while the collector is paused, drop it, and return a weak
    reference to it (None once it is collected)."""
    with paused_gc():
        node = _Node()
        node.me = node
        gone = weakref.ref(node)
        del node
    return gone


@pytest.fixture
def freezing(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each test starts freezing, as every command does, and leaves that as it was."""
    monkeypatch.setattr(gcpause, "_freezing", True)


@pytest.mark.usefixtures("freezing")
def test_a_pause_freezes_what_it_built_a_cycle_included() -> None:
    """A one-shot command's pause freezes: a cycle made then outlives its use (documented)."""
    gone = _cycle_made_in_a_pause()
    gc.collect()
    assert gone() is not None


@pytest.mark.usefixtures("freezing")
def test_after_stop_freezing_a_pause_freezes_nothing_and_cycles_are_collected() -> None:
    """A watch stops freezing once set up: each repair's replan pauses the collector, and a
    freeze then kept the garbage cycles of the moment for good (benchmarks/soak.py)."""
    stop_freezing()
    gone = _cycle_made_in_a_pause()
    assert gc.isenabled()
    gc.collect()
    assert gone() is None
