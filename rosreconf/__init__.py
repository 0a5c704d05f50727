"""rosreconf: configure and reconfigure ROS systems from a component library.

The working form of Aitken, Veres and Judge, "Adaptation of System Configuration under the
Robot Operating System", IFAC 2014. The data flows one way, down the stages (folders of this
package; docs/architecture.md)::

    YAML files -> formats (read, JSON Schema, value and semantic checks, model; positions
                  looked up when a problem is reported) -> solve (count, enumerate,
                  optimise) / analysis (reliability, performance) / planning (PDDL,
                  planners) -> ros (launch files, live graphs) -> render (text, JSON, DOT
                  reports) -> cli
"""

__version__ = "0.1.0"
