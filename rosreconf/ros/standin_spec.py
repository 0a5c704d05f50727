"""Name and describe a stand-in node: what a stand-in must act out, on either middleware.

The ROS 1 stand-in (``ros/ros1/scripts/standin_node.py``, under roslaunch) and the ROS 2 one
(``ros/ros2/scripts/standin_node.py``, an rclpy node) read the specs written here.

Pure data, apart from the module that starts roslaunch (``rosreconf.ros.ros1.standins``), so that
writing a launch file (``rosreconf.ros.launchfiles``) needs no process machinery.

Actions are listed under ``actions`` (name, type, server or client) for a ROS 2 stand-in to
act out. The ROS 1 stand-in ignores that list; it acts an action out as actionlib does, as
five topics (``action_topics``), which the spec lists with the other topics, so the master
shows the action as ``rosreconf.ros.liveactions`` reads it.
"""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from rosreconf.model import Component, Interface, InterfaceKind
from rosreconf.model.wiring import interface_live_name, node_namespace
from rosreconf.ros.liveactions import ROS1_SERVER_PUBLISHES

STANDIN_PACKAGE = "rosreconf_standin"
"""The package a stand-in ``<node pkg=...>`` names (it exists only in a temp dir)."""
STANDIN_EXECUTABLE = "standin_node"
"""The stand-in node's executable in that package (a copy of ``standin_node.py``)."""


def action_topics(name: str, iface: Interface) -> dict[str, dict[str, str]]:
    """Return the five actionlib topics of action ``name`` (ROS 1), keyed by their part."""
    package, _, base = iface.type.partition("/")  # the canonical pkg/T
    types = {
        "goal": f"{package}/{base}ActionGoal",
        "cancel": "actionlib_msgs/GoalID",
        "status": "actionlib_msgs/GoalStatusArray",
        "feedback": f"{package}/{base}ActionFeedback",
        "result": f"{package}/{base}ActionResult",
    }
    return {part: {"topic": f"{name}/{part}", "type": t} for part, t in types.items()}


def _options(component: Component, uses: Collection[Interface] | None) -> list[Interface]:
    """Return the requirement options a stand-in acts out: those it is wired to, or all.

    ``uses`` (``rosreconf.model.wiring.used_interfaces``) holds the options on the node's
    ROS-graph edges in the configuration it is started for; None: every option (a stand-in
    started for no configuration).
    """
    return [o for r in component.requires for o in r.options if uses is None or o in uses]


def standin_spec(component: Component, uses: Collection[Interface] | None = None) -> dict[str, Any]:
    """Return the stand-in JSON spec acting out ``component``'s provisions and requirements.

    ``uses``: the requirement options it is wired to (``_options``). Names are resolved for
    the component's node (``interface_live_name``) and written absolute; rospy resolves a
    launch remapping's ``from`` for the node too, so the stand-in is wired as the real node.
    """
    publish: list[dict[str, str]] = []
    serve: list[dict[str, str]] = []
    subscribe: list[dict[str, str]] = []
    actions: list[dict[str, str]] = []
    for iface in sorted(component.provides):
        name = interface_live_name(component, iface.label)
        if iface.kind is InterfaceKind.SERVICE:
            serve.append({"service": name, "type": iface.type})
        elif iface.kind is InterfaceKind.ACTION:
            actions.append({"action": name, "type": iface.written, "role": "server"})
            for part, entry in action_topics(name, iface).items():
                (publish if part in ROS1_SERVER_PUBLISHES else subscribe).append(entry)
        else:
            publish.append({"topic": name, "type": iface.type})
    for option in _options(component, uses):  # services called are invisible at the master
        if option.kind is InterfaceKind.TOPIC:
            subscribe.append(
                {"topic": interface_live_name(component, option.label), "type": option.type}
            )
        elif option.kind is InterfaceKind.ACTION:
            name = interface_live_name(component, option.label)
            actions.append({"action": name, "type": option.written, "role": "client"})
            for part, entry in action_topics(name, option).items():
                (subscribe if part in ROS1_SERVER_PUBLISHES else publish).append(entry)
    spec: dict[str, Any] = {
        "name": component.node_name,
        "publish": publish,
        "serve": serve,
        "subscribe": subscribe,
    }
    if actions:
        spec["actions"] = actions
    return spec


def ros2_type(library_type: str, kind: str) -> str:
    """Return the ROS 2 name of a library type: ``pkg/Name`` -> ``pkg/<kind>/Name``."""
    parts = library_type.split("/")
    return library_type if len(parts) == 3 else f"{parts[0]}/{kind}/{parts[-1]}"


def ros2_standin_spec(
    component: Component, uses: Collection[Interface] | None = None
) -> dict[str, Any]:
    """Return the JSON spec ROS 2's ``scripts/standin_node.py`` acts out for ``component``.

    As ``standin_spec``, with ROS 2 type names, the namespace, the services the component
    calls (a ROS 2 graph shows clients), and whether it is a managed (lifecycle) node. Its
    names are the ones the component's executable uses, resolved for its node
    (``interface_live_name``: namespace, ``~``, the library's remappings), written absolute; it
    is wired by ``-r`` remappings, as a real executable is: rcl matches a rule's ``from``,
    resolved for the node, against the resolved name, so the two are wired alike.
    """
    publish, serve, subscribe, call = [], [], [], []
    action_serve, action_call = [], []
    for iface in sorted(component.provides):
        name = interface_live_name(component, iface.label)
        if iface.kind is InterfaceKind.ACTION:
            action_serve.append({"action": name, "type": ros2_type(iface.type, "action")})
        elif iface.kind is InterfaceKind.SERVICE:
            serve.append({"service": name, "type": ros2_type(iface.type, "srv")})
        else:
            publish.append({"topic": name, "type": ros2_type(iface.type, "msg")})
    for option in _options(component, uses):
        name = interface_live_name(component, option.label)
        if option.kind is InterfaceKind.ACTION:
            action_call.append({"action": name, "type": ros2_type(option.type, "action")})
        elif option.kind is InterfaceKind.TOPIC:
            subscribe.append({"topic": name, "type": ros2_type(option.type, "msg")})
        else:
            call.append({"service": name, "type": ros2_type(option.type, "srv")})
    launch = component.launch
    return {
        "name": component.node_name,
        "namespace": node_namespace(component) or "/",
        "publish": publish,
        "subscribe": subscribe,
        "serve": serve,
        "call": call,
        **({"action_serve": action_serve} if action_serve else {}),
        **({"action_call": action_call} if action_call else {}),
        "lifecycle": bool(launch is not None and launch.lifecycle),
        "component": component.name,
    }
