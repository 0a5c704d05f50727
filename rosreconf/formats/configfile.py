"""Read and write configuration files (what runs, or should run, per schema).

A configuration file is either

* the JSON that ``rosreconf enumerate --json`` or ``rosreconf plan --json`` prints: for every
  schema in it, its *first* configuration is taken (``plan`` puts the new configuration
  first), or
* a small YAML/JSON document written by hand or by ``rosreconf plan -o``::

      format: rosreconf/configuration
      version: 1
      configurations:
        object_repositioning: {base_joint: NSM1, shoulder_joint: NSM2, ...}

An optional role left empty is ``null`` there (or left out).

Whether a configuration is *valid* is not decided here (see ``rosreconf.model.validity``).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rosreconf import jsonout
from rosreconf.errors import InvalidInputError, Problem, UsageError
from rosreconf.formats import yamlsource as ys
from rosreconf.model import EMPTY, Span

FORMAT = "rosreconf/configuration"


def read_configurations(path: Path) -> dict[str, dict[str, str]]:
    """Return schema name -> (role -> component) from a configuration file.

    Raises:
        UsageError: the file cannot be read.
        InvalidInputError: the file is not one of the accepted shapes.
    """
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise UsageError(f"{path}: cannot read: {exc.strerror}") from None
    tree, doc = ys.read(data, str(path))  # JSON is YAML: one parser, positions for errors
    where = tree.span(tree.root) if tree is not None else Span(str(path), 1, 1)
    if isinstance(doc, dict) and doc.get("format") == FORMAT:
        configs = doc.get("configurations")
        if isinstance(configs, dict) and all(_is_assignment(v) for v in configs.values()):
            return {str(k): _roles(v) for k, v in configs.items()}
    elif isinstance(doc, dict) and isinstance(schemas := doc.get("schemas"), list):
        out: dict[str, dict[str, str]] = {}
        for entry in schemas:
            if not isinstance(entry, dict):
                continue
            configs = entry.get("configurations") or []
            if isinstance(configs, list) and configs and isinstance(configs[0], dict):
                assignment = configs[0].get("assignment")
                if _is_assignment(assignment):
                    out[str(entry.get("name"))] = _roles(assignment)
        if out:
            return out
    raise InvalidInputError(
        [
            Problem(
                where,
                "not a configuration file",
                f"give the JSON of 'rosreconf enumerate --json' or 'plan --json', or a "
                f"document with 'format: {FORMAT}' and 'configurations: {{schema: {{role: "
                "component}}}'",
                code="not-a-configuration",
            )
        ]
    )


def _is_assignment(value: Any) -> bool:
    return isinstance(value, dict) and all(
        isinstance(k, str) and (isinstance(v, str) or v is None) for k, v in value.items()
    )


def _roles(assignment: Any) -> dict[str, str]:
    """Return role -> component; ``null`` (an optional role left empty) becomes ``EMPTY``."""
    return {str(r): EMPTY if c is None else str(c) for r, c in assignment.items()}


def render_configurations(configs: Mapping[str, Mapping[str, str]]) -> str:
    """Return a configuration document (JSON, which is also YAML) for ``configs``."""
    doc = {
        "format": FORMAT,
        "version": 1,
        "configurations": {s: dict(a) for s, a in configs.items()},
    }
    return jsonout.dumps(doc, indent=2) + "\n"
