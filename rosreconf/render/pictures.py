"""Draw the paper's graphs as Graphviz pictures, so a person can see what runs and what changed.

Three views, each a DOT text built from the networkx graphs of ``rosreconf.model`` and
``rosreconf.model.validity`` (one cluster per schema):

======= ======================================================================================
view    what it shows
======= ======================================================================================
system  a schema's system graph (Def. 5, Fig. 4/6): roles as boxes (role, abstraction),
        edges provider -> consumer
ros     a configuration's ROS-graph (Def. 1): nodes as ellipses, topics as boxes, services as
        hexagons, ROS 2 actions as octagons (in the legend only when drawn), edges
        provider -> topic/service/action -> consumer, the message type written on
        the provider's edge (and the tooltip of the consumers' edges);
        failed components red, started green, stopped grey and dashed; a legend
library every role with all its candidate components; failed ones struck out and grey
======= ======================================================================================

``write_picture`` writes any of them as DOT, SVG or PNG, atomically.
"""

from __future__ import annotations

import enum
from collections.abc import Collection, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    VertexKind,
)
from rosreconf.model.validity import ros_graph
from rosreconf.outfiles import output_target, write_atomic
from rosreconf.render.dot import DOT_TIMEOUT, DotGraph, Html, format_for, html, render

if TYPE_CHECKING:  # networkx (0.2 s to import) only when a picture is drawn, not for enumerate
    from rosreconf.model import RosGraph


class View(enum.StrEnum):
    """The pictures rosreconf draws (the CLI's ``--view`` choices)."""

    SYSTEM = "system"
    ROS = "ros"
    LIBRARY = "library"


class Status(enum.StrEnum):
    """How a ROS-graph vertex or edge fares in a reconfiguration (its colour in the picture)."""

    UNCHANGED = "unchanged"
    STARTED = "started"
    STOPPED = "stopped"
    FAILED = "failed"


SHAPES = {
    VertexKind.NODE: "ellipse",
    VertexKind.TOPIC: "box",
    VertexKind.SERVICE: "hexagon",
    VertexKind.ACTION: "octagon",
}
"""Def. 1's three vertex kinds and ROS 2's actions, in shapes that cannot be mistaken for
each other (an action's octagon has two more corners than a service's hexagon: it is a
service with feedback)."""
ALWAYS_IN_LEGEND = frozenset({VertexKind.NODE, VertexKind.TOPIC, VertexKind.SERVICE})
"""The kinds the legend always explains; an action only when the picture has one."""

STYLES: dict[Status, dict[str, str]] = {
    Status.UNCHANGED: {"style": "filled", "fillcolor": "white", "color": "black"},
    Status.STARTED: {
        "style": "filled,bold",
        "fillcolor": "#d9ead3",
        "color": "#38761d",
        "fontcolor": "#274e13",
    },
    Status.STOPPED: {
        "style": "filled,dashed",
        "fillcolor": "#f3f3f3",
        "color": "#999999",
        "fontcolor": "#777777",
    },
    Status.FAILED: {
        "style": "filled,bold",
        "fillcolor": "#f4cccc",
        "color": "#cc0000",
        "fontcolor": "#990000",
    },
}
EDGE_COLOURS = {
    Status.UNCHANGED: {"color": "#444444"},
    Status.STARTED: {"color": "#38761d", "fontcolor": "#38761d"},
    Status.STOPPED: {"color": "#999999", "fontcolor": "#999999", "style": "dashed"},
    Status.FAILED: {"color": "#cc0000", "fontcolor": "#cc0000", "style": "dashed"},
}
FONT = {"fontname": "Helvetica", "fontsize": "11"}

Vertex = tuple[VertexKind, str]


@dataclass(frozen=True)
class RosPicture:
    """One schema's configuration to draw, and the configuration it replaces, if any.

    Attributes:
        schema: the interoperability schema.
        configuration: the configuration whose ROS-graph is drawn.
        before: the configuration running before a reconfiguration; vertices only it has are
            drawn as stopped, vertices only ``configuration`` has as started.
    """

    schema: InteroperabilitySchema
    configuration: Configuration
    before: Configuration | None = None


def system_dot(schemas: Sequence[InteroperabilitySchema]) -> str:
    """Return the system graphs (Def. 5 (2)) of ``schemas`` as DOT, one cluster each."""
    g = _graph("system graph", rankdir="LR")
    for s in schemas:
        g.begin_cluster(s.name, label=s.display_name, **FONT)
        nx_graph = s.graph.to_networkx()
        for role, data in nx_graph.nodes(data=True):
            label = f"{role}\n({data['abstraction']})"
            style = "rounded"
            if data["optional"]:  # may stay empty (docs/formats.md, "Optional roles")
                label, style = label + "\noptional", "rounded,dashed"
            g.node(f"{s.name}:role:{role}", label=label, shape="box", style=style)
        for provider, consumer, data in nx_graph.edges(data=True):
            extra = {"label": ", ".join(data["interfaces"])} if data["interfaces"] else {}
            if data["optional"]:
                extra["style"] = "dashed"  # may be used, need not be (docs/formats.md)
            g.edge(f"{s.name}:role:{provider}", f"{s.name}:role:{consumer}", **extra)
        g.end_cluster()
    return g.text()


def ros_dot(
    library: ComponentLibrary, pictures: Sequence[RosPicture], failed: Collection[str] = ()
) -> str:
    """Return the ROS-graphs (Def. 1) of ``pictures`` as DOT, marking failures and changes."""
    dead = frozenset(failed)
    g = _graph("ROS-graph", rankdir="LR")
    seen: set[Status] = set()
    kinds: set[VertexKind] = set(ALWAYS_IN_LEGEND)
    for p in pictures:
        new = ros_graph(p.configuration, library, p.schema)
        old = ros_graph(p.before, library, p.schema) if p.before is not None else None
        title = f"{p.schema.display_name}: {', '.join(p.configuration.components)}"
        g.begin_cluster(p.schema.name, label=title, **FONT)
        for vertex in _vertices(new, old):
            kind, name = vertex
            data = _data(new, old, vertex)
            status = _status(vertex in new, old, vertex in old if old is not None else False)
            if kind is VertexKind.NODE and name in dead:
                status = Status.FAILED
            seen.add(status)
            kinds.add(kind)
            if kind is VertexKind.NODE:
                label = f"{name}\n({data['role']})"
                if status is Status.FAILED:
                    label += "\nfailed"
            else:
                label = str(data["label"])
            g.node(
                _vid(p.schema, vertex),
                label=label,
                shape=SHAPES[kind],
                tooltip=f"{kind.value} {name}" + (f" ({data['type']})" if "type" in data else ""),
                **STYLES[status],
            )
        for role, comp in p.configuration.assignment:
            if not comp:  # an optional role left empty: drawn as such, no node runs there
                g.node(
                    f"{p.schema.name}:empty:{role}",
                    label=f"{role}\n(empty)",
                    shape="box",
                    style="rounded,dotted",
                    color="#999999",
                    fontcolor="#999999",
                    tooltip=f"optional role {role}, left empty",
                )
        for tail, head in _edges(new, old):
            data = _data(new, old, (tail, head))
            status = _status(
                new.has_edge(tail, head), old, old is not None and old.has_edge(tail, head)
            )
            if {tail[1], head[1]} & dead and status is not Status.STARTED:
                status = Status.FAILED if status is Status.UNCHANGED else status
            # Every edge of a topic/service carries its one type (Def. 1): it is written on
            # the provider's edge and kept as the tooltip of the consumers' edges, which would
            # otherwise repeat it dozens of times and bury the picture.
            text = str(data["type"])
            where = {"label": text} if head[0] is not VertexKind.NODE else {"tooltip": text}
            g.edge(_vid(p.schema, tail), _vid(p.schema, head), **where, **EDGE_COLOURS[status])
        g.end_cluster()
    _ros_legend(g, seen, kinds)
    return g.text()


def library_dot(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    failed: Collection[str] = (),
) -> str:
    """Return every role of ``schemas`` with its candidate components as DOT.

    Failed candidates are struck out on a red ground; candidates that may not serve in the
    schema (Table 1's "In Schema") are grey and italic; the nominal choice is bold.
    """
    dead = frozenset(failed)
    g = _graph("component library", rankdir="LR")
    for s in schemas:
        g.begin_cluster(s.name, label=f"{s.display_name} ({library.name})", **FONT)
        for role in s.graph.roles:
            rows = [
                f'<TR><TD BGCOLOR="#dddddd"><B>{html(role.name)}</B><BR/>'
                f'<FONT POINT-SIZE="9">{html(role.abstraction)}</FONT></TD></TR>'
            ]
            candidates = library.candidates(role.abstraction)
            for c in candidates:
                rows.append(f"<TR><TD{_cell(c, s, dead, role.name)}</TD></TR>")
            if role.optional:
                rows.append('<TR><TD><FONT COLOR="#999999"><I>may stay empty</I></FONT></TD></TR>')
            elif not candidates:
                rows.append('<TR><TD><FONT COLOR="#cc0000">no candidate</FONT></TD></TR>')
            table = '<TABLE BORDER="0" CELLBORDER="1" CELLSPACING="0" CELLPADDING="4">'
            g.node(
                f"{s.name}:role:{role.name}",
                shape="plain",
                label=Html(table + "".join(rows) + "</TABLE>"),
            )
        for e in s.graph.edges:
            style = {"style": "dashed"} if e.optional else {}
            g.edge(f"{s.name}:role:{e.provider}", f"{s.name}:role:{e.consumer}", **style)
        g.end_cluster()
    legend = (
        '<TABLE BORDER="0" CELLBORDER="1" CELLSPACING="0" CELLPADDING="4">'
        '<TR><TD BGCOLOR="#dddddd"><B>legend</B></TD></TR>'
        "<TR><TD><B>nominal choice</B></TD></TR><TR><TD>candidate</TD></TR>"
        '<TR><TD BGCOLOR="#f4cccc"><FONT COLOR="#990000"><S>failed</S></FONT></TD></TR>'
        '<TR><TD><FONT COLOR="#999999"><I>not in this schema</I></FONT></TD></TR></TABLE>'
    )
    g.node("legend", shape="plain", label=Html(legend))
    return g.text()


def picture(
    path: Path | str, dot_text: str, fmt: str | None = None, *, timeout: float = DOT_TIMEOUT
) -> tuple[bytes, str]:
    """Return ``dot_text`` as DOT, SVG or PNG bytes (default: from the suffix) and the format.

    Raises:
        UsageError: unknown format.
        ExternalToolError: Graphviz's ``dot`` is missing, fails or times out (exit 3).
    """
    chosen = format_for(Path(path), fmt)
    data = (
        dot_text.encode("utf-8") if chosen == "dot" else render(dot_text, chosen, timeout=timeout)
    )
    return data, chosen


def write_picture(
    path: Path | str, dot_text: str, fmt: str | None = None, *, timeout: float = DOT_TIMEOUT
) -> str:
    """Write ``dot_text`` to ``path`` as DOT, SVG or PNG (default: from the suffix); return it.

    Nothing is written unless the whole picture is ready (see ``rosreconf.outfiles``); the
    target is checked before Graphviz runs, so a refused path costs no rendering.

    Raises:
        UsageError: unknown format, or ``path`` may not or cannot be written.
        ExternalToolError: Graphviz's ``dot`` is missing, fails or times out (exit 3).
    """
    output_target(path, stdout_ok=False)
    data, chosen = picture(path, dot_text, fmt, timeout=timeout)
    write_atomic(path, data)
    return chosen


def _graph(name: str, **attrs: str) -> DotGraph:
    return DotGraph(
        name,
        graph_attrs={**attrs, **FONT, "labelloc": "t", "nodesep": "0.3", "ranksep": "0.6"},
        node_attrs=dict(FONT),
        edge_attrs={"fontname": "Helvetica", "fontsize": "8", "arrowsize": "0.7"},
    )


def _vid(schema: InteroperabilitySchema, vertex: tuple[VertexKind, str]) -> str:
    return f"{schema.name}:{vertex[0].value}:{vertex[1]}"


def _vertices(new: RosGraph, old: RosGraph | None) -> list[Vertex]:
    """Return the new graph's vertices, then those only the old one has (stopped)."""
    extra = [v for v in old.nodes if v not in new] if old is not None else []
    return [*new.nodes, *extra]


def _edges(new: RosGraph, old: RosGraph | None) -> list[tuple[Vertex, Vertex]]:
    """Return the new graph's edges, then those only the old one has (stopped)."""
    extra = [e for e in old.edges if not new.has_edge(*e)] if old is not None else []
    return [*new.edges, *extra]


def _data(new: RosGraph, old: RosGraph | None, item: Vertex | tuple[Vertex, Vertex]) -> Any:
    """Return the attributes of a vertex or edge from whichever graph has it."""
    graph = new if (item in new.nodes or item in new.edges) or old is None else old
    return graph.nodes[item] if isinstance(item[0], VertexKind) else graph.edges[item]


def _status(in_new: bool, old: RosGraph | None, in_old: bool) -> Status:
    """Compare against the old graph; without one, everything drawn is simply running."""
    if old is None:
        return Status.UNCHANGED
    if in_new and not in_old:
        return Status.STARTED
    return Status.UNCHANGED if in_new else Status.STOPPED


def _cell(c: Component, s: InteroperabilitySchema, dead: frozenset[str], role: str) -> str:
    """Return the rest of a candidate's ``<TD`` cell: struck out, greyed, bold or plain."""
    name = html(c.name)
    if c.name in dead:
        return f' BGCOLOR="#f4cccc"><FONT COLOR="#990000"><S>{name}</S> failed</FONT>'
    if not c.may_serve_in(s.name):
        return f'><FONT COLOR="#999999"><I>{name}</I></FONT>'
    if s.nominal.get(role) == c.name:
        return f"><B>{name}</B>"
    return f">{name}"


def _ros_legend(g: DotGraph, seen: set[Status], kinds: set[VertexKind]) -> None:
    g.begin_cluster("legend", label="legend", **FONT, style="rounded", color="#999999")
    for kind, shape in SHAPES.items():
        if kind not in kinds:
            continue
        g.node(f"legend:{kind.value}", label=kind.value, shape=shape, **STYLES[Status.UNCHANGED])
    for status in (Status.FAILED, Status.STARTED, Status.STOPPED):
        if status in seen:
            g.node(f"legend:{status.value}", label=status.value, shape="ellipse", **STYLES[status])
    g.end_cluster()
