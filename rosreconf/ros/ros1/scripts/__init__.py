"""Scripts run by Debian's ``/usr/bin/python3`` (which has rospy), found by path; never imported."""
