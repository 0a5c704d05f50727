"""Name and describe a stand-in node: what ``rosreconf.ros.standin_node`` must act out.

Pure data, apart from the module that starts roslaunch (``rosreconf.ros.standins``), so that
writing a launch file (``rosreconf.ros.launchfiles``) needs no process machinery.
"""

from __future__ import annotations

from typing import Any

from rosreconf.model import Component, InterfaceKind
from rosreconf.ros.conformance import interface_live_name

STANDIN_PACKAGE = "rosreconf_standin"
"""The package a stand-in ``<node pkg=...>`` names (it exists only in a temp dir)."""
STANDIN_EXECUTABLE = "standin_node"
"""The stand-in node's executable in that package (a copy of ``standin_node.py``)."""


def standin_spec(component: Component) -> dict[str, Any]:
    """Return the stand-in JSON spec acting out ``component``'s provisions and requirements."""
    publish, serve, subscribe = [], [], []
    for iface in sorted(component.provides):
        name = interface_live_name(component, iface.label)
        if iface.kind is InterfaceKind.SERVICE:
            serve.append({"service": name, "type": iface.type})
        else:
            publish.append({"topic": name, "type": iface.type})
    for req in component.requires:
        for option in req.options:  # services called are invisible at the master
            if option.kind is InterfaceKind.TOPIC:
                topic = interface_live_name(component, option.label)
                subscribe.append({"topic": topic, "type": option.type})
    return {"name": component.node_name, "publish": publish, "serve": serve, "subscribe": subscribe}


def ros2_type(library_type: str, kind: str) -> str:
    """Return the ROS 2 name of a library type: ``pkg/Name`` -> ``pkg/<kind>/Name``."""
    parts = library_type.split("/")
    return library_type if len(parts) == 3 else f"{parts[0]}/{kind}/{parts[-1]}"


def ros2_standin_spec(component: Component) -> dict[str, Any]:
    """Return the JSON spec ``rosreconf/ros/ros2/standin_node.py`` acts out for ``component``.

    As ``standin_spec``, with ROS 2 type names, the namespace, the services the component
    calls (a ROS 2 graph shows clients), and whether it is a managed (lifecycle) node.
    """
    publish, serve, subscribe, call = [], [], [], []
    action_serve, action_call = [], []  # the seam for ACTION interfaces (the stand-in refuses)
    for iface in sorted(component.provides):
        name = interface_live_name(component, iface.label)
        if iface.kind.value == "action":
            action_serve.append({"action": name, "type": ros2_type(iface.type, "action")})
        elif iface.kind is InterfaceKind.SERVICE:
            serve.append({"service": name, "type": ros2_type(iface.type, "srv")})
        else:
            publish.append({"topic": name, "type": ros2_type(iface.type, "msg")})
    for req in component.requires:
        for option in req.options:
            name = interface_live_name(component, option.label)
            if option.kind.value == "action":
                action_call.append({"action": name, "type": ros2_type(option.type, "action")})
            elif option.kind is InterfaceKind.TOPIC:
                subscribe.append({"topic": name, "type": ros2_type(option.type, "msg")})
            else:
                call.append({"service": name, "type": ros2_type(option.type, "srv")})
    launch = component.launch
    return {
        "name": component.node_name,
        "namespace": (launch.namespace if launch is not None else None) or "/",
        "publish": publish,
        "subscribe": subscribe,
        "serve": serve,
        "call": call,
        **({"action_serve": action_serve} if action_serve else {}),
        **({"action_call": action_call} if action_call else {}),
        "lifecycle": bool(launch is not None and launch.lifecycle),
    }
