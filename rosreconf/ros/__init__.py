"""Stage 6, ROS: the live half. A running system read, compared, watched and repaired.

Three places, imports pointing from each middleware to the core and never back (import-linter
contracts in ``pyproject.toml``; docs/architecture.md, "The live half"):

- this package, the middleware-neutral core: ``livegraph`` is the one document every live
  source produces; ``conformance`` (with ``edgechecks``, ``dangling``, ``liveactions``,
  ``livenames``) compares it with a configuration's ROS-graph (Def. 1, Lemma 4);
  ``importer`` drafts a library from it; ``watcher`` detects failures and re-plans
  (``replanning``, ``lifecycle_faults``, ``events``); ``launchfiles`` writes ROS 1 and ROS 2
  launch XML and ``standin_spec`` what stand-ins act out. ``sources.LiveSource`` and
  ``actuator.Actuator`` are what a middleware implements; ``launcher`` acts through launch
  files;
- ``ros1``: the master's XML-RPC, roslaunch and the rospy stand-in (``ros1/scripts/``);
- ``ros2``: DDS discovery, node processes, lifecycle and standby, and the scripts run by the
  ROS 2 Python (``ros2/scripts/``).

``connect`` opens the source the options name, the one module that knows both middlewares.
"""
