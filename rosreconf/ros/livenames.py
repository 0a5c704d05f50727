"""Name the model's nodes and interfaces as a live ROS system does, and what differs between them.

The model names nodes after components and interfaces after labels (Omega); a live system
uses global ROS names. ``rosreconf.model.wiring``'s ``node_live_name`` and
``interface_live_name``, on its one resolver of ROS names, are the one mapping (the table is
in ``rosreconf.model.wiring`` and ``rosreconf.ros.conformance``); used here by
``library_providers``. ``Finding`` is one difference found, and
``same_type`` the one comparison of a live type with the library's.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from rosreconf.model import Component, ComponentLibrary, Interface, type_key
from rosreconf.model.wiring import (
    interface_live_name,
    node_live_name,
    remap_rules,
    spelled_name,
)


def rules_said(component: Component, label: str, target: str, action: bool, ros: int) -> str:
    """Say the ``-r FROM:=TO`` rules that point ``component``'s name for ``label`` at ``target``.

    FROM is the name the node's code asks for (``spelled_name``: its library remapping, else
    the label), as a launch remapping (``rosreconf.ros.launchfiles.wiring``) rewrites it; an
    action takes one rule per name under it (``remap_rules``, for ROS version ``ros``).
    """
    rules = remap_rules(spelled_name(component, label), target, action, ros)
    return " ".join(f"-r {a}:={b}" for a, b in rules)


Providers = Mapping[Interface, tuple[tuple[str, str, str], ...]]
"""Interface -> (component, its node's live name, the interface's live name) of every
provision of it in a library."""


def library_providers(library: ComponentLibrary) -> Providers:
    """Return who in ``library`` provides each interface, and under which live name."""
    found: dict[Interface, set[tuple[str, str, str]]] = {}
    for comp in library.components:
        node = node_live_name(comp)
        for iface in comp.provides:
            live = interface_live_name(comp, iface.label)
            found.setdefault(iface, set()).add((comp.name, node, live))
    return {i: tuple(sorted(v)) for i, v in found.items()}


def option_names(component: Component, option: Interface, providers: Providers) -> dict[str, str]:
    """Return every live name ``component`` may be using for its requirement option ``option``.

    Name -> whose it is: the component's own name for it (its own name as the value), and
    each library provider's live name (that provider), which a launch remapping may have
    pointed it at. A name both are keeps the component's own.
    """
    names = {name: who for who, _, name in providers.get(option, ())}
    names[interface_live_name(component, option.label)] = component.name
    return names


@dataclass(frozen=True)
class Finding:
    """One way the live graph differs from the expected ROS-graph.

    Attributes:
        code: ``missing-node``, ``dead-node``, ``extra-node``, ``missing-service``,
            ``missing-topic``, ``wrong-type``, ``unmet-requirement``, ``unwired``,
            ``unpublished-subscription``, ``missing-action``, ``missing-action-client``,
            ``unserved-action-client``, and from a ROS 2 graph ``missing-client``,
            ``qos-incompatible``, ``unserved-client``, ``duplicate-node``, ``not-active``
            and ``not-managed`` (the table is in ``rosreconf.ros.conformance``).
        message: the difference in plain words.
        component: the component concerned, if any (None for extra nodes).
        live_name: the global ROS name concerned (node, topic, service or action).
    """

    code: str
    message: str
    component: str | None
    live_name: str


def same_type(live: str, library: str) -> bool:
    """Tell whether a live type names the library's (ROS 2 ``pkg/msg/Name`` = ``pkg/Name``)."""
    return type_key(live) == type_key(library)
