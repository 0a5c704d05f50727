"""Run a ROS 2 node script whose executor stops for good on SIGUSR1: a hang a process shows not.

A fault injector for the tests, named as such: a real node whose callback never returns (a
deadlock, a blocking call) keeps its process running (state ``S``, not ``T``) and its DDS
participant alive, but answers no service. Nothing a real node can be told to do shows that
on demand, so this wrapper installs a SIGUSR1 handler that sleeps in the main thread (where
rclpy's executor runs) and then runs the script given, with its arguments, as ``__main__``::

    python tests/ros2_hang_on_usr1.py rosreconf/ros/ros2/scripts/standin_node.py SPEC ...
"""

from __future__ import annotations

import runpy
import signal
import sys
import time

signal.signal(signal.SIGUSR1, lambda *_: time.sleep(1e9))  # the executor runs no more
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
