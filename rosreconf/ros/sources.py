"""Where a live graph comes from, and what acts on it there: ``LiveSource``.

Every live command reads one ``LiveGraph`` document, whatever the middleware, so that
comparing, importing, and re-planning are shared. What differs is here::

                  ROS 1 (``--master URI``)             ROS 2 (``--ros2 --domain N``)
    ------------  -----------------------------------  ------------------------------------------
    read          master XML-RPC + each node's getPid  DDS discovery + ros_discovery_info
    dead nodes    stay registered: purged like         leave by themselves when their
                  ``rosnode cleanup``                  participant's lease expires
    stop a node   its API's ``shutdown``               no remote kill in ROS 2: managed nodes get
                                                       lifecycle transitions (listed), processes
                                                       rosreconf started are ended by it
    start nodes   ``roslaunch --wait FILE``            ``ros2 launch FILE`` where a ``ros2``
                                                       command exists; otherwise the file is
                                                       written and the command said
    implemented   ``ros1.source.MasterSource``         ``ros2.source.Ros2Source``

``rosreconf.ros.connect`` opens the one the options name. A source only reads; each makes the
watcher's ``Actuator``, which does the rest of the table: ROS 1's purges, stops and runs
roslaunch (``ros1.source.MasterActuator``); ROS 2's ``--apply`` starts and retires each node's
process itself (``ros2.actuator``), or with ``--ros2-launch`` runs ``ros2 launch``. Both
launchers are a ``launcher.LaunchPort``.
"""

from __future__ import annotations

from typing import Any, Protocol

from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph


class LiveSource(Protocol):
    """A running system rosreconf reads; its actuator acts on it as far as the middleware allows."""

    @property
    def uri(self) -> str:
        """Return where the graph is read (a master URI, or ``ros2://domain/<id>``)."""
        ...

    @property
    def ros_version(self) -> RosVersion:
        """Return which launch files this system runs."""
        ...

    def read(self) -> LiveGraph:
        """Return the live graph now (the one read of every live command, ``watch``'s too).

        Raises:
            ExternalToolError: the graph cannot be read, or only in part (``watch`` stops
                at a first read's, and waits out a later one's).
        """
        ...

    def restarted(self) -> tuple[str, dict[str, Any]] | None:
        """Return what to say when the system restarted since the last call (None: it did not).

        A restarted ROS 1 master lists none of the nodes registered with the old one; a
        ROS 2 graph has no master, and never restarts as a whole.
        """
        ...

    def actuator(self, acting: Acting) -> Actuator:
        """Return what acts on this system for a watcher (``rosreconf.ros.actuator``)."""
        ...

    def close(self) -> None:
        """Release what reading holds (a DDS participant)."""
        ...
