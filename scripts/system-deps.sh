#!/usr/bin/env bash
# Install the Debian packages rosreconf's tests use, only those that are missing.
# Needs root (CI and the development machines run as root); otherwise prints the command.
#   graphviz            dot, for the DOT reports
#   python3-roslaunch   roscore, rosmaster, roslaunch and rosout (ROS 1 from Debian, docs/ros.md)
#   python3-rospy       rospy (and std_msgs) for /usr/bin/python3, run by tests/standin_node.py
#   python3-std-srvs    std_srvs/Trigger, the stand-ins' service type
#   gcc                 builds the tests' fault injector (tests/faults/drop_received.c)
#   gdb                 a diagnosis only: the thread stacks of a ROS 2 node that fails beside a
#                       test's kill without being touched (tests/ros2_harness.thread_stacks)
set -euo pipefail
need=()
command -v dot >/dev/null 2>&1 || need+=(graphviz)
command -v roscore >/dev/null 2>&1 || need+=(python3-roslaunch)
/usr/bin/python3 -c 'import roslaunch.xmlloader' >/dev/null 2>&1 || need+=(python3-roslaunch)
/usr/bin/python3 -c 'import rospy' >/dev/null 2>&1 || need+=(python3-rospy)
/usr/bin/python3 -c 'import std_srvs.srv' >/dev/null 2>&1 || need+=(python3-std-srvs)
command -v gcc >/dev/null 2>&1 || need+=(gcc)
command -v gdb >/dev/null 2>&1 || need+=(gdb)
if [ ${#need[@]} -eq 0 ]; then
  echo "system-deps: all present"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "system-deps: missing ${need[*]}; run: sudo apt-get install -y ${need[*]}" >&2
  exit 1
fi
echo "system-deps: installing ${need[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
