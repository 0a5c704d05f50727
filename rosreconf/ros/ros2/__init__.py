"""ROS 2: read a graph from DDS discovery without ROS 2 installed (extra ``rosreconf[ros2]``),
and act on it: node processes, lifecycle transitions, standby (``actuator``, ``launching``).
"""
