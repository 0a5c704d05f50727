"""Choose where sweeps run: in process, in local worker processes, or on a Dask cluster.

The sweeps (``simulate``, ``whatif``) are embarrassingly parallel and hand out their units of
work through the ``concurrent.futures.Executor`` interface only. A process pool is one such
executor; a Dask distributed client offers another (``Client.get_executor()``), so a sweep
runs on a cluster without knowing it. ``distributed`` is an optional extra
(``rosreconf[dask]``) and is imported only when a cluster address is given.

Both are handed out wrapped in ``Watched``, which owns how work is stopped and how the
executor's own faults end a sweep:

- local workers die with rosreconf (parent-death signal, ``procs.pool_worker_setup``), ignore
  a terminal's Ctrl-C (rosreconf decides), and are killed at once when the sweep ends by an
  exception, Ctrl-C or SIGTERM (``Terminated``), instead of finishing the queued work first;
- a Ctrl-C or SIGTERM is raised in rosreconf only outside the futures' locks (``submit`` and
  ``results.Results`` keep it until they end: ``procs.stops_deferrable``), so none stays taken;
- a worker that dies (killed, out of memory) ends the sweep with ``ExternalToolError``;
- on a Dask cluster, a lost scheduler, cancelled work, and a cluster that stays without any
  worker (or does not answer) for ``LOST_TIMEOUT`` seconds end the sweep with
  ``ExternalToolError`` (exit 3), never a hang.
"""

from __future__ import annotations

import contextlib
import functools
import importlib.util
import logging
import os
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures import BrokenExecutor, CancelledError, Executor, Future, InvalidStateError
from typing import Any, ParamSpec, TypeVar

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.procs import (
    pool_worker_setup,
    sigterm_raises,
    stops_deferrable,
    stops_deferred,
    stops_held,
)

P = ParamSpec("P")
T = TypeVar("T")

CONNECT_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler to answer before giving up (exit 3)."""
LOST_TIMEOUT = 30.0
"""Seconds a sweep waits for a Dask cluster that has no worker or does not answer before it
gives up (exit 3); a scheduler that closes its connection ends the sweep at once."""
CLOSE_TIMEOUT = 5.0
"""Seconds to wait for a Dask client to close (its scheduler may be gone)."""
POLL_SECONDS = 1.0
"""How often the cluster's health is checked while work is pending."""
CLUSTER_SCHEMES = ("tcp://", "tls://", "ws://", "wss://", "ucx://")
"""Address schemes Dask's comm layer knows; anything else is refused before connecting (a
bare HOST:PORT is Dask's tcp://)."""


Health = Callable[[], str | None]
"""Say what is wrong with the executor's cluster (None: healthy); called from a thread."""


class Watched(Executor):
    """Hand work to another executor, turning its faults into ``ExternalToolError`` (exit 3).

    The futures handed out are this class's own: each one takes its inner future's result,
    or the error a user should see when the executor failed (not the function): a broken
    process pool, cancelled work, a lost scheduler. With ``health``, a thread checks the
    cluster while work is pending and fails it all after ``patience`` seconds of trouble.
    With ``hold_stops`` (a local pool, which forks its workers in ``submit``), SIGINT and
    SIGTERM wait until each submit is done (``procs.stops_held``).
    """

    def __init__(
        self,
        inner: Executor,
        where: str,
        health: Health | None = None,
        patience: float = 0.0,
        cancelled: Callable[[], str] = lambda: "the work was cancelled",
        *,
        hold_stops: bool = False,
    ) -> None:
        self.inner = inner
        self._hold_stops = hold_stops
        self.where = where
        self._cancelled = cancelled
        self._health = health
        self._patience = patience
        self._pending: dict[Future[Any], Future[Any]] = {}
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._watchdog: threading.Thread | None = None

    def submit(self, fn: Callable[P, T], /, *args: P.args, **kwargs: P.kwargs) -> Future[T]:
        """Submit ``fn(*args, **kwargs)`` to the inner executor; return a future of ours."""
        with stops_deferred():  # a stop is raised once the futures' locks are let go
            outer: Future[T] = Future()
            try:  # a local pool forks its workers in submit: stops wait until it is done
                with stops_held() if self._hold_stops else contextlib.nullcontext():
                    inner = self.inner.submit(fn, *args, **kwargs)
            except (BrokenExecutor, RuntimeError) as exc:
                raise ExternalToolError(f"{self.where}: cannot take more work ({exc})") from None
            with self._lock:
                self._pending[outer] = inner
            inner.add_done_callback(functools.partial(self._settle, outer))
        if self._health is not None and self._watchdog is None:
            self._watchdog = threading.Thread(
                target=self._watch, name="cluster-health", daemon=True
            )
            self._watchdog.start()
        return outer

    def _settle(self, outer: Future[Any], inner: Future[Any]) -> None:
        with self._lock:
            self._pending.pop(outer, None)
        if inner.cancelled():
            _finish(outer, error=ExternalToolError(f"{self.where}: {self._cancelled()}"))
            return
        exc = inner.exception()
        if exc is None:
            _finish(outer, result=inner.result())
        elif isinstance(exc, BrokenExecutor):  # a process pool's worker died
            _finish(
                outer,
                error=ExternalToolError(
                    f"{self.where}: a worker process died (killed, or out of memory)"
                ),
            )
        elif isinstance(exc, (CancelledError, OSError, TimeoutError)) or _dask_fault(exc):
            shown = str(exc).strip() or type(exc).__name__
            _finish(outer, error=ExternalToolError(f"{self.where}: {shown}"))
        else:  # the function's own error: not a fault of the executor
            _finish(outer, error=exc)

    def fail(self, message: str) -> None:
        """End every pending future with ``ExternalToolError(message)`` and cancel its work."""
        with self._lock:
            pending = list(self._pending.items())
            self._pending.clear()
        for outer, inner in pending:
            inner.cancel()
            _finish(outer, error=ExternalToolError(message))

    def _watch(self) -> None:
        """Check the cluster while work is pending; fail it all after ``patience`` of trouble."""
        assert self._health is not None
        since: float | None = None
        while not self._stop.wait(POLL_SECONDS):
            with self._lock:
                busy = bool(self._pending)
            problem = self._health() if busy else None
            if problem is None:
                since = None
                continue
            since = time.monotonic() if since is None else since
            if time.monotonic() - since >= self._patience:
                self.fail(f"{self.where}: {problem} for {self._patience:g} s; gave up")
                since = None

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """Stop the health checks and shut the inner executor down."""
        self._stop.set()
        if cancel_futures:
            self.fail(f"{self.where}: stopped")
        self.inner.shutdown(wait=wait, cancel_futures=cancel_futures)


def _finish(
    future: Future[Any], *, result: object = None, error: BaseException | None = None
) -> None:
    """Settle ``future`` unless it is settled already (the watchdog may have been first)."""
    with contextlib.suppress(InvalidStateError):
        if error is None:
            future.set_result(result)
        else:
            future.set_exception(error)


def _dask_fault(exc: BaseException) -> bool:
    """Tell whether ``exc`` is Dask's way of saying the cluster, not the function, failed."""
    return type(exc).__module__.startswith("distributed") and type(exc).__name__ in {
        "KilledWorker",
        "CommClosedError",
        "FutureCancelledError",
        "FuturesCancelledError",
        "WorkerStartTimeoutError",
    }


@contextlib.contextmanager
def executor(workers: int | None = None, cluster: str | None = None) -> Iterator[Executor | None]:
    """Yield the executor for ``--workers N`` / ``--cluster ADDRESS`` (None: in process).

    Without a cluster, ``workers`` local processes are used (default one per core); one
    worker means in process, with no pool to start.

    Raises:
        UsageError: both were given, or the address is not a Dask address.
        ExternalToolError: ``distributed`` is missing, the scheduler cannot be reached, or
            the pool or cluster failed during the sweep.
    """
    if cluster is not None:
        if workers is not None:
            raise UsageError(
                "--workers and --cluster exclude each other (the cluster's size rules)"
            )
        with _dask(cluster) as pool:
            yield pool
        return
    n = workers or os.cpu_count() or 1
    if n == 1:
        yield None
        return
    with _local(n) as pool:
        yield pool


@contextlib.contextmanager
def _local(n: int) -> Iterator[Executor]:
    """Run ``n`` worker processes that die with rosreconf; kill them if the sweep is stopped."""
    # Imported here: the process pool imports multiprocessing, which a command that
    # simulates in process (plan, watch, --workers 1) never uses.
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(
        max_workers=n, initializer=pool_worker_setup, initargs=(os.getpid(),)
    )
    try:
        with sigterm_raises(), stops_deferrable():
            yield Watched(pool, f"--workers {n}", hold_stops=True)
    except BaseException:  # an error, Ctrl-C or SIGTERM: the queued work is not wanted
        _kill(pool)
        raise
    pool.shutdown(wait=True)


def _kill(pool: Any) -> None:
    """Cancel a process pool's queued work and kill its workers now (SIGKILL).

    The pool's manager thread is joined too: left running, it may close its wake-up pipe
    while the interpreter's exit hook writes to it (3.11's ``_ThreadWakeup`` checks "closed"
    and writes without a lock), and Ctrl-C printed "Exception ignored ... Bad file
    descriptor" after "interrupted" (1 run in 20 of
    test_signal_to_a_sweep_with_workers_leaves_no_worker_running[sigint] here; 0 in 40 since).
    """
    processes = list(dict(getattr(pool, "_processes", None) or {}).values())
    manager = getattr(pool, "_executor_manager_thread", None)  # shutdown forgets it
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        with contextlib.suppress(OSError, ValueError):
            process.kill()
    for process in processes:
        with contextlib.suppress(OSError, ValueError, AssertionError):
            process.join(CLOSE_TIMEOUT)
    if manager is not None:
        manager.join(CLOSE_TIMEOUT)


@contextlib.contextmanager
def _dask(address: str) -> Iterator[Executor]:
    """Connect to the scheduler at ``address``; yield its executor, watched (module doc)."""
    where = f"--cluster {address}"
    try:
        import distributed
    except ImportError:
        raise ExternalToolError(
            "--cluster needs Dask's distributed package (pip install 'rosreconf[dask]')"
        ) from None
    _check_address(distributed, address, where)
    # Its reconnect errors would repeat ours, with tracebacks: only ours is said. Tornado's
    # too: distributed gives "tornado.application" a handler, which printed a CommClosedError
    # traceback ("Exception in callback") when the scheduler was killed mid-sweep (1 fresh
    # clone's CI run in 16).
    quiet = {
        name: logging.getLogger(name)
        for name in ["distributed", "tornado", *logging.root.manager.loggerDict]
        if name.split(".")[0] in ("distributed", "tornado")
    }
    levels = {name: logger.level for name, logger in quiet.items()}
    for logger in quiet.values():
        logger.setLevel(logging.CRITICAL)
    try:
        with sigterm_raises(), stops_deferrable():
            client = _connect(distributed, address, where)
            try:
                yield Watched(
                    client.get_executor(),
                    where,
                    functools.partial(_cluster_health, client),
                    LOST_TIMEOUT,
                    functools.partial(_why_cancelled, client),
                )
            finally:
                with contextlib.suppress(Exception):
                    client.close(timeout=CLOSE_TIMEOUT)
    finally:
        for name, logger in quiet.items():
            logger.setLevel(levels[name])


def _check_address(distributed: Any, address: str, where: str) -> None:
    """Refuse an address Dask would fail on only after a stall (a half-made client's cleanup).

    Raises:
        UsageError: a malformed address, an unknown scheme, no host or no port (exit 2).
        ExternalToolError: ``tls://`` without Dask's TLS settings, or ``ucx://`` without
            its package (exit 3).
    """
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address)
        if scheme == "ucx":
            host, port = location.rpartition(":")[0], 1
        else:
            host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise UsageError(
            f"{where}: not a scheduler address ({exc}; give tcp://HOST:PORT)"
        ) from None
    if f"{scheme}://" not in CLUSTER_SCHEMES:
        raise UsageError(
            f"{where}: unknown scheme {scheme}:// (give tcp://HOST:PORT; known: "
            f"{', '.join(s.removesuffix('://') for s in CLUSTER_SCHEMES)})"
        )
    if not host or not 0 < int(port) < 65536:
        raise UsageError(f"{where}: needs a host and a port from 1 to 65535 (tcp://HOST:PORT)")
    if (
        scheme in ("tls", "wss")
        and distributed.Security().get_connection_args("client").get("ssl_context") is None
    ):
        raise ExternalToolError(
            f"{where}: {scheme}:// needs Dask's TLS settings (certificates under "
            "distributed.comm.tls in the Dask configuration, or DASK_DISTRIBUTED__COMM__TLS__* "
            "variables)"
        )
    if scheme == "ucx" and importlib.util.find_spec("distributed_ucxx") is None:
        raise ExternalToolError(f"{where}: ucx:// needs the distributed-ucxx package")


def _connect(distributed: Any, address: str, where: str) -> Any:
    """Open a client on ``address`` within ``CONNECT_TIMEOUT``, or say why not (exit 3)."""
    try:
        return distributed.Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError) as exc:
        raise ExternalToolError(f"{where}: cannot reach the scheduler ({exc})") from None
    except Exception as exc:  # a scheme without its security or its package (tls, ucx)
        shown = str(exc).strip() or type(exc).__name__
        raise ExternalToolError(f"{where}: cannot connect ({shown})") from None


def _why_cancelled(client: Any) -> str:
    """Say why Dask cancelled our work; cheap, for it runs on the client's event loop."""
    if client.status != "running":
        return "lost the connection to the scheduler (was it stopped?); the sweep was abandoned"
    return "the scheduler cancelled the work (were its workers stopped?); the sweep was abandoned"


def _cluster_health(client: Any) -> str | None:
    """Say what keeps the cluster from working (None: it has a worker and answers)."""
    if client.status != "running":
        return "lost the scheduler"
    try:
        info = client.sync(
            client.scheduler.identity, n_workers=0, callback_timeout=POLL_SECONDS * 5
        )
    except Exception:
        return "the scheduler does not answer"
    if not info.get("n_workers"):
        return "the cluster has no worker"
    return None
