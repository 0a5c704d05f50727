"""Write launch files that start exactly one configuration, wired along its ROS-graph.

Each chosen component becomes one ``<node>`` from its library ``ros:`` entry (package,
executable, node name, namespace, args, parameters). Wiring follows the ROS-graph (Def. 1):
for every edge provider -> topic/service/action -> consumer, both names are resolved as ROS
resolves them, each for its own node (``rosreconf.model.wiring.resolve_name``: absolute,
relative to the node's namespace, ``~`` under the node's name, after the library's
``remappings``), and the consumer is remapped when the two differ, from the name *its*
executable spells to the provider's resolved name, absolute::

    library                                   launch file
    ----------------------------------------  -----------------------------------------------
    NCA1 provides camera_image,               <node name="NVP1" ...>
         remappings {camera_image:              <remap from="camera_image"
                     /camera1/image}                   to="/camera1/image"/>
    NVP1 requires camera_image                </node>
    sonar_array (namespace /sensors)          <node name="estimator" ...>
         provides scan                          <remap from="scan" to="/sensors/scan"/>
    estimator (namespace /) requires scan     </node>
    monitor (namespace /sensors)              <node name="monitor" namespace="/sensors"/>
         requires scan                          (/sensors/scan already: no remap)

A library ``remappings`` entry says which ROS name a component's executable really uses for
a label; the provider is therefore started as it is and its consumers are remapped to that
name (``rosreconf.ros.conformance`` resolves the same entry the same way when it checks a
live system). A rule for an action's name moves none of the names under it on ROS 1 nor on
Jazzy, so an action takes one rule per name under it (``remap_rules``: actionlib's five
topics, ROS 2's ``_action/`` services and topics). A private name is written ``~/x`` for
ROS 2 (rcl refuses ``~x``). One remapping can point a name at one place only: when a
consumer uses the same label from several providers that use different names, no remapping
is written; a comment in the node and an entry in ``LaunchFile.notes`` say so. The XML is
built with ``xml.etree``; no user value is ever pasted into markup.

``only`` writes just some of the configuration's nodes, still wired against the whole
configuration (``rosreconf watch`` starts only what a reconfiguration adds), and
``stand_ins`` runs every node as ``rosreconf.ros.ros1.standins``' stand-in, which acts out the
component's live names itself (ROS 1 only).
"""

from __future__ import annotations

import enum
import json
import shlex
import xml.etree.ElementTree as ET
from collections.abc import Collection
from dataclasses import dataclass

from rosreconf.errors import RosreconfError
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    Substitution,
)
from rosreconf.model import VertexKind as K
from rosreconf.model.validity import ros_graph
from rosreconf.model.wiring import (
    interface_live_name,
    node_live_name,
    node_namespace,
    remap_rules,
    spelled_name,
    used_interfaces,
)
from rosreconf.ros.standin_spec import STANDIN_EXECUTABLE, STANDIN_PACKAGE, standin_spec


class RosVersion(enum.StrEnum):
    """The launch-file dialects rosreconf writes."""

    ROS1 = "ros1"
    ROS2 = "ros2"


@dataclass(frozen=True)
class LaunchFile:
    """A generated launch file.

    Attributes:
        text: the XML document.
        nodes: the node names it starts, in role order.
        notes: wiring a remapping cannot express (see the module docstring).
    """

    text: str
    nodes: tuple[str, ...]
    notes: tuple[str, ...]


def launch_file(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    configuration: Configuration,
    version: RosVersion,
    *,
    only: Collection[str] | None = None,
    stand_ins: bool = False,
) -> LaunchFile:
    """Return a ROS 1 or ROS 2 XML launch file starting ``configuration`` of ``schema``.

    Args:
        only: start just these components (default: all of the configuration).
        stand_ins: start stand-in nodes instead of the components' executables (ROS 1).

    Raises:
        RosreconfError: chosen components have no ``ros:`` entry (all are named; exit 1).
    """
    chosen = [library[name] for name in configuration.components if only is None or name in only]
    if stand_ins:
        return _stand_in_file(library, schema, configuration, chosen)
    bare = [c.name for c in chosen if c.launch is None]
    if bare:
        raise RosreconfError(
            f"cannot write a launch file for {schema.display_name}: "
            f"{', '.join(bare)} {'has' if len(bare) == 1 else 'have'} no 'ros:' entry "
            "(package, executable) in the library"
        )
    _refuse_shared_node_names(schema, chosen)
    remaps, notes = _wiring(library, schema, configuration)
    root = ET.Element("launch")
    root.append(
        ET.Comment(
            _comment(
                f" Generated by rosreconf: starts configuration "
                f"{', '.join(configuration.components)} of schema {schema.name} "
                f"({schema.display_name}). Regenerate rather than edit. "
            )
        )
    )
    for c in chosen:
        root.append(_node(c, remaps.get(c.name, []), notes.get(c.name, []), version))
    ET.indent(root)
    text = '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(root, encoding="unicode")
    flat = tuple(n for c in chosen for n in notes.get(c.name, []))
    return LaunchFile(text + "\n", tuple(c.name for c in chosen), flat)


def _refuse_shared_node_names(schema: InteroperabilitySchema, chosen: list[Component]) -> None:
    """Refuse two components that would run as one ROS node (the second kills the first)."""
    seen: dict[str, str] = {}
    for c in chosen:
        live = node_live_name(c)
        if live in seen:
            raise RosreconfError(
                f"cannot write a launch file for {schema.display_name}: {seen[live]} and "
                f"{c.name} would both run as the ROS node {live} (give one another "
                "'ros.node' or 'ros.namespace')"
            )
        seen[live] = c.name


def _stand_in_file(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    configuration: Configuration,
    chosen: list[Component],
) -> LaunchFile:
    """Start stand-ins acting out the options they are wired to, remapped as real nodes are."""
    remaps = wiring(library, schema, configuration)
    uses = used_interfaces(library, schema, configuration.mapping)
    root = ET.Element("launch")
    root.append(
        ET.Comment(
            _comment(
                f" Generated by rosreconf: stand-ins for {', '.join(c.name for c in chosen)} "
                f"of {schema.display_name} ({', '.join(configuration.components)}). "
            )
        )
    )
    for c in chosen:
        attrs = {"pkg": STANDIN_PACKAGE, "type": STANDIN_EXECUTABLE, "name": c.node_name}
        if (ns := node_namespace(c)) is not None:
            attrs["ns"] = ns
        # roslaunch splits args like a shell: one single-quoted word, so no ' inside.
        spec = standin_spec(c, uses.get(c.name, frozenset()))
        attrs["args"] = "'" + json.dumps(spec).replace("'", "") + "'"
        attrs["output"] = "log"
        node = ET.SubElement(root, "node", attrs)
        for old, new, action in remaps.get(c.name, []):
            for a, b in remap_rules(old, new, action, 1):
                node.append(ET.Element("remap", {"from": a, "to": b}))
    ET.indent(root)
    text = '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(root, encoding="unicode")
    return LaunchFile(text + "\n", tuple(c.name for c in chosen), ())


Remap = tuple[str, str, bool]
"""One remapping of a consumer: (from, to, whether the name is an action's)."""


def _wiring(
    library: ComponentLibrary, schema: InteroperabilitySchema, configuration: Configuration
) -> tuple[dict[str, list[Remap]], dict[str, list[str]]]:
    """Return per consumer its remappings and the notes about what cannot be.

    Names are compared resolved, each for its own node (``interface_live_name``): a consumer
    in ``/`` and a provider in ``/sensors`` that both say ``scan`` use ``/scan`` and
    ``/sensors/scan``, so the consumer gets ``scan:=/sensors/scan``; two nodes of one
    namespace that say ``scan`` need none. ``from`` is the consumer's own spelling, ``to``
    the provider's resolved name, absolute, so it means the same in any namespace.
    """
    g = ros_graph(configuration, library, schema)
    # (consumer, its spelling) -> (its resolved name, provider -> the provider's resolved name)
    wanted: dict[tuple[str, str], tuple[str, dict[str, str]]] = {}
    actions: set[tuple[str, str]] = set()
    for vertex, (kind, consumer) in g.edges:
        if vertex[0] is K.NODE or kind is not K.NODE:
            continue
        label = str(g.nodes[vertex]["label"])
        user = library[consumer]
        key = (consumer, spelled_name(user, label))
        _, targets = wanted.setdefault(key, (interface_live_name(user, label), {}))
        # a topic may have several publishers (Nav2's controller_server and behavior_server
        # both publish cmd_vel_nav): each one's real name is wanted, one remapping if they agree
        for provider_vertex, _ in g.in_edges(vertex):
            if provider_vertex[0] is K.NODE:
                provider = library[provider_vertex[1]]
                targets[provider.name] = interface_live_name(provider, label)
        if vertex[0] is K.ACTION:
            actions.add(key)
    remaps: dict[str, list[Remap]] = {}
    notes: dict[str, list[str]] = {}
    for (consumer, own), (resolved, targets) in sorted(wanted.items()):
        names = sorted(set(targets.values()))
        if len(names) == 1:
            if names[0] != resolved:
                remaps.setdefault(consumer, []).append((own, names[0], (consumer, own) in actions))
            continue
        listed = ", ".join(f"{p} ({n})" for p, n in sorted(targets.items()))
        notes.setdefault(consumer, []).append(
            f"{consumer} uses '{own}' from several providers under different names: {listed}; "
            "one remapping cannot wire them all, so none is written"
        )
    return remaps, notes


def _node(c: Component, remaps: list[Remap], notes: list[str], version: RosVersion) -> ET.Element:
    launch = c.launch
    assert launch is not None  # checked by launch_file
    ros1 = version is RosVersion.ROS1
    attrs = {
        "pkg": launch.package,
        "type" if ros1 else "exec": launch.executable,
        "name": c.node_name,
    }
    if (ns := node_namespace(c)) is not None:
        attrs["ns" if ros1 else "namespace"] = ns
    if launch.args:
        attrs["args"] = shlex.join(launch.args)  # both dialects split args like a shell
    node = ET.Element("node", attrs)
    for note in notes:
        node.append(ET.Comment(_comment(f" {note} ")))
    for name, value in sorted(launch.parameters.items()):
        node.append(ET.Element("param", _param(name, value, version)))
    for old, new, action in remaps:
        for a, b in remap_rules(old, new, action, 1 if ros1 else 2):
            node.append(ET.Element("remap", {"from": a, "to": b}))
    return node


ROS1_TYPES = {bool: "bool", int: "int", float: "double", str: "str"}
"""Python value type -> roslaunch ``<param type=...>`` (explicit, so "1" stays a string)."""

ROS2_TYPES = {bool: "bool", int: "int", float: "float", str: "str"}
"""Python value type -> ROS 2 launch XML ``<param type=...>`` (launch_ros, Humble and later)."""


def _param(name: str, value: str | int | float | bool, version: RosVersion) -> dict[str, str]:
    """Return a ``<param>``'s attributes: the value as text and its type, named explicitly.

    Without ``type`` both dialects guess the type from the text, and ROS 2's launch guesses
    with YAML twice (launch_xml's attribute coercion, then launch_ros's parameter
    evaluation), so even a quoted ``'y'`` came back as a bool; with ``type`` each reads the
    text as exactly that type. A marked substitution is left to the launcher's own rules.
    """
    if isinstance(value, Substitution):  # marked by the user: the launcher evaluates it
        return {"name": name, "value": str(value)}
    text = ("true" if value else "false") if isinstance(value, bool) else str(value)
    types = ROS1_TYPES if version is RosVersion.ROS1 else ROS2_TYPES
    return {"name": name, "value": text, "type": types[type(value)]}


def rcl_value(value: str | int | float | bool) -> str:
    """Write ``value`` so that rcl's ``-p name:=value`` parser reads back its type and value.

    rcl types a plain scalar with rules of its own (rcl_yaml_param_parser ``get_value``), not
    YAML 1.1's or 1.2's: ``y``/``n``/``yes``/``on`` are bools, anything ``strtol`` (base 0:
    ``0x1F``, ``017``) reads whole an integer, anything ``strtod`` reads whole (``1e3``,
    ``inf``, ``nan``, ``.5``) a double. Only a quoted scalar is always a string, so every
    string is written double-quoted, with everything outside printable ASCII escaped:
    a single-quoted scalar would fold a line break into a space, and libyaml refuses raw
    control characters. Python writes a float always with ``.``, ``e``, ``inf`` or ``nan``,
    which ``strtol`` does not read whole, so a float stays a double and an int an integer.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, Substitution):  # marked by the user: nothing evaluates it here
        return str(value)
    if isinstance(value, str):
        return _yaml_double_quoted(value)
    return repr(value)


def _yaml_double_quoted(text: str) -> str:
    """Return ``text`` as a YAML double-quoted scalar that libyaml reads back exactly."""
    out = []
    for char in text:
        code = ord(char)
        if char in '"\\':
            out.append("\\" + char)
        elif 0x20 <= code < 0x7F:
            out.append(char)
        elif code < 0x100:
            out.append(f"\\x{code:02x}")
        elif code < 0x10000:
            out.append(f"\\u{code:04x}")
        else:
            out.append(f"\\U{code:08x}")
    return '"' + "".join(out) + '"'


def _comment(text: str) -> str:
    """Make ``text`` safe inside ``<!-- -->`` (no ``--``, no trailing ``-``)."""
    while "--" in text:
        text = text.replace("--", "- -")
    return text if not text.endswith("-") else text + " "


def wiring(
    library: ComponentLibrary, schema: InteroperabilitySchema, configuration: Configuration
) -> dict[str, list[Remap]]:
    """Return per consumer the remappings wiring it along the ROS-graph."""
    return _wiring(library, schema, configuration)[0]


def ros2_node_arguments(
    library: ComponentLibrary,
    component: str,
    remaps: dict[str, list[Remap]],
) -> list[str]:
    """Return the ``--ros-args`` that start ``component``'s node as its launch file would.

    Node name, namespace, the remappings wiring it (``remaps``, from ``wiring``), and its
    parameters (written so rcl reads each as the library's type, ``rcl_value``), for running
    the executable directly as ``ros2 run`` does (``rosreconf.ros.ros2.nodes``).
    """
    c = library[component]
    args = ["--ros-args", "-r", f"__node:={c.node_name}"]
    launch = c.launch
    if (ns := node_namespace(c)) is not None:
        args += ["-r", f"__ns:={ns}"]
    for rule in ros2_rules(remaps.get(component, [])):
        args += ["-r", rule]
    for name, value in sorted(launch.parameters.items()) if launch is not None else ():
        args += ["-p", f"{name}:={rcl_value(value)}"]
    return args


def ros2_rules(remaps: list[Remap]) -> list[str]:
    """Return the rcl rules ``from:=to`` that wire a node by ``remaps`` (from ``wiring``).

    One per topic or service, one per name under an action (``remap_rules``), a private
    name spelled ``~/x``: what ``--ros-args -r`` takes, in order.
    """
    return [f"{a}:={b}" for old, new, action in remaps for a, b in remap_rules(old, new, action, 2)]
