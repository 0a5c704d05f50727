"""What ``watch`` does to a running system, behind one interface: the ``Actuator``.

The watcher (``rosreconf.ros.watcher``) decides what must change; an actuator changes it, as
far as its middleware lets it. Each source makes its own (``LiveSource.actuator``), so the
watcher holds one and never asks which::

    actuator                        made for                  start            retire
    ------------------------------  ------------------------  ---------------  ---------------------
    ``launcher.LaunchActuator``     ROS 1 (``--master URI``)  roslaunch        the node API's
                                                                               ``shutdown``
    ``ros2.launching.Ros2Launch``   ROS 2, ``--ros2-launch``  ``ros2 launch``  lifecycle transitions
                                                                               listed for a person
    ``ros2.actuator.Ros2Actuator``  ROS 2, ``--apply``        own processes    own processes ended,
                                                                               managed nodes
                                                                               transitioned, outside
                                                                               ones stopped or named

Each implementation owns its state, as a ros2_control hardware interface does: the parts it
acts through are its own (``Ros2Actuator`` holds its node processes, transitions, standbys
and the supervisor of the nodes rosreconf did not start, ``ros2.supervisor``), never a layer
it forwards to. A new way of acting is one more class: it implements ``start``, ``replace``
and ``close``, and inherits the rest as "nothing of that kind here" from ``Actuator``.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.options import WatchOptions

if TYPE_CHECKING:
    from rosreconf.ros.replanning import Change

Say = Callable[..., None]
"""Receives one event: its kind, its message, and its data as keyword arguments."""


@dataclass(frozen=True)
class Acting:
    """What a watcher's actuator is made from: the watcher's options, and what it acts with.

    Attributes:
        library, schema: what the configuration is made of.
        workdir: a private directory (the stand-in package; removed by the caller).
        env: the environment started processes run in.
        say: receives every event.
        options: as ``watch`` got them; without ``apply``, the actuator is asked only to
            read (``visible``, ``filtered``).
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    workdir: Path
    env: Mapping[str, str]
    say: Say
    options: WatchOptions = field(default_factory=WatchOptions)

    @property
    def directory(self) -> Path:
        """Return where launch files and launch output go."""
        launch_dir = self.options.launch_dir
        return launch_dir if launch_dir is not None else self.workdir


class Actuator(Protocol):
    """Start and retire a running system's components, and say what happened to them.

    ``start``, ``replace`` and ``close`` act; every other member has a default here (nothing
    held out of service, no own processes), which an implementation overrides where its
    middleware has more to say. Subclass it explicitly to inherit them.
    """

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Start ``components`` of ``current`` (or say how); True if something was started."""
        ...

    def replace(
        self,
        changes: list[Change],
        new: Configuration,
        failed: Collection[str],
        graph: Callable[[bool], LiveGraph],
    ) -> bool:
        """Put ``new`` in service: start what is new, retire what ``changes`` takes out.

        Retiring takes a component out of service (stopped, or its lifecycle taken down),
        and a kept component that is rewired is restarted. Each implementation orders the
        two as its middleware needs (make before break, or stop first). ``graph(fresh)``
        returns the live graph: read again with True, else the one last read if there is
        one. True if something was started.
        """
        ...

    def not_running(self, missing: list[str]) -> tuple[list[str], str]:
        """Return which of ``missing`` were started already, and why they may not run."""
        ...

    def close(self) -> None:
        """Stop every process started here (saying which), and release what is held."""
        ...

    def exits(self, current: Configuration, failed: Collection[str], *, tend: bool) -> set[str]:
        """Hand on what own processes said; return the components of ``current`` that ended.

        With ``tend``, keep up what is prepared in advance (not while confirming a change).
        """
        return set()

    def exited(self) -> bool:
        """Return whether an own node process has ended (a wait between polls ends early)."""
        return False

    def ended(self) -> bool:
        """Return whether the process that made the last change has exited (no use waiting)."""
        return False

    def forget(self, graph: LiveGraph, dead: list[str]) -> None:
        """Forget the ``dead`` nodes of ``graph`` where the middleware keeps listing them
        (ROS 1's master: ``purged``). Default: it forgets them by itself (a DDS lease)."""
        return None

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes held out of service on purpose."""
        return graph

    def filtered(self, check: Conformance) -> Conformance:
        """Return ``check`` without the findings about what is held out of service."""
        return check

    def left_running(self, check: Conformance) -> bool:
        """Return whether only nodes a person must stop keep ``check`` from conforming."""
        return False

    def settled(self, current: Configuration, failed: Collection[str]) -> None:
        """Note that ``current`` conforms (prepare what goes on standby for it)."""
        return None

    def started(self) -> frozenset[str]:
        """Return the components whose running process rosreconf started (never a clash)."""
        return frozenset()

    def theirs(self) -> frozenset[str]:
        """Return the components found running in a process rosreconf did not start (what
        started it restarts it; ``Restarts.last_resort``). Default: none known.
        """
        return frozenset()

    def awaited(self) -> frozenset[str]:
        """Return the components a person was asked to restart: gone a while, not failed."""
        return frozenset()

    def restart(self, *, stop: bool) -> None:
        """Forget what was started with a restarted master (with ``stop``, stop it)."""
        return None

    @property
    def reactivate(self) -> Callable[[str, str], bool] | None:
        """Return how to make a managed component ``active`` again; None: only say it."""
        return None

    def incarnations(self, node: str) -> frozenset[str] | None:
        """Return who announces ``node`` now (one id per process); None: cannot be told."""
        return None

    def squatter(self, component: str, role: str, node: str, beside: bool) -> bool:
        """Name, or stop, a node holding ``component``'s name that is not it (``clashes``);
        True when it was stopped (the name is free).
        """
        return False

    def retask(self, schema: InteroperabilitySchema) -> None:
        """Act for ``schema`` from now on (a task switch): what starts is wired for it."""
        return None

    def await_rewire(self, component: str, role: str, configuration: Configuration) -> None:
        """Ask a person to restart a node rosreconf did not start, wired for ``configuration``."""
        return None
