#!/usr/bin/env python3
"""Fake planner: start, report, then hang until killed (tests the wall-clock timeout)."""

import time

from _report import report

report()
while True:
    time.sleep(60)
