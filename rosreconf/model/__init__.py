"""The paper's model: immutable, free of I/O, named as in Aitken, Veres and Judge (2014).

Every class here is a frozen dataclass of tuples and frozensets, so a loaded library or
schema can be shared between the enumerator, the PDDL renderer and the reports without
anyone changing it under the others' feet. Source positions are kept beside the values
(``Span``) so that semantic checks made long after parsing can still point at a line.

How the paper's names map onto this module::

    paper                                  here
    -------------------------------------  ------------------------------------------
    Omega (interface label)                Interface.label
    Gamma (message class)                  Interface.type (canonical: type_key)
    S+ / T+ (Def. 2, provision)            Component.provides
    S- / T- (Def. 3, requirement)          Component.requires (each a Requirement)
    abstraction N -> Lambda (Def. 5 (1))   Component.abstraction
    component library L                    ComponentLibrary
    system graph (Def. 5 (2))              SystemGraph (roles labelled from Lambda)
    interoperability schema [G, x, e]      InteroperabilitySchema (graph, skill, environment)
    configuration library C (Def. 8)       ConfigurationLibrary (orthogonality: analysis)
    ROS-graph {N, T, S, E} (Def. 1)        RosGraph (a networkx DiGraph; nodes, topics,
                                           services, actions)
    configuration                          Configuration (role -> component)
    M-solution: a component's model        Component.dynamics (TransferFunction | StateSpace)
    M-solution: environment, loops         InteroperabilitySchema.simulation (Simulation)
    (not in the paper) what is measured    ComponentLibrary.context (ContextVariable, in
                                           model.context; docs/context.md)
    (not in the paper) usable only when    Component.when (Condition), RuledOut
"""

# The model's public names, re-exported so that readers import them from one place.
from typing import TYPE_CHECKING, Any

from rosreconf.model.dynamics import (
    ControlLoop,
    Dynamics,
    PerformanceRequirements,
    Simulation,
    StateSpace,
    TransferFunction,
)
from rosreconf.model.library import (
    NOWHERE,
    Component,
    ComponentLibrary,
    Interface,
    InterfaceKind,
    Requirement,
    RosLaunch,
    Span,
    Substitution,
    type_folder,
    type_key,
)
from rosreconf.model.schema import (
    EMPTY,
    Configuration,
    ConfigurationLibrary,
    Edge,
    InteroperabilitySchema,
    Role,
    SystemGraph,
    VertexKind,
    interface_vertex,
    node_vertex,
    shown,
    shown_text,
)

if TYPE_CHECKING:
    from rosreconf.model.schema import RosGraph


def __getattr__(name: str) -> Any:
    """Return ``RosGraph`` lazily: it is networkx's DiGraph, which is slow to import."""
    if name == "RosGraph":
        from rosreconf.model import schema

        return schema.RosGraph
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "EMPTY",
    "NOWHERE",
    "Component",
    "ComponentLibrary",
    "Configuration",
    "ConfigurationLibrary",
    "ControlLoop",
    "Dynamics",
    "Edge",
    "Interface",
    "InterfaceKind",
    "InteroperabilitySchema",
    "PerformanceRequirements",
    "Requirement",
    "Role",
    "RosGraph",
    "RosLaunch",
    "Simulation",
    "Span",
    "StateSpace",
    "Substitution",
    "SystemGraph",
    "TransferFunction",
    "VertexKind",
    "interface_vertex",
    "node_vertex",
    "shown",
    "shown_text",
    "type_folder",
    "type_key",
]
