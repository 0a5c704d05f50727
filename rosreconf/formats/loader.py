"""Load component libraries and interoperability schemas from YAML, with positions.

Each file goes through three steps: YAML -> positioned tree (``yamlsource``), structure
checked against the shipped JSON Schema (``structure``, errors mapped back to
``file:line:column``), then model objects (``model``). Problems are collected per file and
across files; the caller gets the model of every well-formed file *and* the list of
problems, so ``validate`` can report everything in one run while ``enumerate`` can refuse
to work on invalid input.
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
from types import MappingProxyType

from rosreconf.errors import InvalidInputError, Problem, Severity, UsageError
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.checks import check
from rosreconf.formats.structure import DocumentKind, kind_of, structure_problems
from rosreconf.formats.values import duplicate_edges, value_problems
from rosreconf.model import (
    Component,
    ComponentLibrary,
    ConfigurationLibrary,
    ControlLoop,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    PerformanceRequirements,
    Requirement,
    Role,
    RosLaunch,
    Simulation,
    Span,
    StateSpace,
    Substitution,
    SystemGraph,
    TransferFunction,
)
from rosreconf.model.dynamics import Dynamics
from rosreconf.model.qos import QosProfile
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
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def load_sources(sources: Iterable[Source]) -> Loaded:
    """Parse and build every source, collecting problems instead of stopping at the first."""
    with _paused_gc():
        return _load_sources(sources)


def _load_sources(sources: Iterable[Source]) -> Loaded:
    loaded = Loaded()
    for src in sources:
        loaded.files.append(src.name)
        if src.size > ys.MAX_BYTES:
            loaded.problems.append(ys.too_large(src.name, src.size))
            loaded.library_complete = False
            continue
        try:
            tree = ys.parse(src.data, src.name)
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
        structural = list(structure_problems(tree, kind))
        if not structural and kind is DocumentKind.LIBRARY and isinstance(tree, ys.YMapping):
            structural = value_problems(tree)
        if structural:
            loaded.problems.extend(structural)
            loaded.library_complete &= kind is not DocumentKind.LIBRARY
            continue
        assert isinstance(tree, ys.YMapping)
        if kind is DocumentKind.LIBRARY:
            loaded.libraries.append(_build_library(tree, src.name))
        else:
            loaded.problems.extend(duplicate_edges(tree))
            loaded.schemas.append(_build_schema(tree, src.name))
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


# --- building model objects from well-formed trees --------------------------------------


def _text(node: ys.YNode | None, default: str = "") -> str:
    """Return a scalar as the text the user wrote (so names are never turned into numbers)."""
    if isinstance(node, ys.YScalar):
        return node.raw
    return default


def _seq(node: ys.YNode | None) -> list[ys.YNode]:
    return node.items if isinstance(node, ys.YSequence) else []


def _map(node: ys.YNode | None) -> dict[str, ys.YNode]:
    return node.items if isinstance(node, ys.YMapping) else {}


def _plain(node: ys.YNode) -> dict[str, object]:
    """Return a (schema-checked) mapping of scalars as plain Python values."""
    return {k: v.value for k, v in _map(node).items() if isinstance(v, ys.YScalar)}


def _interface(node: ys.YNode) -> Interface:
    items = _map(node)
    kind = InterfaceKind.SERVICE if "service" in items else InterfaceKind.TOPIC
    return Interface(kind, _text(items[kind.value]), _text(items["type"]))


def _requirement(node: ys.YNode) -> Requirement:
    items = _map(node)
    if "any_of" in items:
        return Requirement(tuple(_interface(o) for o in _seq(items["any_of"])), node.span)
    return Requirement((_interface(node),), node.span)


def _launch(node: ys.YNode | None) -> RosLaunch | None:
    if node is None:
        return None
    items = _map(node)
    params: dict[str, str | int | float | bool] = {}
    for key, value in _map(items.get("parameters")).items():
        if isinstance(value, ys.YMapping):  # {substitution: ...}, marked by the user
            params[key] = Substitution(_text(value.items["substitution"]))
            continue
        assert isinstance(value, ys.YScalar) and value.value is not None
        params[key] = value.value
    remaps = {k: _text(v) for k, v in _map(items.get("remappings")).items()}
    ns = items.get("namespace")
    lifecycle = items.get("lifecycle")
    node_name = items.get("node")
    return RosLaunch(
        package=_text(items["package"]),
        executable=_text(items["executable"]),
        parameters=MappingProxyType(params),
        remappings=MappingProxyType(remaps),
        namespace=_text(ns) if ns is not None else None,
        lifecycle=isinstance(lifecycle, ys.YScalar) and lifecycle.value is True,
        node=_text(node_name) if node_name is not None else None,
        args=tuple(_text(a) for a in _seq(items.get("args"))),
    )


def _number(node: ys.YNode | None, default: float) -> float:
    if isinstance(node, ys.YScalar) and isinstance(node.value, int | float):
        return float(node.value)
    return default


def _dynamics(node: ys.YNode | None, key: str, where: dict[str, Span]) -> Dynamics | None:
    """Build a transfer function or state-space model; record where its values are."""
    if node is None:
        return None
    items = _map(node)
    where[key] = node.span
    if "delay" in items:
        where[f"{key}.delay"] = items["delay"].span
    delay = _number(items.get("delay"), 0.0)
    if "state_space" in items:
        ss = _map(items["state_space"])
        where[f"{key}.state_space"] = items["state_space"].span
        matrices: dict[str, tuple[tuple[float, ...], ...]] = {}
        for part in ("A", "B", "C", "D"):
            path = f"{key}.state_space.{part}"
            where[path] = ss[part].span
            rows = []
            for i, row in enumerate(_seq(ss[part])):
                where[f"{path}.{i}"] = row.span
                cells = _seq(row)
                for j, n in enumerate(cells):
                    where[f"{path}.{i}.{j}"] = n.span
                rows.append(tuple(_number(n, 0.0) for n in cells))
            matrices[part] = tuple(rows)
        return StateSpace(matrices["A"], matrices["B"], matrices["C"], matrices["D"], delay)
    tf = _map(items["transfer_function"])
    coefficients: dict[str, tuple[float, ...]] = {}
    for part in ("num", "den"):
        where[f"{key}.{part}"] = tf[part].span
        values = _seq(tf[part])
        for i, n in enumerate(values):
            where[f"{key}.{part}.{i}"] = n.span
        coefficients[part] = tuple(_number(n, 0.0) for n in values)
    return TransferFunction(coefficients["num"], coefficients["den"], delay)


def _simulation(node: ys.YNode | None, where: dict[str, Span]) -> Simulation | None:
    """Build a schema's simulation block; positions go under ``simulation.`` in ``where``."""
    if node is None:
        return None
    items = _map(node)
    where["simulation"] = node.span
    loops = []
    for i, n in enumerate(_seq(items["loops"])):
        loop = _map(n)
        key = f"simulation.loops.{i}"
        where[key] = n.span
        where[f"{key}.name"] = loop["name"].span
        paths: dict[str, tuple[str, ...]] = {}
        for path in ("forward", "feedback"):
            roles = _seq(loop.get(path))
            for j, r in enumerate(roles):
                where[f"{key}.{path}.{j}"] = r.span
            paths[path] = tuple(_text(r) for r in roles)
        plant = _dynamics(loop["plant"], f"{key}.plant", where)
        assert plant is not None
        loops.append(ControlLoop(_text(loop["name"]), paths["forward"], plant, paths["feedback"]))
    limits = _map(items.get("requirements"))
    for metric, value in limits.items():
        where[f"simulation.requirements.{metric}"] = value.span
    for key in ("reference", "duration"):
        if key in items:
            where[f"simulation.{key}"] = items[key].span
    return Simulation(
        loops=tuple(loops),
        reference=_number(items.get("reference"), 1.0),
        duration=_number(items.get("duration"), 10.0),
        requirements=PerformanceRequirements(
            **{m: _number(v, 0.0) for m, v in limits.items()}  # keys fixed by the JSON Schema
        ),
    )


def _component(node: ys.YNode) -> Component:
    items = _map(node)
    fp = items.get("failure_probability")
    metrics: dict[str, float] = {}
    for key, value in _map(items.get("metrics")).items():
        assert isinstance(value, ys.YScalar) and isinstance(value.value, int | float)
        metrics[key] = float(value.value)
    where = {"name": items["name"].span, "abstraction": items["abstraction"].span}
    for key in ("needs", "excludes", "schemas"):
        for n in _seq(items.get(key)):
            where[f"{key}.{_text(n)}"] = n.span
    for key in ("provides", "requires"):
        for i, n in enumerate(_seq(items.get(key))):
            where[f"{key}.{i}"] = n.span
    qos: dict[str, QosProfile] = {}
    for n in [*_seq(items.get("provides")), *_seq(items.get("requires"))]:
        for option in _seq(_map(n).get("any_of")) or [n]:
            spec = _map(option).get("qos")
            if spec is not None:
                label = _text(_map(option).get("topic", _map(option).get("service")))
                qos[label] = QosProfile.from_dict(_plain(spec))
                where[f"qos.{label}"] = spec.span
    for i, n in enumerate(_seq(_map(items.get("ros")).get("args"))):
        where[f"ros.args.{i}"] = n.span
    dynamics = _dynamics(items.get("dynamics"), "dynamics", where)
    return Component(
        name=_text(items["name"]),
        abstraction=_text(items["abstraction"]),
        provides=frozenset(_interface(n) for n in _seq(items.get("provides"))),
        requires=tuple(_requirement(n) for n in _seq(items.get("requires"))),
        failure_probability=(
            float(fp.value) if isinstance(fp, ys.YScalar) and fp.value is not None else None
        ),
        needs=frozenset(_text(n) for n in _seq(items.get("needs"))),
        excludes=frozenset(_text(n) for n in _seq(items.get("excludes"))),
        schemas=frozenset(_text(n) for n in _seq(items.get("schemas"))),
        launch=_launch(items.get("ros")),
        metrics=MappingProxyType(metrics),
        qos=MappingProxyType(qos),
        dynamics=dynamics,
        description=_text(items.get("description")),
        span=node.span,
        where=MappingProxyType(where),
    )


def _build_library(tree: ys.YMapping, name: str) -> ComponentLibrary:
    items = tree.items
    return ComponentLibrary(
        name=_text(items["name"]),
        components=tuple(_component(n) for n in _seq(items["components"])),
        description=_text(items.get("description")),
        source=(name,),
    )


def _build_schema(tree: ys.YMapping, name: str) -> InteroperabilitySchema:
    items = tree.items
    roles = tuple(
        Role(
            name=_text(_map(n)["name"]),
            abstraction=_text(_map(n)["abstraction"]),
            description=_text(_map(n).get("description")),
            span=n.span,
        )
        for n in _seq(items["roles"])
    )
    edges = []
    for n in _seq(items.get("edges")):
        e = _map(n)
        interfaces = frozenset(_text(i) for i in _seq(e.get("interfaces")))
        opt = e.get("optional")
        optional = isinstance(opt, ys.YScalar) and opt.value is True
        for p in _seq(e["providers"]):
            edges.append(Edge(_text(e["consumer"]), _text(p), interfaces, p.span, optional))
    nominal = {k: _text(v) for k, v in _map(items.get("nominal")).items()}
    where = {"name": items["name"].span}
    where.update({f"nominal.{k}": v.span for k, v in _map(items.get("nominal")).items()})
    for n in _seq(items["roles"]):
        where[f"role.{_text(_map(n)['name'])}.abstraction"] = _map(n)["abstraction"].span
    simulation = _simulation(items.get("simulation"), where)
    return InteroperabilitySchema(
        name=_text(items["name"]),
        title=_text(items.get("title")),
        graph=SystemGraph(roles, tuple(edges)),
        skill=_text(items["skill"]).strip(),
        environment=_text(items["environment"]).strip(),
        nominal=MappingProxyType(nominal),
        simulation=simulation,
        span=tree.span,
        source=name,
        where=MappingProxyType(where),
    )
