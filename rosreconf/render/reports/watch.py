"""Report ``rosreconf watch``'s events: one timestamped line for people, one JSON line for logs."""

from __future__ import annotations

from rosreconf import jsonout
from rosreconf.ros.events import Event


def event_line(event: Event) -> str:
    """Return the event as ``<ISO time> watch: <message>`` (no newline)."""
    return f"{event.time.isoformat(timespec='milliseconds')} watch: {event.message}"


def event_json(event: Event) -> str:
    """Return the event as one JSON line (``--json-log``), newline included."""
    doc = {"time": event.time.isoformat(), "event": event.kind, "message": event.message}
    return jsonout.dumps({**doc, **event.data}) + "\n"
