"""``rosreconf watch``: keep a live system in a valid configuration when its nodes fail."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import replace
from pathlib import Path
from typing import IO, Annotated

import typer

from rosreconf.cli.common import (
    ConfigurationOption,
    DistroOption,
    DomainOption,
    FailOption,
    LibraryOption,
    MasterTimeoutOption,
    MaxAnswerOption,
    OnlySchemaOption,
    OptionalMasterOption,
    Ros2Option,
    SchemaOption,
    WatchSearchLimitOption,
    WatchSearchTimeOption,
    finite,
    select,
    weights_of,
)
from rosreconf.cli.console import stderr
from rosreconf.cli.stopping import stop_on_signals
from rosreconf.errors import ExitCode, ExternalToolError, UsageError
from rosreconf.gcpause import stop_freezing
from rosreconf.model import ComponentLibrary
from rosreconf.procs import private_workdir
from rosreconf.render.reports.watch import event_json, event_line
from rosreconf.ros.connect import DEFAULT_MAX_BYTES, DEFAULT_TIMEOUT, open_face, watch_source
from rosreconf.ros.events import Event
from rosreconf.ros.launcher import launch_log_dir
from rosreconf.ros.livecontext import DWELL, SILENCE, LiveContext
from rosreconf.ros.livegraph import FACE_NAME
from rosreconf.ros.options import ContextOptions, Ros2Options, WatchOptions
from rosreconf.ros.polling import poll
from rosreconf.ros.restarts import HOLD_SECONDS, RESTART_WINDOW
from rosreconf.ros.tasks import Tasks
from rosreconf.ros.watcher import Watcher
from rosreconf.solve.running import one_target
from rosreconf.solve.search import SEARCH_LIMIT, SEARCH_TIME, Budget


def watch_command(
    master: OptionalMasterOption = None,
    configuration: ConfigurationOption = None,
    only: OnlySchemaOption = None,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    apply: Annotated[
        bool, typer.Option("--apply", help="Stop and start components, not only replan.")
    ] = False,
    stand_ins: Annotated[
        bool,
        typer.Option("--stand-ins", help="Launch stand-in nodes instead of the real executables."),
    ] = False,
    standby: Annotated[
        bool,
        typer.Option(
            "--standby",
            help="ROS 2: start, configure managed alternatives in advance (failover: activate).",
        ),
    ] = False,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="ROS 2 --apply: supervise the domain though another watch supervises it.",
        ),
    ] = False,
    restarts: Annotated[
        int,
        typer.Option(
            "--restarts",
            min=0,
            max=1000,
            help="Restart a failed component in place (1 change) up to N times per "
            "--restart-window while another configuration is left; then hold it failed and "
            "move away from it. 0: never. With none left, it is restarted anyway, backing off.",
        ),
    ] = 0,
    restart_window: Annotated[
        float,
        typer.Option(min=1.0, max=86400, callback=finite, help="Seconds --restarts counts over."),
    ] = RESTART_WINDOW,
    hold: Annotated[
        float,
        typer.Option(
            min=0.0,
            max=86400,
            callback=finite,
            help="Seconds a failed component is held before it is a candidate again; the "
            "longest wait between restarts of one no configuration can do without.",
        ),
    ] = HOLD_SECONDS,
    prefer_after: Annotated[
        float,
        typer.Option(
            "--prefer-after",
            min=0.0,
            max=86400,
            callback=finite,
            help="--apply: return to the configuration a failure left once all its components "
            "have been candidates this many seconds (held ones back twice as late). 0: never.",
        ),
    ] = 0.0,
    prefer: Annotated[
        list[str] | None,
        typer.Option(
            "--prefer",
            metavar="METRIC=WEIGHT",
            help="Move to the best configuration by these weights (as --best --objective) "
            "once failures and context allow it; never back and forth (repeatable).",
            show_default=False,
        ),
    ] = None,
    dwell: Annotated[
        float,
        typer.Option(
            min=0.0,
            max=3600,
            callback=finite,
            help="ROS 2: seconds a context condition must hold, or fail, without a break "
            "before a component is ruled out or usable again.",
        ),
    ] = DWELL,
    context_silence: Annotated[
        float,
        typer.Option(
            "--context-silence",
            min=0.1,
            max=3600,
            callback=finite,
            help="ROS 2: seconds without a reading before a context topic is said silent.",
        ),
    ] = SILENCE,
    context_lost: Annotated[
        str,
        typer.Option(
            "--context-lost",
            metavar="keep|fail",
            help="ROS 2: a silent context topic keeps its last value (keep), or its "
            "conditions fail (fail).",
        ),
    ] = "keep",
    stop_outside: Annotated[
        bool,
        typer.Option(
            "--stop-outside",
            help="ROS 2 --apply: stop the process of a replaced node rosreconf did not start "
            "(SIGINT, SIGTERM, SIGKILL), when /proc confirms it runs that node alone.",
        ),
    ] = False,
    face: Annotated[
        bool,
        typer.Option(
            "--face/--no-face",
            help="ROS 2: serve rosreconf's node (task parameter, /diagnostics, /rosout).",
        ),
    ] = True,
    face_name: Annotated[
        str,
        typer.Option(
            "--face-name",
            help="ROS 2: the face node's name (base name rosreconf or rosreconf_*).",
        ),
    ] = FACE_NAME,
    ros2_launch: Annotated[
        bool,
        typer.Option(
            "--ros2-launch",
            help="ROS 2: run 'ros2 launch' on launch files instead of starting each node.",
        ),
    ] = False,
    interval: Annotated[
        float, typer.Option(min=0.05, max=3600, callback=finite, help="Seconds between polls.")
    ] = 1.0,
    settle: Annotated[
        float,
        typer.Option(
            min=1.0,
            max=3600,
            callback=finite,
            help="Seconds a change may take to show on the master.",
        ),
    ] = 30.0,
    json_log: Annotated[
        Path | None, typer.Option("--json-log", help="Also write every event as a JSON line.")
    ] = None,
    once: Annotated[bool, typer.Option("--once", help="Poll once, act, confirm, exit.")] = False,
    master_timeout: MasterTimeoutOption = DEFAULT_TIMEOUT,
    max_answer_mb: MaxAnswerOption = DEFAULT_MAX_BYTES >> 20,
    ros2: Ros2Option = False,
    domain: DomainOption = 0,
    distro: DistroOption = None,
    search_limit: WatchSearchLimitOption = SEARCH_LIMIT,
    search_time: WatchSearchTimeOption = SEARCH_TIME,
) -> None:
    """Watch the live system; when a node fails, replan with the fewest changes (and apply).

    Logs every decision with a timestamp on stderr. Ctrl-C or SIGTERM stops everything it
    started (within 4 s; exit 130 or 143). With --apply, launch files and output are kept in a
    new directory rosreconf-watch-* under ROS's log directory (said at the start). ROS 2 nodes
    run as ros2 run starts them (<prefix>/lib/<package>/<executable>); stand-ins and
    rosreconf's ROS 2 helpers run under ROSRECONF_ROS2_PYTHON or the first python3 with rclpy
    (exit 3 if one is needed and none is found). When no configuration is found (none
    exists, or the search for one meeting the performance requirements is spent), it logs
    no-configuration and keeps watching. With --once: exit 0 if the system conforms at the
    end, else 1. A second --ros2 --apply watch on a domain that another watch of this host
    supervises is refused (exit 2, naming its pid), unless --force. A failed component is
    restarted in place up to --restarts times per --restart-window, else held failed for
    --hold seconds (twice as long each time it is held again), then a candidate again; with
    --prefer-after, watch returns to the configuration it left once that one is whole again;
    with --prefer, to the best by those weights. On ROS 2 the library's context topics are
    read (docs/context.md): a component whose 'when' conditions fail for --dwell seconds is
    replanned away, as a failed one is; a topic silent for --context-silence is said.
    With --apply, a failed component without which no configuration is left is restarted in
    place at once whatever --restarts says (a hold would leave the robot down), then after
    1, 2, 4 ... s up to --hold while it keeps failing. A node process that exits before it
    is ready is logged as failed with its exit status and the last lines of its log (ROS 2).
    """

    if context_lost not in ("keep", "fail"):
        raise UsageError(f"--context-lost {context_lost}: write keep or fail")
    sel = select(library, schema, None, [only] if only else None)
    target = one_target(sel, configuration)
    tasks = Tasks({s.name: s for s in select(library, schema).schemas})  # all it may switch to
    for name in fail or []:
        if name not in sel.library:
            raise UsageError(f"--fail {name}: no such component")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    options = WatchOptions(
        apply=apply,
        stand_ins=stand_ins,
        settle=settle,
        restart_limit=restarts,
        restart_window=restart_window,
        hold=hold,
        prefer_after=prefer_after,
        budget=Budget(search_limit, search_time),
        prefer=tuple(weights_of(prefer, sel.library, "--prefer").items()),
        context=ContextOptions(dwell, context_silence, context_lost == "fail"),
        ros2=Ros2Options(standby, ros2_launch, stop_outside, force, face, face_name),
    )
    timeout, max_bytes = master_timeout, max_answer_mb << 20
    source, release = watch_source(
        master,
        ros2,
        domain,
        distro,
        env,
        options,
        timeout=timeout,
        max_bytes=max_bytes,
        on_note=_note,
    )
    try:  # a refusal below closes the source at once: nothing left for the exit to wait on
        keep = _launch_dir(env, release) if apply else None
    except BaseException:
        source.close()
        raise
    with ExitStack() as stack:
        signals = stack.enter_context(stop_on_signals())
        stack.callback(source.close)
        if release is not None:
            stack.callback(release)
        if keep is not None:
            stack.callback(_remove_if_empty, keep)
        log_file: IO[str] | None = None
        if json_log is not None:
            log_file = stack.enter_context(json_log.open("a", encoding="utf-8"))

        def log(event: Event) -> None:
            stderr.print(event_line(event), markup=False)
            if log_file is not None:
                log_file.write(event_json(event))
                log_file.flush()

        work = stack.enter_context(private_workdir())
        sch, config = target.schema, target.configuration
        context = _context(sel.library, options, ros2)
        watcher = Watcher(
            source,
            sel.library,
            sch,
            config,
            work,
            env,
            log,
            replace(options, launch_dir=keep),
            failed=set(fail or []),
            stop_requested=signals.requested,
            tasks=tasks,
            context=context,
        )
        stack.callback(tasks.close)  # after the watcher's close: the face says its last words
        stack.callback(watcher.close)
        if ros2 and (face or context is not None):
            _open_face(options, env, work / "face.log", tasks, context, stack)
        what = (
            f"and repairing (launch files kept in {keep})"
            if apply
            else "(not repairing: no --apply)"
        )
        log(
            Event(
                "started",
                f"watching {sch.display_name} on {source.uri} {what}: "
                f"{', '.join(config.components)}",
                {"configuration": config.shown},
            )
        )
        stop_freezing()  # it runs on: a pause's freeze would keep the garbage cycles of then
        check = poll(watcher, interval, once=once)
        if signals.signum is not None:
            raise typer.Exit(128 + signals.signum)
        raise typer.Exit(ExitCode.OK if check.ok else ExitCode.FAILED)


def _context(library: ComponentLibrary, options: WatchOptions, ros2: bool) -> LiveContext | None:
    """Return the context to read live: ROS 2 only (its face node subscribes to the topics)."""
    if not library.context:
        return None
    if not ros2:
        _note("note: context is read live on ROS 2 only: its conditions are taken to hold")
        return None
    o = options.context
    return LiveContext(library, o.dwell, o.silence, o.lost_fails)


def _open_face(
    options: WatchOptions,
    env: dict[str, str],
    log: Path,
    tasks: Tasks,
    context: LiveContext | None,
    stack: ExitStack,
) -> None:
    """Start the ROS 2 face (or, with --no-face, a node reading context alone); without it,
    say why and watch all the same."""
    try:
        face = open_face(options, env, log, tasks, context)
    except ExternalToolError as exc:
        lost = "; context is not read: its conditions are taken to hold" if context else ""
        _note(f"note: no ROS 2 face: {exc}{lost}")
        return
    if context is not None:
        context.listening()
    if options.ros2.face:
        tasks.faces.append(face)
    else:
        stack.callback(face.close)


def _note(text: str) -> None:
    """Say what a ROS 2 read left out, or a domain claim not made (on stderr)."""
    stderr.print(text, markup=False)


def _launch_dir(env: dict[str, str], release: Callable[[], None] | None) -> Path:
    """Make the directory launch files and launch output are kept in (``--apply``).

    Raises:
        UsageError: it cannot be made (exit 2; the domain's claim is released first).
    """
    try:
        return launch_log_dir(env)
    except OSError as exc:
        if release is not None:
            release()
        where = exc.filename or "ROS's log directory"
        msg = f"{where}: cannot make a directory for launch files: {exc.strerror}"
        raise UsageError(f"{msg} (set ROS_LOG_DIR to a writable directory)") from None


def _remove_if_empty(path: Path) -> None:
    """Remove the launch directory watch made if nothing was launched (rmdir refuses else)."""
    with contextlib.suppress(OSError):
        path.rmdir()
