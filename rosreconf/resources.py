"""Find bundled files (example libraries, schemas, templates, JSON Schemas) in one place.

The example data and templates live at the top of the checkout; pyproject.toml maps those
folders into the package as ``rosreconf.libraries``, ``rosreconf.schemas`` and
``rosreconf.templates``, so the same ``importlib.resources`` lookup works from a checkout
(editable install) and from an installed wheel.
"""

from __future__ import annotations

import enum
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path

_CHECKOUT = Path(__file__).resolve().parent.parent

MAX_YAML_BYTES = 64 * 1024 * 1024
"""Largest YAML file rosreconf reads: room for a 10,000-role, 10-candidate library (27 MB as
``rosreconf generate`` writes it). Here, below both, so that the loader that reads files
(``formats.yamlsource.MAX_BYTES``) and ``generate`` that writes them share one limit."""


class Bundle(enum.StrEnum):
    """The folders of bundled files."""

    LIBRARIES = "libraries"
    SCHEMAS = "schemas"
    TEMPLATES = "templates"
    DATA = "data"


def bundled(kind: Bundle, name: str | None = None) -> Traversable:
    """Return the bundled folder ``kind``, or the file ``name`` inside it."""
    root: Traversable
    if kind is Bundle.DATA:
        root = resources.files("rosreconf.data")
    else:
        try:
            root = resources.files(f"rosreconf.{kind.value}")
        except ModuleNotFoundError:
            # Run from a checkout whose folder shadows the installed package (python -m in the
            # repository root): the folders sit beside the package.
            root = _CHECKOUT / kind.value
    return root if name is None else root.joinpath(name)


def bundled_files(kind: Bundle, suffix: str = ".yaml") -> list[Traversable]:
    """Return the bundled files of ``kind`` ending in ``suffix``, sorted by name."""
    return sorted(
        (f for f in bundled(kind).iterdir() if f.is_file() and f.name.endswith(suffix)),
        key=lambda f: f.name,
    )
