"""Open the live source the options name: a ROS 1 master, a ROS 2 domain or a snapshot.

The one place that knows both middlewares (``ros1.source``, ``ros2.source``); everything else
in ``rosreconf.ros`` works on a ``LiveSource`` (``rosreconf.ros.sources``), and the CLI
imports neither middleware: what ``watch`` needs of ROS 2 before it reads (rclpy for the
stand-ins, the domain's claim, the options only ROS 2 has) is checked and taken here
(``watch_source``), and the defaults of every read are named here.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, MutableMapping
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.ros.livecontext import LiveContext
from rosreconf.ros.livegraph import LiveGraph, from_json
from rosreconf.ros.options import WatchOptions
from rosreconf.ros.ros1.rosmaster import DEFAULT_MAX_BYTES, DEFAULT_TIMEOUT
from rosreconf.ros.ros1.source import MasterSource
from rosreconf.ros.ros2.discovery import FIRST_READ_AT_LEAST
from rosreconf.ros.ros2.domainclaim import Claim, claim_domain
from rosreconf.ros.ros2.face import FaceNode, ask_switch
from rosreconf.ros.ros2.names import check_domain, gid_sizes
from rosreconf.ros.ros2.runtime import ros2_python
from rosreconf.ros.ros2.source import Ros2Source
from rosreconf.ros.sources import LiveSource
from rosreconf.ros.tasks import Face, Tasks

__all__ = [
    "DEFAULT_MAX_BYTES",
    "DEFAULT_SPIN_TIME",
    "DEFAULT_TIMEOUT",
    "ask_switch",
    "open_face",
    "open_source",
    "read_any",
    "watch_source",
]

DEFAULT_SPIN_TIME = FIRST_READ_AT_LEAST
"""Seconds a ROS 2 read listens at least before it may settle (``--spin-time``)."""


def open_source(
    master: str | None,
    ros2: bool,
    domain: int,
    distro: str | None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    spin_time: float = DEFAULT_SPIN_TIME,
) -> MasterSource | Ros2Source:
    """Return the source the options name: ``--master URI`` or ``--ros2 [--domain N]``.

    Raises:
        UsageError: both or neither are given, or ``--distro`` without ``--ros2``.
    """
    if ros2 == (master is not None):
        raise UsageError("give exactly one of --master URI and --ros2 [--domain N]")
    if master is not None:
        if distro is not None:
            raise UsageError("--distro is for --ros2 (ROS 2 over DDS) only")
        return MasterSource(master, timeout, max_bytes)
    check_domain(domain)
    gid_sizes(distro)  # refuse an unknown distribution before joining the domain
    return Ros2Source(domain, distro, spin_time=spin_time)


def read_any(
    master: str | None,
    snapshot: Path | None,
    ros2: bool = False,
    domain: int = 0,
    distro: str | None = None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    on_note: Callable[[str], None] | None = None,
    spin_time: float | None = None,
) -> LiveGraph:
    """Read the live graph from exactly one of a master, ROS 2 discovery and a snapshot.

    A ROS 2 read also asks every managed node its lifecycle state, and says through
    ``on_note`` what it had to leave out (undecodable or forged discovery samples).

    Raises:
        UsageError: not exactly one is given, or the snapshot cannot be read.
        ExternalToolError: the master does not answer, DDS cannot be used, or nothing ROS 2
            was seen on the domain.
    """
    if sum((master is not None, snapshot is not None, ros2)) != 1:
        raise UsageError("give exactly one of --master URI, --ros2 and --snapshot FILE")
    if spin_time is not None and not ros2:
        raise UsageError("--spin-time is for --ros2 (ROS 2 over DDS) only")
    if snapshot is not None:
        try:
            return from_json(snapshot.read_text(encoding="utf-8"), str(snapshot))
        except OSError as exc:
            raise UsageError(f"{snapshot}: cannot read: {exc.strerror}") from None
    spin = DEFAULT_SPIN_TIME if spin_time is None else spin_time
    source = open_source(
        master, ros2, domain, distro, timeout=timeout, max_bytes=max_bytes, spin_time=spin
    )
    if isinstance(source, Ros2Source):
        source.on_note = on_note
    try:
        return source.read()
    finally:
        source.close()


def watch_source(
    master: str | None,
    ros2: bool,
    domain: int,
    distro: str | None,
    env: MutableMapping[str, str],
    options: WatchOptions,
    *,
    timeout: float,
    max_bytes: int,
    on_note: Callable[[str], None],
) -> tuple[LiveSource, Callable[[], None] | None]:
    """Open the source ``watch`` watches, ``options`` checked against it and its domain taken.

    Returns the source and what releases the domain's claim (ROS 2 ``--apply``; else None).
    ``env`` (what started processes run in) gets the master's URI or the domain. ``on_note``
    says what a read left out, and a claim not made.

    Raises:
        UsageError: options that do not go together, or another watch on the domain (exit 2).
        ExternalToolError: stand-ins on ROS 2 and no Python with rclpy here (exit 3).
    """
    apply = options.apply
    if ros2 and master is None and apply and options.stand_ins:
        ros2_python(env)  # no rclpy here: said now, before a DDS session is even opened
    source = open_source(master, ros2, domain, distro, timeout=timeout, max_bytes=max_bytes)
    try:  # a refusal below closes the source at once: nothing left for the exit to wait on
        if isinstance(source, Ros2Source):
            source.empty_ok = (
                apply  # it starts the nodes itself: an empty domain is where it starts
            )
            source.on_note = on_note
        ros2 = isinstance(source, Ros2Source)
        options.check(ros2)
        if master is not None:
            env["ROS_MASTER_URI"] = master
        else:
            env["ROS_DOMAIN_ID"] = str(domain)
        claim = _claim(domain, options.ros2.force, on_note) if ros2 and apply else None
    except BaseException:
        source.close()
        raise
    return source, None if claim is None else claim.release


def open_face(
    options: WatchOptions,
    env: Mapping[str, str],
    log: Path,
    tasks: Tasks,
    context: LiveContext | None = None,
) -> Face:
    """Start the ROS 2 face ``options`` name (``ros2.face``), its requests going to ``tasks``,
    its context readings to ``context``. Without the face (``--no-face``) and with context
    to read, a node ``<face name>_context`` only reads it.

    Raises:
        ExternalToolError: no ROS 2 Python with rclpy and diagnostic_msgs, or it did not start.
    """
    serve = options.ros2.face
    name = options.ros2.face_name + ("" if serve else "_context")
    if context is None:
        return FaceNode(name, env, log, tasks.ask, serve=serve)
    args = context.variables, context.heard, context.unreadable
    return FaceNode(name, env, log, tasks.ask, *args, serve=serve)


def _claim(domain: int, force: bool, on_note: Callable[[str], None]) -> Claim | None:
    """Take ``domain`` for this watch; refuse when another watch holds it (see domainclaim).

    Two supervisors of one domain each start and stop nodes against the other. ``--force``
    goes on without the claim, said through ``on_note``; so does a claim that cannot be made.

    Raises:
        UsageError: another watch supervises the domain, and no ``--force`` (exit 2).
    """
    try:
        got = claim_domain(domain)
    except OSError as exc:
        on_note(
            f"note: cannot claim ROS domain {domain} ({exc.strerror}): another watch on it"
            " would not be seen"
        )
        return None
    if isinstance(got, Claim):
        return got
    if not force:
        raise UsageError(
            f"{got.message}: two watches would start and stop nodes against each other. Stop "
            "that one, watch without --apply, or pass --force"
        )
    on_note(f"note: {got.message}; going on (--force)")
    return None
