#!/usr/bin/env python3
"""Fake planner: write a complete plan whose actions no domain declares, in mixed case."""

import sys

from _report import plan_file, report

report()
with open(plan_file(sys.argv), "w", encoding="utf-8") as plan:
    plan.write("(TELEPORT Robot_1 Nowhere)\n(hover)\n; a comment line\n(Pick  R2   C-9)\n")
    plan.write("; cost = 7 (general cost)\n")
