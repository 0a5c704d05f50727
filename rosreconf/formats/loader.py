"""Load component libraries and interoperability schemas from YAML, with positions.

Each file goes through three steps: YAML -> positioned tree and plain data (``yamlsource``),
structure checked against the shipped JSON Schema (``structure``, errors mapped back to
``file:line:column``) and values checked (``values``), then model objects (``build``).
Problems are collected per file and across files; the caller gets the model of every
well-formed file *and* the list of problems, so ``validate`` can report everything in one
run while ``enumerate`` can refuse to work on invalid input.

Positions are needed only to report a problem, and building them is most of the cost of
reading a large library. So the commands load through ``load_reported``: every file is
first read as plain data alone (``positions=False``: no tree, no span), checked (structure,
values, TODO marks, then the semantic checks) and built; at the first thing to report, of
any severity, anywhere (``NeedsPositions``), every file is loaded again the positioned way,
and that load and its problems are the answer, so every message and position is the one the
positioned load gives. A file with problems costs two reads; a clean one, one cheap read.
"""

from __future__ import annotations

import contextlib
import gc
import re
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import InvalidInputError, Problem, Severity
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.build import Interfaces, NeedsPositions, build_library, build_schema
from rosreconf.formats.checks import check
from rosreconf.formats.sources import YAML_SUFFIXES, Source, discover, read_sources
from rosreconf.formats.structure import (
    DocumentKind,
    kind_of,
    kind_of_plain,
    structure_problems,
    structure_valid,
)
from rosreconf.formats.values import (
    clean_numbers,
    clean_values,
    duplicate_edges,
    repeated_edges,
    schema_value_problems,
    value_problems,
)
from rosreconf.model import ComponentLibrary, ConfigurationLibrary, InteroperabilitySchema, Span
from rosreconf.resources import Bundle, bundled

__all__ = [
    "YAML_SUFFIXES",
    "Loaded",
    "Source",
    "check_loaded",
    "discover",
    "load_bundled",
    "load_checked",
    "load_paths",
    "load_reported",
    "load_selection",
    "load_sources",
    "load_split",
    "read_sources",
    "todo_marks",
]


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


def load_sources(sources: Iterable[Source], *, positions: bool = True) -> Loaded:
    """Parse and build every source, collecting problems instead of stopping at the first.

    With ``positions=False`` the files are read as plain data and the model has no
    positions (``load_reported``); the first thing to report raises ``NeedsPositions``.
    """
    with _paused_gc():
        return _load_sources(sources) if positions else _load_plain(sources)


def _load_plain(sources: Iterable[Source]) -> Loaded:
    """Load clean files without positions; raise ``NeedsPositions`` at anything to report.

    The same steps as ``_load_sources``, each asking only whether there is a problem: a
    file the fast reader declines, an unknown ``format``, a JSON Schema, value or TODO
    problem, or a duplicate edge sends every file back to be loaded with positions.
    """
    loaded = Loaded()
    interfaces: Interfaces = {}  # shared by every library file (see build_library)
    for src in sources:
        loaded.files.append(src.name)
        plain = ys.DECLINED if src.size > ys.MAX_BYTES else ys.parse_plain_only(src.data, src.name)
        if isinstance(plain, ys.Declined):
            raise NeedsPositions(f"{src.name}: the fast reader declined it")
        kind = kind_of_plain(plain)
        if kind is None or not structure_valid(kind, plain) or _has_todo(src):
            raise NeedsPositions(f"{src.name}: a format, structure or TODO problem")
        if kind is DocumentKind.LIBRARY:
            if not clean_values(plain):
                raise NeedsPositions(f"{src.name}: a value problem")
            loaded.libraries.append(build_library(plain, src.name, interfaces))
        else:
            if repeated_edges(plain):
                raise NeedsPositions(f"{src.name}: a duplicate edge")
            if isinstance(plain, dict) and not clean_numbers(plain.get("simulation")):
                raise NeedsPositions(f"{src.name}: a number too large for a float")
            loaded.schemas.append(build_schema(plain, src.name))
    return loaded


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
        elif not structural and isinstance(tree, ys.YMapping):
            structural = schema_value_problems(tree)
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


def _has_todo(src: Source) -> bool:
    """Tell whether ``todo_marks`` has anything to report for ``src``."""
    return b"TODO" in src.data and next(todo_marks(src), None) is not None


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


def load_paths(paths: Sequence[Path], *, positions: bool = True) -> Loaded:
    """Load the YAML files at ``paths`` (files or folders)."""
    return load_sources(read_sources(discover(paths)), positions=positions)


def load_bundled(*, positions: bool = True) -> Loaded:
    """Load the bundled example (the paper's robot arm and the mobile robot)."""
    sources = []
    for kind in (Bundle.LIBRARIES, Bundle.SCHEMAS):
        for f in sorted(bundled(kind).iterdir(), key=lambda t: t.name):
            if f.is_file() and f.name.endswith(YAML_SUFFIXES):
                sources.append(Source(f"<bundled>/{kind.value}/{f.name}", f.read_bytes()))
    loaded = load_sources(sources, positions=positions)
    loaded.note = "no libraries/ or schemas/ here: using the bundled example"
    return loaded


DEFAULT_FOLDERS = (Path("libraries"), Path("schemas"))


def load_selection(
    paths: Sequence[Path], *, base: Path | None = None, positions: bool = True
) -> Loaded:
    """Load what the user named, else ``libraries/`` and ``schemas/`` here, else the bundle.

    This is the one rule every command uses to pick its input, so that ``rosreconf
    validate``, ``enumerate`` and ``plan`` always look at the same files.
    """
    if paths:
        return load_paths(paths, positions=positions)
    here = base or Path()
    folders = [here / f for f in DEFAULT_FOLDERS if (here / f).is_dir()]
    if folders:
        loaded = load_paths(folders, positions=positions)
        loaded.note = "using " + " and ".join(f"{f.name}/" for f in folders)
        return loaded
    return load_bundled(positions=positions)


def load_split(
    library_paths: Sequence[Path],
    schema_paths: Sequence[Path],
    *,
    base: Path | None = None,
    positions: bool = True,
) -> Loaded:
    """Load libraries and schemas chosen separately (``--library``/``--schema`` options).

    Whichever side is not given comes from the default rule of ``load_selection``.
    """
    if not library_paths and not schema_paths:
        return load_selection([], base=base, positions=positions)
    if library_paths and schema_paths:  # both given: the defaults are not read at all
        return load_paths([*library_paths, *schema_paths], positions=positions)
    default = load_selection([], base=base, positions=positions)
    given = load_paths([*library_paths, *schema_paths], positions=positions)
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


def load_reported(
    load: Callable[[bool], Loaded], *, errors_only: bool = False
) -> tuple[Loaded, list[Problem]]:
    """Load with ``load(positions)`` and check; return what was loaded and every problem.

    The one place where the rule of this module's doc is applied: ``load(False)`` and the
    semantic checks first; on anything to report, ``load(True)`` and its checks are the
    answer, so problems and the model they point into always carry their positions.

    ``errors_only``: the caller reports errors only and drops warnings (the solvers, through
    ``load_checked``). Then semantic warnings alone do not cost the second load, and the
    problems returned are the errors only. A library given with one schema out of several
    warns for every component whose abstraction that schema does not use, and would
    otherwise be read twice by every command.
    """

    def reported(problems: list[Problem]) -> list[Problem]:
        return [p for p in problems if p.severity is Severity.ERROR] if errors_only else problems

    try:
        loaded = load(False)
        if not reported(check_loaded(loaded)):
            return loaded, []
    except NeedsPositions:
        pass
    loaded = load(True)
    return loaded, reported([*loaded.problems, *check_loaded(loaded)])


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
    loaded, errors = load_reported(
        lambda positions: load_split(library_paths, schema_paths, base=base, positions=positions),
        errors_only=True,
    )
    if errors:
        raise InvalidInputError(errors)
    return loaded
