"""What ``rosreconf watch`` decides and observes, as events for people and for programs."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any


@dataclass(frozen=True)
class Event:
    """One decision or observation, for people (``message``) and programs (``data``).

    Attributes:
        kind: ``started``, ``running`` (once: every component seen alive), ``stopped``,
            ``failed``, ``purged``, ``replanned``, ``why``, ``no-configuration``, ``stop``,
            ``launch``, ``would-launch`` (no launcher here), ``lifecycle`` (ROS 2 managed
            nodes: one per transition, with its result), ``stop-by-hand`` (ROS 2),
            ``left-running``, ``launch-error``, ``launch-exited``, ``conformant``,
            ``not-conformant``, ``missing``, ``master-lost``, ``master-back``,
            ``master-restarted``, ``graph-unsettled``, ``graph-settled`` (ROS 2), ``kept``,
            ``standby-hung`` (ROS 2), ``restart``, ``hold``, ``release``, ``helper``,
            ``watched``, ``exited``, ``passed-over``, ``task`` (a switch of task decided: its
            changes), ``task-refused`` (a switch asked for and refused, with the reason),
            ``prefer`` (a move to a better configuration), ``context`` (a component ruled out
            by context, or usable again), ``context-lost``, ``context-back``,
            ``context-error`` (ROS 2: a context topic silent, heard again, unreadable).
        message: what happened and why, in plain words.
        data: details for the JSON log (component names, configurations, seconds).
        time: when (UTC).
    """

    kind: str
    message: str
    data: Mapping[str, Any] = field(default_factory=dict)
    time: datetime = field(default_factory=lambda: datetime.now(UTC))
