"""roslaunch's output lines are classified by their log level (issue 22): an INFO line that
mentions "error" or "not found" is no ``launch-error``; ERROR/FATAL lines and roslaunch's own
failures (``has died``, ``RLException``) are."""

from __future__ import annotations

from rosreconf.ros.launcher import error_lines

OUTPUT = """\
[INFO] [1700000000.1]: no error: parameter not found, using default
[ INFO] [1700000000.123]: cannot find calibration, using defaults
[ WARN] [1700000000.1]: failed once, retrying
[node-1] [INFO] [17.0]: exception handler installed
INFO: nothing failed
process[x-1]: started with pid [12]
[ERROR] [1700000000.1]: failed to open device
[ FATAL] [17.0]: no such device
ERROR: cannot launch node of type [pkg/x]: x
[x-1] process has died [pid 12, exit code 1]
RLException: Invalid roslaunch XML syntax
"""


def test_roslaunch_info_lines_are_not_launch_errors() -> None:
    assert error_lines(OUTPUT) == [
        "[ERROR] [1700000000.1]: failed to open device",
        "[ FATAL] [17.0]: no such device",
        "ERROR: cannot launch node of type [pkg/x]: x",
        "[x-1] process has died [pid 12, exit code 1]",
        "RLException: Invalid roslaunch XML syntax",
    ]
