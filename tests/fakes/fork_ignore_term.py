#!/usr/bin/env python3
"""Fake planner: fork a child that ignores SIGTERM, then both hang (tests killing the group)."""

import os
import signal
import time

from _report import report

ready_read, ready_write = os.pipe()
child = os.fork()
if child == 0:
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    os.write(ready_write, b"x")
    while True:
        time.sleep(60)
os.read(ready_read, 1)  # the child ignores SIGTERM from here on
report(os.getpid(), child)
if os.environ.get("FAKE_PARENT_EXITS"):
    raise SystemExit(0)  # leave the child behind, still holding our stdout
while True:
    time.sleep(60)
