#!/usr/bin/env python3
"""Fake planner: exit with the code given as the first argument, writing no plan."""

import sys

from _report import report

report()
print("fake planner: exiting with", sys.argv[1])
print("fake planner: the last words of an error", file=sys.stderr)
raise SystemExit(int(sys.argv[1]))
