"""Read a ROS 2 graph from DDS discovery, without ROS 2 installed (extra ``rosreconf[ros2]``)."""
