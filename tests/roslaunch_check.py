#!/usr/bin/python3
"""Check ROS 1 launch files with the real roslaunch parser, without starting anything.

Run it with the system Python (``/usr/bin/python3``, python3-roslaunch from Debian)::

    /usr/bin/python3 tests/roslaunch_check.py FILE.launch...

It loads each file the way ``roslaunch`` does (``XmlLoader`` into a ``ROSLaunchConfig``,
then ``assign_machines``), which checks XML syntax, required attributes, node names,
duplicate names and typed params, but never looks the packages up: ``<node pkg=...>`` may
name packages that are not installed. What roslaunch only warns about (unknown tags and
attributes) is collected as ``warnings``. Prints one JSON document::

    {"files": [{"file": ..., "error": null | "...", "warnings": [...],
                "nodes": [{"name": "/ns/n", "package": ..., "type": ..., "remap": [[a, b]]}],
                "params": {"/ns/n/gain": 2.5}}]}

Exit status: 0 when every file loaded without errors or warnings, 1 otherwise, 2 on usage.
"""

from __future__ import annotations

import json
import sys
from typing import Any

import roslaunch.config
import roslaunch.core
import roslaunch.xmlloader
import rospkg.common


def check(path: str) -> dict[str, Any]:
    """Load one launch file and report its nodes, params, error and warnings."""
    config = roslaunch.config.ROSLaunchConfig()
    loader = roslaunch.xmlloader.XmlLoader(resolve_anon=False)
    report: dict[str, Any] = {"file": path, "error": None, "warnings": [], "nodes": []}
    try:
        loader.load(path, config, verbose=False)
        config.assign_machines()
    except (roslaunch.core.RLException, rospkg.common.ResourceNotFound, OSError) as e:
        kind = "package not found: " if isinstance(e, rospkg.common.ResourceNotFound) else ""
        report["error"] = kind + str(e).strip()
    report["warnings"] = [str(w) for w in config.config_errors]
    report["nodes"] = [
        {
            "name": (n.namespace or "/") + n.name,
            "package": n.package,
            "type": n.type,
            "remap": [list(r) for r in n.remap_args],
        }
        for n in config.nodes
    ]
    report["params"] = {k: p.value for k, p in sorted(config.params.items())}
    return report


def main(argv: list[str]) -> int:
    """Check every file named on the command line; print the JSON report."""
    if len(argv) < 2:
        print(f"usage: {argv[0]} FILE.launch...", file=sys.stderr)
        return 2
    reports = [check(path) for path in argv[1:]]
    print(json.dumps({"files": reports}, indent=2, default=str))
    return 0 if all(r["error"] is None and not r["warnings"] for r in reports) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
