"""What a watch's face shows: its state as one JSON document, and its log lines' levels.

Pure tables, so that the ROS 2 face (``ros2/scripts/face_node.py``) only turns them into
messages: ``diagnostics`` gives the rows of ``/diagnostics`` (one per role, one for the
configuration's conformance; levels as ``diagnostic_msgs/msg/DiagnosticStatus``'s OK, WARN,
ERROR: 0, 1, 2, which the node sends as its byte constants), ``level_of`` the ``/rosout``
level of each event kind. Names are grouped by prefix (``rosreconf: role/<role>``,
``rosreconf: conformance``, ``rosreconf: context/<name>``), as the diagnostic aggregator's
``AnalyzerGroup`` groups them.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.context import show
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.events import Event
from rosreconf.ros.livecontext import VariableState

OK, WARN, ERROR = 0, 1, 2
"""``DiagnosticStatus`` levels."""
HARDWARE_ID = "rosreconf"
PREFIX = "rosreconf: "

ERROR_KINDS = frozenset(
    {"failed", "no-configuration", "not-conformant", "launch-error", "launch-exited",
     "standby-hung", "master-lost", "context-error"}
)  # fmt: skip
WARN_KINDS = frozenset(
    {"replanned", "passed-over", "task-refused", "restart", "hold", "stop-by-hand",
     "left-running", "missing", "master-restarted", "graph-unsettled", "purged", "context",
     "context-lost", "prefer"}
)  # fmt: skip
DEBUG_KINDS = frozenset({"helper"})


@dataclass(frozen=True)
class Verdict:
    """Whether one task can be switched to now, and why not (the face's table)."""

    task: str
    title: str
    ok: bool
    reason: str
    changes: int | None = None


def level_of(kind: str) -> str:
    """Return the log level an event of ``kind`` has on ``/rosout`` (failures ERROR, replans
    WARN, the rest INFO; the helpers' own chatter DEBUG)."""
    if kind in ERROR_KINDS:
        return "error"
    if kind in WARN_KINDS:
        return "warn"
    return "debug" if kind in DEBUG_KINDS else "info"


@dataclass
class Health:
    """The configuration's conformance as the last events said it (level, words, findings)."""

    level: int = WARN
    message: str = "not checked yet"
    findings: list[str] = field(default_factory=list)
    no_standby: dict[str, str] = field(default_factory=dict)
    """Standbys missing (``--standby``): component -> why, until it is configured."""

    def saw(self, event: Event) -> None:
        """Follow the events that change it."""
        comp = str(event.data.get("component", ""))
        if event.kind in ("no-standby", "standby-hung"):
            self.no_standby[comp] = event.message
        elif event.data.get("transition") == "configure" and event.data.get("ok"):
            self.no_standby.pop(comp, None)
        if event.kind == "conformant":
            self.level, self.message, self.findings = OK, event.message, []
        elif event.kind == "not-conformant":
            self.level, self.message = ERROR, event.message
            self.findings = [str(f) for f in event.data.get("findings", [])]
        elif event.kind in ("failed", "replanned", "task"):
            self.level, self.message = WARN, f"changing: {event.message}"


def role_rows(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Configuration,
    failed: Collection[str],
    running: Collection[str],
    no_standby: Mapping[str, str] | None = None,
    ruled: Mapping[str, str] | None = None,
) -> list[dict[str, Any]]:
    """Return one row per role: OK running; WARN not running yet (degraded), or a standby of
    its missing (``no_standby``: component -> why); ERROR failed or ruled out by context
    (``ruled``: component -> why), or empty when required. Values: the component and its
    node."""
    now = current.mapping
    missing = no_standby or {}
    ruled = ruled or {}
    rows = []
    for role in schema.graph.roles:
        comp = now.get(role.name, "")
        known = library.by_name.get(comp)
        node = node_live_name(known) if known is not None else ""
        if not comp:
            level, text = (OK, "empty (optional)") if role.optional else (ERROR, "empty: required")
        elif comp in ruled:
            level, text = ERROR, f"ruled out: {ruled[comp]}"
        elif comp in failed:
            level, text = ERROR, f"{comp} failed"
        elif comp not in running:
            level, text = WARN, f"{comp} not running yet (degraded)"
        else:
            level, text = OK, f"{comp} running"
        gone = [c for c in missing if c in library.by_name and c != comp
                and library.by_name[c].abstraction == role.abstraction]  # fmt: skip
        if level == OK and gone:
            level, text = WARN, f"{text}; standby missing: {missing[gone[0]]}"
        rows.append(
            {
                "name": f"{PREFIX}role/{role.name}",
                "level": level,
                "message": text,
                "hardware_id": HARDWARE_ID,
                "values": [["component", comp], ["node", node]],
            }
        )
    return rows


def conformance_row(schema: InteroperabilitySchema, health: Health) -> dict[str, Any]:
    """Return the row of the configuration's conformance, with its last findings."""
    values = [["task", schema.name]] + [
        [f"finding {i}", f] for i, f in enumerate(health.findings, 1)
    ]
    return {
        "name": f"{PREFIX}conformance",
        "level": health.level,
        "message": health.message,
        "hardware_id": HARDWARE_ID,
        "values": values,
    }


def context_rows(states: Sequence[VariableState]) -> list[dict[str, Any]]:
    """Return one row per context variable: OK heard; WARN never heard or silent. Its
    message says the value and the components it rules out now, each with why."""
    rows = []
    for v in states:
        value = "not heard yet" if v.value is None else show(v.value)
        level = WARN if v.lost or v.value is None else OK
        text = f"{v.name} = {value}" + (" (silent)" if v.lost else "")
        if v.rules_out:
            text += "; rules out " + ", ".join(c for c, _ in v.rules_out)
        values = [["topic", v.topic], ["value", value]]
        values += [[f"rules out {c}", why] for c, why in v.rules_out]
        rows.append({"name": f"{PREFIX}context/{v.name}", "level": level, "message": text,
                     "hardware_id": HARDWARE_ID, "values": values})  # fmt: skip
    return rows


def snapshot(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Configuration,
    failed: Collection[str],
    running: Collection[str],
    health: Health,
    verdicts: Sequence[Verdict],
    switching: str | None,
    context: Sequence[VariableState] = (),
) -> dict[str, Any]:
    """Return the state a face shows, as one JSON document (the face's ``state`` line)."""
    ruled = {c: why for v in context for c, why in v.rules_out}
    return {
        "task": schema.name,
        "configuration": {r: c or None for r, c in current.assignment},
        "failed": sorted(failed),
        "switching": switching,
        "tasks": [
            {"task": v.task, "title": v.title, "ok": v.ok, "reason": v.reason, "changes": v.changes}
            for v in verdicts
        ],
        "diagnostics": [
            *role_rows(library, schema, current, failed, running, health.no_standby, ruled),
            conformance_row(schema, health),
            *context_rows(context),
        ],
    }
