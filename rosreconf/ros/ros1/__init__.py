"""ROS 1: the master's XML-RPC, roslaunch, and rosreconf's rospy stand-in (in ``scripts/``)."""
