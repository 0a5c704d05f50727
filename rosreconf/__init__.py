"""rosreconf: configure and reconfigure ROS systems from a component library.

The working form of Aitken, Veres and Judge, "Adaptation of System Configuration under the
Robot Operating System", IFAC 2014. The data flows one way, one module per arrow::

    YAML files -> loader (source positions) -> checks -> validity / solver / planning
               -> Configuration and ROS-graph -> reports (text, JSON, DOT, launch files)
"""

__version__ = "0.1.0"
