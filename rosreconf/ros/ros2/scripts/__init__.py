"""Scripts run by the ROS 2 Python (which has rclpy), found by path; never imported."""
