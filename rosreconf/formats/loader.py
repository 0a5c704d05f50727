"""Load component libraries and interoperability schemas from YAML, with positions.

Each file is read once into its plain data and a table of where each value is written
(``yamlsource.read``, which also says what is wrong with its YAML), checked (``structure``,
``values``) and built (``build``); a problem is placed by looking its path up in the table
(``positions.Positions``). The caller gets the model of every well-formed file *and* every
problem, so ``validate`` reports everything in one run while ``enumerate`` can refuse to
work on invalid input.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import InvalidInputError, Problem, Severity
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.build import Interfaces, build_library, build_schema
from rosreconf.formats.checks import check
from rosreconf.formats.positions import Positions
from rosreconf.formats.sources import YAML_SUFFIXES, Source, discover, read_sources
from rosreconf.formats.structure import DocumentKind, format_problem, kind_of, structure_problems
from rosreconf.formats.values import duplicate_edges, schema_value_problems, value_problems
from rosreconf.gcpause import paused_gc
from rosreconf.model import ComponentLibrary, ConfigurationLibrary, InteroperabilitySchema, Span
from rosreconf.resources import Bundle, bundled


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


def load_sources(sources: Iterable[Source]) -> Loaded:
    """Parse, check and build every source, collecting problems instead of stopping at the first."""
    loaded = Loaded()
    interfaces: Interfaces = {}  # shared by every library file (see build_library)
    with paused_gc():
        for src in sources:
            loaded.files.append(src.name)
            try:
                if src.size > ys.MAX_BYTES:
                    raise InvalidInputError([ys.too_large(src.name, src.size)])
                _load_one(src, loaded, interfaces)
            except InvalidInputError as exc:
                loaded.problems.extend(exc.problems)
                loaded.library_complete = False
    return loaded


def _load_one(src: Source, loaded: Loaded, interfaces: Interfaces) -> None:
    """Read, check and build one file into ``loaded`` (see the module docstring).

    Raises:
        InvalidInputError: the file is not YAML rosreconf reads, or names no known format.
    """
    found, plain = ys.read(src.data, src.name)  # says what is wrong with the YAML itself
    kind = kind_of(plain)
    if kind is None:
        raise InvalidInputError([format_problem(found, plain, src.name)])
    assert found is not None, "a document that names its format has positions"
    tree: Positions = found
    structural = structure_problems(tree, kind, plain)
    loaded.problems.extend(todo_marks(src))
    if not structural and kind is DocumentKind.LIBRARY:
        structural = value_problems(tree, plain)
    elif not structural:
        structural = schema_value_problems(tree, plain)
    if structural:
        loaded.problems.extend(structural)
        loaded.library_complete &= kind is not DocumentKind.LIBRARY
    elif kind is DocumentKind.LIBRARY:
        loaded.libraries.append(
            build_library(plain, src.name, _ReadAgain(src), interfaces, tree.without_plain())
        )
    else:
        loaded.problems.extend(duplicate_edges(tree, plain))
        loaded.schemas.append(build_schema(plain, tree, src.name))


@dataclass(frozen=True, eq=False)
class _ReadAgain:
    """A library file's positions, read again from the bytes read when a position is first
    asked for (``build._Where``: only a problem asks).

    The library keeps its table without the plain data (``Positions.without_plain``), which
    places what a path names; a position named by a value (``needs.<name>``,
    ``provides.<interface>``) needs the values' text, so the file is read again then. The
    last file read again is kept (``_read_again``), so the problems of one file read it
    once; the bytes are the ones read first, not the file as it is on disk now.
    """

    src: Source

    def __call__(self) -> Positions:
        return _read_again(self)


@functools.lru_cache(maxsize=1)
def _read_again(again: _ReadAgain) -> Positions:
    tree, _ = ys.read(again.src.data, again.src.name)
    assert tree is not None, "it was read with positions before"
    return tree


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
    library_paths: Sequence[Path],
    schema_paths: Sequence[Path],
    *,
    base: Path | None = None,
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
    with paused_gc():
        return check(loaded.libraries, loaded.schemas, library_complete=loaded.library_complete)


def problems_of(loaded: Loaded, *, errors_only: bool = False) -> list[Problem]:
    """Return every problem of what was loaded: the files' own, then the semantic checks'."""
    problems = [*loaded.problems, *check_loaded(loaded)]
    return [p for p in problems if p.severity is Severity.ERROR] if errors_only else problems


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
    errors = problems_of(loaded, errors_only=True)
    if errors:
        raise InvalidInputError(errors)
    return loaded
