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
