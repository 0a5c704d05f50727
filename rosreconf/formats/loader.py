"""Load component libraries and interoperability schemas from YAML, with positions.

Each file goes through three steps: YAML -> positioned tree and plain data (``yamlsource``),
structure checked against the shipped JSON Schema (``structure``, errors mapped back to
``file:line:column``) and values checked (``values``), then model objects (``build``).
Problems are collected per file and across files; the caller gets the model of every
well-formed file *and* the list of problems, so ``validate`` can report everything in one
run while ``enumerate`` can refuse to work on invalid input.
"""

from __future__ import annotations

import contextlib
import errno
import gc
import os
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import InvalidInputError, Problem, Severity, UsageError
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.build import Interfaces, build_library, build_schema
from rosreconf.formats.checks import check
from rosreconf.formats.structure import DocumentKind, kind_of, structure_problems
from rosreconf.formats.values import duplicate_edges, value_problems
from rosreconf.model import ComponentLibrary, ConfigurationLibrary, InteroperabilitySchema, Span
from rosreconf.outfiles import special_kind
from rosreconf.resources import Bundle, bundled

YAML_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class Source:
    """One input file: its name as shown to the user and its bytes."""

    name: str
    data: bytes
    size: int = -1
    """The file's size when only its first bytes were read (over the limit); else -1."""


@dataclass
class Loaded:
    """What loading a set of files produced: the models that could be built, and problems.

    Attributes:
        libraries: one ComponentLibrary per well-formed library file.
        schemas: one InteroperabilitySchema per well-formed schema file.
        problems: every problem found, in every file.
        files: the names of the files read.
        library_complete: false when a file that is (or may be) a library failed to load, so
            checks needing the whole library must not run.
        note: how the files were chosen, for the user ("bundled example: ...").
    """

    libraries: list[ComponentLibrary] = field(default_factory=list)
    schemas: list[InteroperabilitySchema] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    library_complete: bool = True
    note: str = ""

    @property
    def library(self) -> ComponentLibrary:
        """Return L: all library files joined into one."""
        return ComponentLibrary.merge(self.libraries)

    @property
    def configurations(self) -> ConfigurationLibrary:
        """Return C: all schemas, in file order."""
        return ConfigurationLibrary(tuple(self.schemas))


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


@contextlib.contextmanager
def _paused_gc() -> Iterator[None]:
    """Pause the cyclic garbage collector while a library's tree and model are built.

    Loading only adds objects (trees, plain data, model); reference counting frees the
    trees. Each collection would walk everything loaded so far: at 1000 roles x 10 those
    walks cost more than the loading itself (``rosreconf.solve.factors.paused_gc`` does the
    same for the solvers' tables).

    Then everything alive is frozen (``gc.freeze``): the loaded model lives as long as the
    command, and every object made while the collector was paused sits in its youngest
    generation, so the next three collections would each walk all of it again (0.1 s each
    at 1000 roles, ten times that at 10,000). Frozen objects are still freed by reference
    counting; only a reference cycle made during loading would now outlive its use.
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.freeze()
            gc.enable()


def load_sources(sources: Iterable[Source]) -> Loaded:
    """Parse and build every source, collecting problems instead of stopping at the first."""
    with _paused_gc():
        return _load_sources(sources)


def _load_sources(sources: Iterable[Source]) -> Loaded:
    loaded = Loaded()
    interfaces: Interfaces = {}  # shared by every library file (see build_library)
    for src in sources:
        loaded.files.append(src.name)
        if src.size > ys.MAX_BYTES:
            loaded.problems.append(ys.too_large(src.name, src.size))
            loaded.library_complete = False
            continue
        try:
            tree, plain = ys.parse_plain(src.data, src.name)
        except InvalidInputError as exc:
            loaded.problems.extend(exc.problems)
            loaded.library_complete = False
            continue
        kind, problems = kind_of(tree, src.name)
        if kind is None or tree is None:
            loaded.problems.extend(problems)
            loaded.library_complete = False
            continue
        loaded.problems.extend(todo_marks(src))
        structural = list(structure_problems(tree, kind, plain))
        if not structural and kind is DocumentKind.LIBRARY and isinstance(tree, ys.YMapping):
            structural = value_problems(tree, plain)
        if structural:
            loaded.problems.extend(structural)
            loaded.library_complete &= kind is not DocumentKind.LIBRARY
            continue
        assert isinstance(tree, ys.YMapping)
        if kind is DocumentKind.LIBRARY:
            loaded.libraries.append(build_library(tree, src.name, interfaces))
        else:
            loaded.problems.extend(duplicate_edges(tree))
            loaded.schemas.append(build_schema(tree, src.name))
    return loaded


TODO_MARK = re.compile(rb"#.*?\bTODO\b|\bTODO_\w")
"""A ``# TODO`` comment or a ``TODO_...`` placeholder, as ``rosreconf import`` writes them."""


def todo_marks(src: Source) -> Iterator[Problem]:
    """Yield one warning per line still holding a TODO mark (an unfinished import draft).

    Warnings, not errors: a draft loads and validates, so a person can work through it;
    ``validate --strict`` fails on them, so an unfinished draft cannot pass a strict gate.
    """
    if b"TODO" not in src.data:
        return
    for number, line in enumerate(src.data.splitlines(), start=1):
        found = TODO_MARK.search(line)
        if found is None:
            continue
        column = len(line[: found.start()].decode("utf-8", "replace")) + 1
        yield Problem(
            Span(src.name, number, column),
            "unfinished draft: a TODO mark is left",
            "fill in what it asks for and remove the mark",
            code="todo",
            severity=Severity.WARNING,
        )


def load_paths(paths: Sequence[Path]) -> Loaded:
    """Load the YAML files at ``paths`` (files or folders)."""
    return load_sources(read_sources(discover(paths)))


def load_bundled() -> Loaded:
    """Load the bundled example (the paper's robot arm and the mobile robot)."""
    sources = []
    for kind in (Bundle.LIBRARIES, Bundle.SCHEMAS):
        for f in sorted(bundled(kind).iterdir(), key=lambda t: t.name):
            if f.is_file() and f.name.endswith(YAML_SUFFIXES):
                sources.append(Source(f"<bundled>/{kind.value}/{f.name}", f.read_bytes()))
    loaded = load_sources(sources)
    loaded.note = "no libraries/ or schemas/ here: using the bundled example"
    return loaded


DEFAULT_FOLDERS = (Path("libraries"), Path("schemas"))


def load_selection(paths: Sequence[Path], *, base: Path | None = None) -> Loaded:
    """Load what the user named, else ``libraries/`` and ``schemas/`` here, else the bundle.

    This is the one rule every command uses to pick its input, so that ``rosreconf
    validate``, ``enumerate`` and ``plan`` always look at the same files.
    """
    if paths:
        return load_paths(paths)
    here = base or Path()
    folders = [here / f for f in DEFAULT_FOLDERS if (here / f).is_dir()]
    if folders:
        loaded = load_paths(folders)
        loaded.note = "using " + " and ".join(f"{f.name}/" for f in folders)
        return loaded
    return load_bundled()


def load_split(
    library_paths: Sequence[Path], schema_paths: Sequence[Path], *, base: Path | None = None
) -> Loaded:
    """Load libraries and schemas chosen separately (``--library``/``--schema`` options).

    Whichever side is not given comes from the default rule of ``load_selection``.
    """
    if not library_paths and not schema_paths:
        return load_selection([], base=base)
    if library_paths and schema_paths:  # both given: the defaults are not read at all
        return load_paths([*library_paths, *schema_paths])
    default = load_selection([], base=base)
    given = load_paths([*library_paths, *schema_paths])
    if not library_paths:
        given.libraries = default.libraries + given.libraries
        given.files = [f for f in default.files if "librar" in f] + given.files
    if not schema_paths:
        given.schemas = given.schemas + default.schemas
        given.files = given.files + [f for f in default.files if "schema" in f]
    given.problems += [p for p in default.problems if p not in given.problems]
    return given


def check_loaded(loaded: Loaded) -> list[Problem]:
    """Return the semantic problems of what ``loaded`` holds (see ``rosreconf.formats.checks``)."""
    with _paused_gc():
        return check(loaded.libraries, loaded.schemas, library_complete=loaded.library_complete)


def load_checked(
    library_paths: Sequence[Path] = (),
    schema_paths: Sequence[Path] = (),
    *,
    base: Path | None = None,
) -> Loaded:
    """Load like ``load_split`` and refuse input with any error (for the solvers).

    Raises:
        InvalidInputError: with every structural and semantic error of the files.
    """
    loaded = load_split(library_paths, schema_paths, base=base)
    problems = [*loaded.problems, *check_loaded(loaded)]
    errors = [p for p in problems if p.severity is Severity.ERROR]
    if errors:
        raise InvalidInputError(errors)
    return loaded
