#!/usr/bin/env python3
"""Fake FF: check the ``-o DOMAIN -f PROBLEM`` command line, print a recorded transcript.

The transcript is the file named by FAKE_FF_TRANSCRIPT and the exit code is FAKE_FF_EXIT (FF
exits 1 for both trivially true and trivially false goals).
"""

import os
import sys
from pathlib import Path

from _report import report

report()
args = sys.argv[1:]
if len(args) != 4 or args[0] != "-o" or args[2] != "-f" or not Path(args[3]).is_file():
    print("fake ff: usage: ff -o DOMAIN -f PROBLEM", file=sys.stderr)
    raise SystemExit(2)
print(Path(os.environ["FAKE_FF_TRANSCRIPT"]).read_text(encoding="utf-8"), end="")
raise SystemExit(int(os.environ.get("FAKE_FF_EXIT", "0")))
