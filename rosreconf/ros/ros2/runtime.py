"""Find what running ROS 2 nodes needs here: a Python with rclpy, executables, lease settings.

rosreconf's own environment has no rclpy (it reads DDS with cyclonedds); what it starts as a
ROS 2 node (a stand-in, a lifecycle agent) runs under a Python that has it:
``ROSRECONF_ROS2_PYTHON``, else the first ``python3`` on PATH that imports rclpy. A
component's real executable is found as ``ros2 run`` finds it: the package is a file
``share/ament_index/resource_index/packages/<package>`` under a prefix of
``AMENT_PREFIX_PATH``, and the program is ``<prefix>/lib/<package>/<executable>``.

Processes rosreconf starts get a Fast DDS XML profile with a short participant lease
(``lease_profile``), so that another reader (``inspect``, a second ``watch``) sees them go
within seconds when they are killed; rosreconf itself sees its own processes exit at once.

rosreconf's own participants (stand-ins, the lifecycle agent) use Fast DDS's UDP transport
only (``own_participant_env``), never its shared memory: see ``OWN_TRANSPORTS``; and no
XTypes type lookup service (``own_profile``): see ``NO_TYPE_LOOKUP``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Mapping, Sequence
from pathlib import Path

from rosreconf.errors import ExternalToolError
from rosreconf.procs import run_program
from rosreconf.procs.child import ALIVE_PIPES, LINUX, preexec, release

PYTHON_ENV = "ROSRECONF_ROS2_PYTHON"
HOW_TO_GET_ONE = (
    "set ROSRECONF_ROS2_PYTHON to a Python that has rclpy, or put one first on PATH "
    "(a ROS 2 install's 'source /opt/ros/<distro>/setup.bash', or from PyPI: "
    "python3 -m venv ros2 && ros2/bin/pip install 'ros-jazzy-rclpy[fastrtps]==7.1.6' "
    "ros-jazzy-std-msgs ros-jazzy-std-srvs ros-jazzy-lifecycle-msgs; see docs/live.md)"
)
ANSWER_SECONDS = 10.0
"""How long a ROS 2 Python may take to answer the rclpy check, and a helper to say it is ready.

Measured here at a load of 4.5 on two cores: the check 0.15 s, the stand-in zygote 0.8 s, the
lifecycle agent 0.5 s. A Python or helper that hangs is named after this, not after a minute.
"""
LEASE_SECONDS = 2.0
"""The participant lease of the processes rosreconf starts (Fast DDS's default is 20 s)."""
FIND_RCLPY = "import importlib.util, sys; sys.exit(importlib.util.find_spec('rclpy') is None)"
"""Finding rclpy without importing it (its C extension takes a second to load)."""
_FOUND: dict[tuple[str | None, str | None], str] = {}
TRANSPORTS_ENV = "FASTDDS_BUILTIN_TRANSPORTS"
OWN_TRANSPORTS = "UDPv4"
"""The Fast DDS transports of rosreconf's own participants (Fast DDS 2.13+ reads the variable).

Fast DDS's shared-memory transport keeps one file per port in /dev/shm for the whole host,
whatever the domain. A participant killed while it creates a port's file leaves it 0 bytes
long, and every later participant that picks that port waits in boost.interprocess's
open-or-create for it to be initialised, for ever (seen here: ten stand-ins stuck in
``rcl_node_init`` on ``/dev/shm/fastrtps_port7013``, made 1 h 40 min before; Fast DDS's own
``fastdds shm clean`` removes only ports with a lock file, which this one never got).
rosreconf kills its stand-ins when it stops them, at any moment, so they must neither leave
such a file nor wait on one; on UDP they talk to SHM participants all the same. The team's own
executables keep whatever transports their environment gives them.
"""


NO_TYPE_LOOKUP = """
        <propertiesPolicy>
          <properties>
            <property>
              <name>fastdds.type_propagation</name>
              <value>disabled</value>
            </property>
          </properties>
        </propertiesPolicy>"""
"""The XML that keeps one of rosreconf's participants from running XTypes type lookup.

Fast DDS 3 (Kilted) runs a type lookup service in every participant by default: each
endpoint it discovers with a type it has not registered makes it ask the remote participant
for that type, and two threads of its own (``dds.tls.request``, ``dds.tls.replies``) serve
and take the answers. In Fast DDS 3.2.3 (and on its main branch of 2026-08-20) the
reply thread reads the table of pending callbacks (``TypeLookupManager::notify_callbacks``)
without the lock under which the discovery thread adds to it
(``check_type_identifier_received``): a stand-in that discovers many endpoints while it
starts, as during a repair, sometimes dies of SIGSEGV in that thread (its Python stack shows
whatever the main thread was doing: ``create_node``, ``create_service``). Measured with
``benchmarks/standin_starts.py`` (see docs/live.md). rosreconf's participants need none of
it: ROS 2 matches endpoints by type name and type hash, and a Fast DDS 3 endpoint without
type information is matched by type name. Fast DDS 2 (Jazzy) knows no such property and
ignores it. The team's own executables keep whatever their environment gives them.
"""


def own_participant_env(env: Mapping[str, str]) -> dict[str, str]:
    """Return ``env`` for one of rosreconf's own participants: UDP only, unless the user said.

    See ``OWN_TRANSPORTS`` for why; a ``FASTDDS_BUILTIN_TRANSPORTS`` the user set is kept.
    """
    out = dict(env)
    out.setdefault(TRANSPORTS_ENV, OWN_TRANSPORTS)
    return out


def ros2_python(env: Mapping[str, str]) -> str:
    """Return the Python that runs rosreconf's ROS 2 helpers (see the module docstring).

    Raises:
        ExternalToolError: none is found (exit 3), with how to get one.
    """
    key = (env.get(PYTHON_ENV), env.get("PATH"))
    if key in _FOUND:
        return _FOUND[key]
    named = env.get(PYTHON_ENV)
    if named:
        path = shutil.which(named, path=env.get("PATH")) or named
        if not os.access(path, os.X_OK):
            raise ExternalToolError(f"{PYTHON_ENV}={named}: no such executable ({HOW_TO_GET_ONE})")
        _check_rclpy(path, env, f"{PYTHON_ENV}={named}")
        _FOUND[key] = path
        return path
    for folder in (env.get("PATH") or "").split(os.pathsep):
        path = os.path.join(folder or ".", "python3")
        if os.access(path, os.X_OK) and _imports_rclpy(path, env):
            _FOUND[key] = path
            return path
    raise ExternalToolError(f"no python3 on PATH imports rclpy: {HOW_TO_GET_ONE}")


def _check_rclpy(python: str, env: Mapping[str, str], named: str) -> None:
    """Make sure the named ``python`` finds rclpy; say how it failed, naming it.

    Raises:
        ExternalToolError: it hangs (no answer within ``ANSWER_SECONDS``), or it answered
            without rclpy (with the last line of its error output).
    """
    result = run_program([python, "-c", FIND_RCLPY], timeout=ANSWER_SECONDS, env=env)
    if result.timed_out:
        raise ExternalToolError(
            f"{named} did not answer within {ANSWER_SECONDS:g} s when asked to find rclpy "
            f"(it hangs): {HOW_TO_GET_ONE}"
        )
    if not result.ok:
        said = (result.stderr.strip().splitlines() or ["no error output"])[-1][:200]
        how = "rclpy not found" if result.returncode == 1 and not result.stderr.strip() else said
        raise ExternalToolError(f"{named} cannot import rclpy ({how}; {HOW_TO_GET_ONE})")


def _imports_rclpy(python: str, env: Mapping[str, str]) -> bool:
    """Tell whether ``python`` can import rclpy (one short run of it)."""
    return run_program([python, "-c", FIND_RCLPY], timeout=ANSWER_SECONDS, env=env).ok


def start_helper(
    argv: Sequence[str], env: Mapping[str, str], log: Path, keep_fds: Sequence[int] = ()
) -> tuple[subprocess.Popen[bytes], int]:
    """Start one of rosreconf's ROS 2 helpers: JSON lines on its stdin and stdout.

    Its stderr goes to ``log``. It gets a new session, a parent-death signal and a group
    watchdog (``rosreconf.procs.child``), so it dies with rosreconf even on SIGKILL, and
    rosreconf's own transports (``own_participant_env``); ``keep_fds`` are passed on. Returns
    the process and the watchdog pipe's write end (``release`` it once the helper is dead).

    Raises:
        ExternalToolError: the program cannot be run.
    """
    alive_read, alive = os.pipe() if LINUX else (-1, -1)
    with log.open("ab") as err:
        try:
            process = subprocess.Popen(
                list(argv),
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=err,
                env=own_participant_env(env),
                start_new_session=True,
                pass_fds=((alive_read,) if LINUX else ()) + tuple(keep_fds),
                preexec_fn=preexec(None, None, alive_read),
            )
        except OSError as exc:
            release(alive)
            raise ExternalToolError(f"cannot run {argv[0]}: {exc.strerror or exc}") from exc
        finally:
            if LINUX:
                os.close(alive_read)
    if LINUX:
        ALIVE_PIPES.append(alive)
    return process, alive


def ament_executable(package: str, executable: str, env: Mapping[str, str]) -> Path:
    """Return ``<prefix>/lib/<package>/<executable>`` as ``ros2 run`` finds it.

    Raises:
        ExternalToolError: no prefix of AMENT_PREFIX_PATH has the package or the program.
    """
    prefixes = [p for p in (env.get("AMENT_PREFIX_PATH") or "").split(os.pathsep) if p]
    for prefix in prefixes:
        marker = Path(prefix, "share", "ament_index", "resource_index", "packages", package)
        if marker.is_file():
            program = Path(prefix, "lib", package, executable)
            if program.is_file() and os.access(program, os.X_OK):
                return program
            raise ExternalToolError(
                f"package {package} (in {prefix}) has no executable {executable} "
                f"(looked for {program})"
            )
    where = ", ".join(prefixes) if prefixes else "AMENT_PREFIX_PATH is empty"
    raise ExternalToolError(
        f"ROS 2 package {package} was not found ({where}): source the workspace that "
        "builds it, or use --stand-ins"
    )


def lease_profile(lease: float = LEASE_SECONDS, *, own: bool = False) -> str:
    """Return a Fast DDS XML profile giving every participant a ``lease`` s lease.

    The participant announces itself three times per lease. Fast DDS 2 (Jazzy) reads it from
    ``FASTRTPS_DEFAULT_PROFILES_FILE``, Fast DDS 3 (Kilted) from
    ``FASTDDS_DEFAULT_PROFILES_FILE``. ``own``: the profile of rosreconf's own participants,
    which also run no type lookup service (``NO_TYPE_LOOKUP``).
    """
    sec, nsec = int(lease), int(lease % 1 * 1e9)
    asec, ansec = int(lease / 3), int(lease / 3 % 1 * 1e9)
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <participant profile_name="rosreconf_short_lease" is_default_profile="true">
      <rtps>
        <builtin>
          <discovery_config>
            <leaseDuration><sec>{sec}</sec><nanosec>{nsec}</nanosec></leaseDuration>
            <leaseAnnouncement><sec>{asec}</sec><nanosec>{ansec}</nanosec></leaseAnnouncement>
          </discovery_config>
        </builtin>{NO_TYPE_LOOKUP if own else ""}
      </rtps>
    </participant>
  </profiles>
</dds>
"""


def own_profile(directory: Path, lease: float = LEASE_SECONDS) -> Path:
    """Write the Fast DDS profile of rosreconf's own participants in ``directory``; return it.

    The short lease (``lease_profile``) and no type lookup service (``NO_TYPE_LOOKUP``).
    """
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / "fastdds-own-participants.xml"
    path.write_text(lease_profile(lease, own=True), encoding="utf-8")
    return path


def node_env(env: Mapping[str, str], profile: Path) -> dict[str, str]:
    """Return ``env`` for a node rosreconf starts: the short-lease profile, a log directory.

    A profile the user named already is kept (theirs wins). rclpy needs HOME or ROS_LOG_DIR.
    """
    out = dict(env)
    for name in ("FASTRTPS_DEFAULT_PROFILES_FILE", "FASTDDS_DEFAULT_PROFILES_FILE"):
        out.setdefault(name, str(profile))
    if not out.get("HOME") and not out.get("ROS_LOG_DIR"):
        out["ROS_LOG_DIR"] = str(profile.parent)
    return out
