"""Run every external program rosreconf needs (planners, graphviz, roslaunch) the same way.

One function owns the subprocess so that each rule below holds for all of them:

- an argument list, never a shell, so no file or component name is ever interpreted;
- a new session (``start_new_session=True``), so the program and everything it forks form one
  process group that can be signalled as a whole, and a terminal's Ctrl-C reaches rosreconf
  only, which then decides what to stop;
- a wall-clock timeout that stops the whole group: SIGTERM, a short grace, then SIGKILL, which
  also ends children that ignore SIGTERM; a KeyboardInterrupt or SIGTERM that reaches
  rosreconf while it waits stops the group the same way and is then re-raised;
- after every run, whatever is left of the group (a daemon the program forked) is killed;
- the group dies with rosreconf, even when rosreconf is killed with SIGKILL and no cleanup
  code can run (Linux): the program gets ``PR_SET_PDEATHSIG`` (SIGKILL), and because that
  signal reaches only the program and not the workers it forks (Fast Downward's driver runs
  its translator and search as children), a watchdog forked into the group before ``exec``
  waits on a pipe whose only writer is rosreconf; when the pipe closes without a word, the
  watchdog kills the whole group;
- SIGINT has its default action in the program even when rosreconf runs with SIGINT ignored
  (a background job of a script): the program is in its own session, so no terminal's Ctrl-C
  reaches it anyway, and the only SIGINT it ever gets is rosreconf's own request to stop
  (``Background.stop``), which an inherited "ignore" would silently defeat (subprocess's
  ``restore_signals`` does not cover SIGINT);
- optional address-space and CPU-time limits, set with ``setrlimit`` in the child; those, the
  SIGINT reset, the parent-death signal and the watchdog are all the ``preexec_fn`` does;
- stdout and stderr go to anonymous temporary files (no pipe can fill up and block the
  program) and only their last ``max_output_bytes`` are kept;
- an executable that does not exist is a result (``missing``), not an exception, so that a
  planner adapter can say which package to install; ``ProgramResult.check`` turns any failure
  into an ``ExternalToolError`` for callers that only want success.

The modules, one concern each: ``run`` (run a program to its end), ``background`` (own a
long-running one: roslaunch), ``child`` (the setup between fork and exec: parent-death
signal, watchdog, limits; ``pool_worker_setup`` gives local worker processes the same
parent-death signal), ``signals`` (SIGTERM as an exception, signals to groups),
``workdirs`` (private temp dirs), ``procstat`` (read any process's /proc/<pid>/stat, with
its command name intact), ``ladder`` (SIGINT, SIGTERM, SIGKILL in turn, a grace apart, until
the processes have gone; each caller says what is signalled). Import from here: the names
below are the API.
"""

from rosreconf.procs.background import Background, descendants, start_program, stop_all
from rosreconf.procs.child import pool_worker_setup
from rosreconf.procs.procstat import PROC, ProcStat, read_stat
from rosreconf.procs.run import (
    GRACE_SECONDS,
    MAX_OUTPUT_BYTES,
    MISSING_RETURNCODE,
    ProgramResult,
    run_program,
)
from rosreconf.procs.signals import (
    Terminated,
    sigterm_raises,
    stops_deferrable,
    stops_deferred,
    stops_held,
)
from rosreconf.procs.workdirs import WORKDIR_PREFIX, clean_stale_workdirs, private_workdir

__all__ = [
    "GRACE_SECONDS",
    "MAX_OUTPUT_BYTES",
    "MISSING_RETURNCODE",
    "PROC",
    "WORKDIR_PREFIX",
    "Background",
    "ProcStat",
    "ProgramResult",
    "Terminated",
    "clean_stale_workdirs",
    "descendants",
    "pool_worker_setup",
    "private_workdir",
    "read_stat",
    "run_program",
    "sigterm_raises",
    "start_program",
    "stop_all",
    "stops_deferrable",
    "stops_deferred",
    "stops_held",
]
