"""Write Graphviz DOT text safely, and turn it into SVG or PNG with Graphviz's ``dot``.

DOT is written here, in one small class, rather than with networkx's ``nx_pydot`` or
``nx_agraph``: both need a package rosreconf does not keep (pydot, or pygraphviz with its C
build), and the subset needed (nodes, edges, clusters, attributes) is small. All quoting
lives in ``quote`` and ``html``: every user-supplied name passes through one of them, so a
component called ``a"b`` or a label with ``<`` can never break out of its string.

Rendering runs ``dot`` through ``rosreconf.procs.run_program`` (argument list, process-group
timeout) in a private temp dir, because ``dot`` writes PNG bytes that must not be decoded.
"""

from __future__ import annotations

import html as _html
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.procs import private_workdir, run_program

DOT_TIMEOUT = 60.0
"""Seconds ``dot`` may take for one picture before its process group is stopped."""

FORMATS = {".dot": "dot", ".gv": "dot", ".svg": "svg", ".png": "png"}
"""File suffix -> picture format; the format names are also the CLI's ``--format`` choices."""

INSTALL_HINT = (
    "Graphviz's dot was not found; install Graphviz (Debian/Ubuntu: apt-get install graphviz; "
    "macOS: brew install graphviz), or write DOT text with --format dot"
)


class Html(str):
    """Mark an attribute value as a Graphviz HTML-like label (written ``<...>``, not quoted)."""

    __slots__ = ()


def quote(text: str) -> str:
    """Return ``text`` as a DOT double-quoted string; a newline becomes a centred line break."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    return '"' + escaped.replace("\r", "").replace("\n", "\\n") + '"'


def html(text: str) -> str:
    """Escape ``text`` for use inside an HTML-like label."""
    return _html.escape(text, quote=True)


def _value(value: str) -> str:
    return f"<{value}>" if isinstance(value, Html) else quote(value)


def _attrs(attrs: dict[str, str]) -> str:
    if not attrs:
        return ""
    return " [" + ", ".join(f"{k}={_value(v)}" for k, v in attrs.items()) + "]"


@dataclass
class DotGraph:
    """A directed graph being written as DOT text, with clusters one level deep.

    Attributes:
        name: the graph's name (also its title in SVG viewers).
        graph_attrs: graph attributes (``rankdir``, ``label`` ...).
        node_attrs: default node attributes.
        edge_attrs: default edge attributes.
        lines: the statements written so far, already quoted and indented.
    """

    name: str
    graph_attrs: dict[str, str] = field(default_factory=dict)
    node_attrs: dict[str, str] = field(default_factory=dict)
    edge_attrs: dict[str, str] = field(default_factory=dict)
    lines: list[str] = field(default_factory=list)
    _indent: str = "  "

    def node(self, node_id: str, **attrs: str) -> None:
        """Add a node with attributes (``id`` is quoted; it never needs to be unique-safe)."""
        self.lines.append(f"{self._indent}{quote(node_id)}{_attrs(attrs)};")

    def edge(self, tail: str, head: str, **attrs: str) -> None:
        """Add an edge ``tail -> head``."""
        self.lines.append(f"{self._indent}{quote(tail)} -> {quote(head)}{_attrs(attrs)};")

    def begin_cluster(self, cluster_id: str, **attrs: str) -> None:
        """Open a cluster (``subgraph cluster_...``); close it with ``end_cluster``."""
        self.lines.append(f"  subgraph {quote('cluster_' + cluster_id)} {{")
        self._indent = "    "
        self.lines.extend(f"    {key}={_value(value)};" for key, value in attrs.items())

    def end_cluster(self) -> None:
        """Close the open cluster."""
        self._indent = "  "
        self.lines.append("  }")

    def text(self) -> str:
        """Return the whole graph as DOT text."""
        head = [f"digraph {quote(self.name)} {{"]
        head += [f"  {k}={_value(v)};" for k, v in self.graph_attrs.items()]
        if self.node_attrs:
            head.append(f"  node{_attrs(self.node_attrs)};")
        if self.edge_attrs:
            head.append(f"  edge{_attrs(self.edge_attrs)};")
        return "\n".join([*head, *self.lines, "}"]) + "\n"


def format_for(path: Path, given: str | None = None) -> str:
    """Return the picture format: ``given`` if set, else the one ``path``'s suffix names.

    Raises:
        UsageError: the format is unknown, or cannot be told from the suffix.
    """
    choices = sorted(set(FORMATS.values()))
    if given is not None:
        if given not in choices:
            raise UsageError(f"--format {given}: choose one of {', '.join(choices)}")
        return given
    if str(path) == "-":
        return "dot"  # stdout: text unless --format asks for a picture
    fmt = FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise UsageError(
            f"{path}: cannot tell the picture format from the suffix; name the file "
            f"{', '.join(sorted(FORMATS))}, or give --format ({', '.join(choices)})"
        )
    return fmt


def render(dot_text: str, fmt: str, *, timeout: float = DOT_TIMEOUT) -> bytes:
    """Return ``dot_text`` rendered by Graphviz as ``fmt`` (``svg`` or ``png``) bytes.

    Raises:
        ExternalToolError: ``dot`` is missing (with how to install it), fails or times out.
    """
    with private_workdir() as work:
        out = work / f"picture.{fmt}"
        result = run_program(
            ["dot", f"-T{fmt}", "-o", str(out)], timeout=timeout, stdin=dot_text.encode("utf-8")
        )
        if result.missing:
            raise ExternalToolError(INSTALL_HINT)
        result.check()
        try:
            return out.read_bytes()
        except OSError:
            raise ExternalToolError(f"dot wrote no {fmt} picture") from None
