"""What ``watch`` was asked to do, as one value: ``WatchOptions``, with its ROS 2 part.

The CLI builds it once from its flags; the watcher reads it, and hands it on whole to the
actuator its source makes (``actuator.Acting``). An option is then one field here, one flag
and one use, never a copy per layer it passes through.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.ros.livecontext import DWELL, SILENCE
from rosreconf.ros.livegraph import FACE_NAME, is_own_face
from rosreconf.ros.restarts import HOLD_SECONDS, RESTART_WINDOW
from rosreconf.solve.search import Budget


@dataclass(frozen=True)
class Ros2Options:
    """What only a ROS 2 ``watch --apply`` acts on.

    Attributes:
        standby: start and configure managed alternatives in advance.
        launch: run ``ros2 launch`` on launch files instead of starting each node's process.
        stop_outside: stop the process of a replaced node rosreconf did not start, when it
            runs only that node (``ros2.byhand``).
        force: supervise the domain though another watch supervises it (``ros2.domainclaim``).
        face: serve the watch's ROS 2 face (``ros2.face``: task parameter, /diagnostics,
            /rosout); ROS 2 only, with or without ``apply``.
        face_name: the face node's name; its base name is ``rosreconf`` or starts with
            ``rosreconf_``, so that ``inspect`` and ``watch`` know it for rosreconf's own.
    """

    standby: bool = False
    launch: bool = False
    stop_outside: bool = False
    force: bool = False
    face: bool = True
    face_name: str = FACE_NAME


@dataclass(frozen=True)
class ContextOptions:
    """How context read live rules components out (``livecontext.LiveContext``).

    Attributes:
        dwell: seconds a component's usability must be said without a break before it
            changes (``--dwell``).
        silence: seconds without a reading before a context topic is silent
            (``--context-silence``).
        lost_fails: a silent topic's conditions fail (``--context-lost fail``); else its
            last value is kept (``keep``).
    """

    dwell: float = DWELL
    silence: float = SILENCE
    lost_fails: bool = False


@dataclass(frozen=True)
class WatchOptions:
    """How a watcher watches, and how its actuator acts.

    Attributes:
        apply: stop and start components, rather than only say what should change.
        stand_ins: start stand-in nodes instead of the components' real executables.
        settle: seconds to wait for the live graph to conform after applying a change.
        launch_dir: where launch files and launch output go, kept after the watcher ends
            (default: the watcher's private directory).
        restart_limit, restart_window, hold: restart in place, hold, release (``restarts``).
        prefer_after: return to the configuration a failure left once its components have
            been candidates this long (``preference``; 0: never).
        budget: how far to search for a configuration that meets the performance
            requirements when the fewest-change one does not (``analysis.choice``).
        prefer: metric -> weight (``--prefer``): move to a configuration whose weighted
            metric sum is less, once failures and context allow it (``preference``).
        context: how context read live rules components out.
        ros2: what only ROS 2 acts on.
    """

    apply: bool = False
    stand_ins: bool = False
    settle: float = 30.0
    launch_dir: Path | None = None
    restart_limit: int = 0
    restart_window: float = RESTART_WINDOW
    hold: float = HOLD_SECONDS
    prefer_after: float = 0.0
    budget: Budget | None = None
    prefer: tuple[tuple[str, float], ...] = ()
    context: ContextOptions = field(default_factory=ContextOptions)
    ros2: Ros2Options = field(default_factory=Ros2Options)

    def check(self, ros2: bool) -> None:
        """Refuse options that do not go together on this middleware (``ros2``: ROS 2's).

        Raises:
            UsageError: ROS 2 options without ``--ros2 --apply``, or stand-ins with
                ``--ros2-launch`` (exit 2).
        """
        r = self.ros2
        if (r.standby or r.launch or r.stop_outside) and not (ros2 and self.apply):
            raise UsageError("--standby, --ros2-launch and --stop-outside are for --ros2 --apply")
        if self.stand_ins and r.launch:
            raise UsageError("--stand-ins start rclpy processes of their own: drop --ros2-launch")
        if r.face_name != FACE_NAME and not (ros2 and r.face):
            raise UsageError("--face-name is for --ros2 with its face (no --no-face)")
        if not is_own_face(r.face_name):
            raise UsageError(
                f"--face-name {r.face_name}: an absolute ROS name whose base name is rosreconf "
                "or starts with rosreconf_ (/robot1/rosreconf), so that inspect knows it"
            )
