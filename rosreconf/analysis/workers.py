"""Choose where sweeps run: in process, in local worker processes, or on a Dask cluster.

The sweeps (``simulate``, ``whatif``) are embarrassingly parallel and hand out their units of
work through the ``concurrent.futures.Executor`` interface only. A process pool is one such
executor; a Dask distributed client offers another (``Client.get_executor()``), so a sweep
runs on a cluster without knowing it. ``distributed`` is an optional extra
(``rosreconf[dask]``) and is imported only when a cluster address is given.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from typing import TYPE_CHECKING

from rosreconf.errors import ExternalToolError, UsageError

if TYPE_CHECKING:
    from concurrent.futures import Executor

CONNECT_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler to answer before giving up (exit 3)."""


@contextlib.contextmanager
def executor(workers: int | None = None, cluster: str | None = None) -> Iterator[Executor | None]:
    """Yield the executor for ``--workers N`` / ``--cluster ADDRESS`` (None: in process).

    Without a cluster, ``workers`` local processes are used (default one per core); one
    worker means in process, with no pool to start.

    Raises:
        UsageError: both were given.
        ExternalToolError: ``distributed`` is missing or the scheduler cannot be reached.
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
    # Imported here: the process pool imports multiprocessing, which a command that
    # simulates in process (plan, watch, --workers 1) never uses.
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=n) as pool:
        yield pool


@contextlib.contextmanager
def _dask(address: str) -> Iterator[Executor]:
    try:
        import distributed
    except ImportError:
        raise ExternalToolError(
            "--cluster needs Dask's distributed package (pip install 'rosreconf[dask]')"
        ) from None
    try:
        client = distributed.Client(  # type: ignore[no-untyped-call]
            address, timeout=CONNECT_TIMEOUT, set_as_default=False
        )
    except (OSError, TimeoutError, ValueError) as exc:
        raise ExternalToolError(
            f"--cluster {address}: cannot reach the scheduler ({exc})"
        ) from None
    try:
        yield client.get_executor()  # type: ignore[no-untyped-call]
    finally:
        client.close()  # type: ignore[no-untyped-call]
