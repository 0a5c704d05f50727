"""Find the YAML files a command is pointed at and read their bytes, failing clearly.

The first step of loading (``loader``): which files (folders expanded, special files
named for what they are) and their bytes (at most one byte over the parser's limit).
Nothing here parses YAML.
"""

from __future__ import annotations

import errno
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.formats import yamlsource as ys
from rosreconf.outfiles import special_kind

YAML_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class Source:
    """One input file: its name as shown to the user and its bytes."""

    name: str
    data: bytes
    size: int = -1
    """The file's size when only its first bytes were read (over the limit); else -1."""


def discover(paths: Iterable[Path]) -> list[Path]:
    """Expand folders into their YAML files (sorted, recursive); keep files as given.

    A FIFO, a device or a symlink loop is named for what it is, given directly or found in a
    folder under a YAML name: reading one would block, never end, or fail obscurely. A folder
    without YAML files is an error too: a CI job pointed at the wrong folder must fail, not
    report "0 file(s) valid".

    Raises:
        UsageError: a path does not exist, is not a regular file or folder, or a folder holds
            no YAML file.
    """
    out: list[Path] = []
    for p in paths:
        kind = _file_kind(p)
        if kind == "a folder":
            found = []
            for f in sorted(p.rglob("*")):
                if f.suffix not in YAML_SUFFIXES or f.is_dir():
                    continue
                inner = _file_kind(f)
                if inner != "a regular file":
                    raise UsageError(f"{f}: is {inner}, not a YAML file (remove or rename it)")
                found.append(f)
            if not found:
                raise UsageError(
                    f"{p}: folder has no .yaml or .yml files (is it the right folder?)"
                )
            out.extend(found)
        elif kind == "a regular file":
            out.append(p)
        elif kind is None:
            raise UsageError(f"{p}: no such file or folder")
        else:
            raise UsageError(f"{p}: is {kind}, not a YAML file or folder")
    return out


def _file_kind(path: Path) -> str | None:
    """Name what ``path`` is ("a regular file", "a FIFO (named pipe)"...); None if nothing."""
    try:
        info = os.stat(path)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return "a symlink loop"
        if os.path.islink(path):
            return "a broken symlink"
        return None
    return special_kind(info.st_mode)


def read_sources(paths: Iterable[Path]) -> list[Source]:
    """Read files as bytes, at most one byte over the parser's limit, failing clearly.

    Reading stops after ``MAX_BYTES + 1`` bytes, so a 200 MB file costs no more than the limit
    and the parser still reports it as too large (with its real size from ``stat``).
    """
    sources = []
    for p in paths:
        try:
            with open(p, "rb") as f:
                data = f.read(ys.MAX_BYTES + 1)
                size = max(len(data), os.fstat(f.fileno()).st_size)
            sources.append(Source(str(p), data, size))
        except OSError as exc:
            raise UsageError(f"{p}: cannot read: {exc.strerror}") from None
    return sources
