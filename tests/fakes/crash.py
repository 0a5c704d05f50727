#!/usr/bin/env python3
"""Fake planner: die of SIGSEGV like a crashing C++ search (returncode -11), without a core."""

import os
import resource
import signal

from _report import report

report()
resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
os.kill(os.getpid(), signal.SIGSEGV)
