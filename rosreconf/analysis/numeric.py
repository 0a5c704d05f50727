"""Import numpy with its OpenBLAS started on one thread: the simulation's only BLAS setting.

The simulation computes on 5x5 to 30x30 matrices, where BLAS threads only add
synchronisation, so it runs single-threaded (``performance.single_threaded_blas``). Limiting
after the fact is not free, though: numpy's bundled OpenBLAS starts one thread per core when
it is loaded, and on a busy two-core machine those threads' start-up cost 30 to 60 ms of CPU
per process, a twentieth of ``plan``'s whole-process time. OpenBLAS reads
``OPENBLAS_NUM_THREADS`` once, when it is loaded, so the simulation's modules import numpy
from here: if numpy is not loaded yet and the user has not chosen a thread count, the
variable is set to 1 for the import and removed right after. Nothing else sees it: programs
started later (planners, ROS nodes) inherit the environment as it was. A program that
imports the simulation before numpy gets a single-threaded OpenBLAS, as the simulation would
set anyway; ``threadpoolctl.threadpool_limits`` raises it again.
"""

from __future__ import annotations

import os
import sys

THREADS_VARIABLE = "OPENBLAS_NUM_THREADS"
"""What OpenBLAS reads, once, when it is loaded (numpy's wheels bundle OpenBLAS)."""

if "numpy" not in sys.modules and THREADS_VARIABLE not in os.environ:
    os.environ[THREADS_VARIABLE] = "1"
    try:
        import numpy as np
    finally:
        del os.environ[THREADS_VARIABLE]
else:
    import numpy as np

__all__ = ["np"]
