#!/usr/bin/env python3
"""Fake roslaunch whose nodes are slow to stop: it ignores SIGINT and runs on (a fault injector).

A real roslaunch stops on SIGINT by asking each node to stop and waiting up to 15 s for it; on
a loaded machine that took longer than watch's 4 s hard stop (seen once in eight fresh clones,
``test_live_ros``). That cannot be provoked on demand with real nodes, so this stands in for
it: it says it started (as roslaunch's output does), writes its pid next to the launch file,
then ignores SIGINT until it is killed. The pid file is renamed into place, so a reader never
sees it empty (seen once in a fresh clone).
"""

import os
import signal
import sys
import time
from pathlib import Path

signal.signal(signal.SIGINT, signal.SIG_IGN)
launch = Path(sys.argv[-1])
pid_file = launch.parent / f"{launch.stem}.fake-pid"
pid_file.with_suffix(".tmp").write_text(str(os.getpid()))
pid_file.with_suffix(".tmp").replace(pid_file)  # whole or absent: the test reads it at once
print(f"... logging to {launch.parent}", flush=True)
while True:
    time.sleep(60)
