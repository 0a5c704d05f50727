"""Talking to running ROS systems (ROS 1 master, ROS 2 over DDS)."""
