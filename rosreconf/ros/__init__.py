"""Stage 6, ROS: the live graph, conformance, import, watch and launch files.

``livegraph`` is the one document every live source produces; ``rosmaster`` reads it from a
ROS 1 master; ``conformance`` compares it with a configuration's ROS-graph (Def. 1, Lemma 4);
``importer`` drafts a library from it; ``watcher`` detects failures and re-plans;
``launchfiles`` writes ROS 1 and ROS 2 launch XML; ``standins`` starts stand-in nodes.
"""
