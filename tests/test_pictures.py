"""Pictures: the DOT rosreconf writes, read back by an independent parser (pydot) and by dot.

pydot (test extra only) parses the DOT text, so vertices, shapes and edges are checked as a
reader sees them, not as the writer meant them; SVG rendering uses the real Graphviz.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

import pydot
import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.cli.common import Selection, select
from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.model import VertexKind
from rosreconf.model.validity import ros_graph
from rosreconf.render.dot import DotGraph, format_for, quote
from rosreconf.render.pictures import (
    SHAPES,
    STYLES,
    RosPicture,
    Status,
    library_dot,
    ros_dot,
    system_dot,
    write_picture,
)
from rosreconf.solve.running import targets

SCHEMA = "object_repositioning"


def _sel(*failed: str) -> Selection:
    return select(None, None, list(failed), [SCHEMA])


def _parse(text: str) -> pydot.Dot:
    (graph,) = pydot.graph_from_dot_data(text)
    return graph


def _nodes(graph: pydot.Dot) -> dict[str, dict[str, str]]:
    """Return node id -> attributes (unquoted) over the graph and its clusters."""
    out: dict[str, dict[str, str]] = {}
    for g in [graph, *graph.get_subgraphs()]:
        for n in g.get_nodes():
            if n.get_name().strip('"') not in ("node", "edge", "graph"):
                out[n.get_name().strip('"')] = {
                    k: v.strip('"') for k, v in n.get_attributes().items()
                }
    return out


def _edges(graph: pydot.Dot) -> dict[tuple[str, str], dict[str, str]]:
    out = {}
    for g in [graph, *graph.get_subgraphs()]:
        for e in g.get_edges():
            key = (str(e.get_source()).strip('"'), str(e.get_destination()).strip('"'))
            out[key] = {k: v.strip('"') for k, v in e.get_attributes().items()}
    return out


def _ros_picture(*failed: str) -> tuple[str, RosPicture, Selection]:
    sel = _sel(*failed)
    (t,) = targets(sel, None)
    picture = RosPicture(t.schema, t.configuration, t.before)
    return ros_dot(sel.library, [picture], sel.failed), picture, sel


def test_ros_view_has_every_vertex_in_its_shape_and_every_edge() -> None:
    text, picture, sel = _ros_picture()
    g = ros_graph(picture.configuration, sel.library, picture.schema)
    nodes, edges = _nodes(_parse(text)), _edges(_parse(text))
    for (kind, name), data in g.nodes(data=True):
        attrs = nodes[f"{SCHEMA}:{kind.value}:{name}"]
        assert attrs["shape"] == SHAPES[kind]
        assert attrs["fillcolor"] == STYLES[Status.UNCHANGED]["fillcolor"]
        assert attrs["label"].startswith(name if kind is VertexKind.NODE else data["label"])
    assert len({SHAPES[k] for k in VertexKind}) == len(VertexKind)  # no two kinds alike
    drawn = {k for k in edges if not k[0].startswith("legend")}
    expected = {
        (f"{SCHEMA}:{a[0].value}:{a[1]}", f"{SCHEMA}:{b[0].value}:{b[1]}") for a, b in g.edges
    }
    assert drawn == expected
    for (tail, head), data in g.edges.items():
        attrs = edges[f"{SCHEMA}:{tail[0].value}:{tail[1]}", f"{SCHEMA}:{head[0].value}:{head[1]}"]
        shown = attrs.get("label") if head[0] is not VertexKind.NODE else attrs.get("tooltip")
        assert shown == data["type"]


def test_reconfiguration_marks_failed_started_and_stopped() -> None:
    text, picture, _ = _ros_picture("NSM3")
    assert picture.before is not None
    nodes = _nodes(_parse(text))
    assert nodes[f"{SCHEMA}:node:NSM3"]["fillcolor"] == STYLES[Status.FAILED]["fillcolor"]
    assert "failed" in nodes[f"{SCHEMA}:node:NSM3"]["label"]
    assert nodes[f"{SCHEMA}:node:NSM1"]["style"] == STYLES[Status.STOPPED]["style"]
    assert nodes[f"{SCHEMA}:node:NDC3"]["fillcolor"] == STYLES[Status.STARTED]["fillcolor"]
    assert nodes[f"{SCHEMA}:node:NCA1"]["fillcolor"] == STYLES[Status.UNCHANGED]["fillcolor"]
    legend = {k for k in nodes if k.startswith("legend:")}
    assert legend == {
        f"legend:{x}" for x in ("node", "topic", "service", "failed", "started", "stopped")
    }


def test_system_view_draws_roles_and_provider_to_consumer_edges() -> None:
    sel = _sel()
    (schema,) = sel.schemas
    parsed = _parse(system_dot(sel.schemas))
    nodes = _nodes(parsed)
    assert set(nodes) == {f"{SCHEMA}:role:{r.name}" for r in schema.graph.roles}
    assert all(a["shape"] == "box" for a in nodes.values())
    assert nodes[f"{SCHEMA}:role:camera"]["label"] == "camera\\n(camera)"
    expected = {
        (f"{SCHEMA}:role:{e.provider}", f"{SCHEMA}:role:{e.consumer}") for e in schema.graph.edges
    }
    assert set(_edges(parsed)) == expected


def test_library_view_strikes_out_failed_candidates() -> None:
    sel = _sel("NSM3")
    nodes = _nodes(_parse(library_dot(sel.library, sel.schemas, sel.failed)))
    elbow = nodes[f"{SCHEMA}:role:elbow_joint"]["label"]
    assert "<S>NSM3</S>" in elbow and "NDC3" in elbow
    assert "<B>NSM1</B>" in nodes[f"{SCHEMA}:role:base_joint"]["label"]


def test_quote_escapes_quotes_backslashes_and_newlines() -> None:
    assert quote('a"b\\c\nd') == '"a\\"b\\\\c\\nd"'
    g = DotGraph("t")
    g.node('x"; evil=1; "', label="<b>")
    (node,) = [n for n in _parse(g.text()).get_nodes() if n.get_name() not in ("node", "edge")]
    assert node.get_name() == '"x\\"; evil=1; \\""'


def test_format_comes_from_the_suffix_or_the_option() -> None:
    assert format_for(Path("a.SVG")) == "svg"
    assert format_for(Path("a.txt"), "png") == "png"
    with pytest.raises(UsageError):
        format_for(Path("a.txt"))


def test_missing_dot_is_exit_3_and_writes_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, runner: CliRunner
) -> None:
    target = tmp_path / "g.svg"
    target.write_text("old")
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    with pytest.raises(ExternalToolError, match="apt-get install graphviz"):
        write_picture(target, "digraph {}")
    result = runner.invoke(app, ["graph", "--only", SCHEMA, "-o", str(target)])
    assert result.exit_code == 3, result.output
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["g.svg"]


def test_graph_writes_dot_without_graphviz(tmp_path: Path, runner: CliRunner) -> None:
    out = tmp_path / "lib.dot"
    result = runner.invoke(app, ["graph", "--view", "library", "--fail", "NSM3", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "<S>NSM3</S>" in out.read_text()


@pytest.mark.graphviz
def test_svg_is_well_formed_and_names_every_vertex(tmp_path: Path) -> None:
    text, picture, sel = _ros_picture("NSM3")
    out = tmp_path / "ros.svg"
    assert write_picture(out, text) == "svg"
    root = ET.parse(out).getroot()
    words = {t.strip() for el in root.iter() if el.text for t in [el.text]}
    g = ros_graph(picture.configuration, sel.library, picture.schema)
    for (kind, name), data in g.nodes(data=True):
        assert (name if kind is VertexKind.NODE else data["label"]) in words
    assert {"NSM3", "legend", "failed", "started", "stopped"} <= words


@pytest.mark.graphviz
def test_enumerate_draws_the_first_configuration_of_each_schema(
    tmp_path: Path, runner: CliRunner
) -> None:
    out = tmp_path / "first.png"
    result = runner.invoke(app, ["enumerate", "--limit", "1", "--graph", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(b"\x89PNG")
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


@pytest.mark.planner
def test_plan_draws_the_reconfiguration(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "replan.dot"
    result = runner.invoke(app, ["plan", "--fail", "NSM3", "--only", SCHEMA, "--graph", str(out)])
    assert result.exit_code == 0, result.stderr
    nodes = _nodes(_parse(out.read_text(encoding="utf-8")))
    fill = {name: attrs.get("fillcolor") for name, attrs in nodes.items()}
    started = {n for n, c in fill.items() if c == STYLES[Status.STARTED]["fillcolor"]}
    stopped = {n for n, c in fill.items() if c == STYLES[Status.STOPPED]["fillcolor"]}
    failed = {n for n, c in fill.items() if c == STYLES[Status.FAILED]["fillcolor"]}
    assert {f"{SCHEMA}:node:NDC{i}" for i in range(1, 6)} <= started
    assert {f"{SCHEMA}:node:NSM1", f"{SCHEMA}:node:NFB21"} <= stopped
    assert f"{SCHEMA}:node:NSM3" in failed
