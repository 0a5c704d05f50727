#!/usr/bin/env python3
"""Fake anytime planner: write two complete plans, start a third, then hang until stopped."""

import sys
import time

from _report import plan_file, report

prefix = plan_file(sys.argv)
with open(prefix + ".1", "w", encoding="utf-8") as plan:
    plan.write("(pick sensor cam_a power image)\n(pick driver base_b path motion)\n")
    plan.write("; cost = 15 (general cost)\n")
with open(prefix + ".2", "w", encoding="utf-8") as plan:
    plan.write("(pick sensor cam_b power image)\n; cost = 1 (general cost)\n")
with open(prefix + ".3", "w", encoding="utf-8") as plan:
    plan.write("(pick sensor")
report()
while True:
    time.sleep(60)
