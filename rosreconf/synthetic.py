"""Generate large, valid, reproducible libraries and schemas to measure rosreconf at scale.

The system graph is layered like the paper's Fig. 2: sensors -> perception -> control ->
actuators, each role a consumer of one to three neighbouring roles of the layer before it
(a band, so the graph's treewidth stays small and exact counting stays cheap). Every role
has ``K`` candidates; a candidate provides its role's output in interface family ``a``,
``b`` or both, and requires each provider's output in family ``a``, ``b`` or either, so only
some candidate pairs are compatible. One candidate per role provides and accepts both
families and takes part in no coupling: these form the nominal configuration, which is
therefore always valid. Couplings (``needs``/``excludes``) join other candidates of
neighbouring roles at density ``coupling`` (the share of edges carrying one).

How names change across layers::

    layer        role     abstraction   component    output topic (family a / b)
    -----------  -------  ------------  -----------  ---------------------------
    sensors      sen3     sen3          SEN3_C0..    sen3_a / sen3_b
    perception   per3     per3          PER3_C0..    per3_a / per3_b
    control      ctl3     ctl3          CTL3_C0..    ctl3_a / ctl3_b
    actuators    act3     act3          ACT3_C0..    (provides nothing)
"""

from __future__ import annotations

import itertools
import random
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.outfiles import output_folder, write_atomic
from rosreconf.resources import MAX_YAML_BYTES as MAX_BYTES

LAYERS = ("sen", "per", "ctl", "act")
"""Layer prefixes in the order information flows (Fig. 2)."""

FAMILY_TYPES = {"a": "gen_msgs/FamilyA", "b": "gen_msgs/FamilyB"}
"""Message class of each interface family (one type per label, as the checks demand)."""

LIBRARY_HEADER = "# yaml-language-server: $schema=../rosreconf/data/component-library.schema.json"
SCHEMA_HEADER = (
    "# yaml-language-server: $schema=../rosreconf/data/interoperability-schema.schema.json"
)


@dataclass
class _Candidate:
    """One generated component: its families, requirements and couplings."""

    name: str
    provides: tuple[str, ...]
    requires: dict[str, tuple[str, ...]] = field(default_factory=dict)
    needs: set[str] = field(default_factory=set)
    excludes: set[str] = field(default_factory=set)


@dataclass(frozen=True)
class Generated:
    """The text of one generated library file and one schema file.

    Attributes:
        library: the component library YAML (docs/formats.md).
        schema: the interoperability schema YAML, with a valid nominal configuration.
    """

    library: str
    schema: str


def layer_sizes(roles: int) -> list[int]:
    """Split ``roles`` over the four layers as evenly as possible (earlier layers first)."""
    return [roles // 4 + (1 if i < roles % 4 else 0) for i in range(4)]


MAX_COMPONENTS = 200_000
"""The largest library ``generate`` writes (roles x candidates): about 0.4 GB of memory and
under a minute (whole process, /usr/bin/time, 2 x 100,000 components: 0.29 GB / 18 s at
10,000 x 10, 0.41 GB / 49 s at 10 x 20,000); the old unbounded ``--roles 1000000`` ran the
machine out of memory."""


def check_sizes(roles: int, candidates: int, coupling: float = 0.2) -> None:
    """Refuse sizes ``generate`` cannot or will not make, before anything is made.

    Raises:
        ValueError: a size below 1, more than ``MAX_COMPONENTS`` components, or a coupling
            outside [0, 1].
    """
    if roles < 1 or candidates < 1:
        raise ValueError("roles and candidates must be at least 1")
    if roles * candidates > MAX_COMPONENTS:
        raise ValueError(
            f"--roles {roles} x --candidates {candidates} is {roles * candidates:,} components; "
            f"generate writes at most {MAX_COMPONENTS:,} (fewer roles or candidates)"
        )
    if not 0.0 <= coupling <= 1.0:
        raise ValueError("coupling must be between 0 and 1")


def generate(
    roles: int,
    candidates: int,
    coupling: float = 0.2,
    seed: int = 0,
    *,
    dynamics: bool = False,
) -> Generated:
    """Return a library and schema of ``roles`` roles with ``candidates`` candidates each.

    The same arguments always give the same bytes (``random.Random(seed)``). With
    ``dynamics`` every component also gets a transfer function and the schema a simulation
    block (``_dynamics``); they come from a second random stream, so the rest of the files
    is the same bytes as without.

    Raises:
        ValueError: a size below 1, more than ``MAX_COMPONENTS`` components, or a coupling
            outside [0, 1].
    """
    check_sizes(roles, candidates, coupling)
    rng = random.Random(seed)
    layers = [
        [f"{prefix}{i}" for i in range(n)]
        for prefix, n in zip(LAYERS, layer_sizes(roles), strict=True)
    ]
    layers = [layer for layer in layers if layer]
    edges: list[tuple[str, list[str]]] = []
    for before, layer in itertools.pairwise(layers):
        for j, consumer in enumerate(layer):
            centre = j * len(before) // len(layer)
            width = rng.choices((1, 2, 3), weights=(5, 4, 1))[0]
            edges.append((consumer, before[centre : centre + width]))
    last = {name for name in layers[-1]} if len(layers) > 1 else set()
    cands: dict[str, list[_Candidate]] = {}
    nominal: dict[str, str] = {}
    for layer in layers:
        for role in layer:
            universal = rng.randrange(candidates)
            row = []
            for k in range(candidates):
                if role in last:
                    fams: tuple[str, ...] = ()
                elif k == universal or rng.random() < 0.2:
                    fams = ("a", "b")
                else:
                    fams = (rng.choice("ab"),)
                row.append(_Candidate(f"{role.upper()}_C{k}", fams))
            cands[role] = row
            nominal[role] = row[universal].name
    universal_names = set(nominal.values())
    for consumer, providers in edges:
        for cand in cands[consumer]:
            for p in providers:
                if cand.name in universal_names or rng.random() < 0.2:
                    cand.requires[p] = ("a", "b")
                else:
                    cand.requires[p] = (rng.choice("ab"),)
        for p in providers:
            if candidates < 2 or rng.random() >= coupling:
                continue
            who = rng.choice([c for c in cands[consumer] if c.name not in universal_names])
            other = rng.choice(cands[p]).name
            if other in who.needs or other in who.excludes:
                continue
            (who.needs if rng.random() < 0.5 else who.excludes).add(other)
    models = _dynamics(layers, cands, random.Random(seed + 1)) if dynamics else None
    library = _library_text(roles, candidates, seed, layers, cands, rng, models)
    schema = _schema_text(roles, candidates, seed, layers, edges, nominal, models)
    return Generated(library, schema)


@dataclass(frozen=True)
class _Models:
    """Generated dynamics: per component a transfer function line, and the loops."""

    lines: dict[str, list[str]]
    loops: list[tuple[str, list[str], list[str]]]


def _dynamics(
    layers: list[list[str]], cands: dict[str, list[_Candidate]], rng: random.Random
) -> _Models | None:
    """Give every component a model by its layer and close one loop per actuator role.

    Sensors and perception are lags with dead time, controllers PI, actuators lags; loop
    ``i`` runs control ``i`` -> actuator ``i`` -> a first-order plant, fed back through
    sensor ``i`` and perception ``i`` (indices wrap around their layers). Gains are drawn
    so that most loops are stable and some are not, as with real parts.
    """
    if len(layers) < 4:
        return None
    lines: dict[str, list[str]] = {}
    for layer in layers:
        for role in layer:
            for c in cands[role]:
                kind = role[:3]
                if kind in ("sen", "per"):
                    tau, delay = rng.uniform(0.01, 0.1), rng.uniform(0.0, 0.1)
                    tf = f"{{num: [1.0], den: [{tau:.3f}, 1.0]}}"
                    extra = [f"      delay: {delay:.3f}"]
                elif kind == "ctl":
                    kp, ki = rng.uniform(0.5, 4.0), rng.uniform(0.2, 3.0)
                    tf, extra = f"{{num: [{kp:.3f}, {ki:.3f}], den: [1.0, 0.0]}}", []
                else:
                    tau = rng.uniform(0.02, 0.3)
                    tf, extra = f"{{num: [1.0], den: [{tau:.3f}, 1.0]}}", []
                lines[c.name] = ["    dynamics:", f"      transfer_function: {tf}", *extra]
    sen, per, ctl, act = layers
    loops = [
        (f"loop{i}", [ctl[i % len(ctl)], a], [sen[i % len(sen)], per[i % len(per)]])
        for i, a in enumerate(act)
    ]
    return _Models(lines, loops)


def _library_text(
    roles: int,
    candidates: int,
    seed: int,
    layers: list[list[str]],
    cands: dict[str, list[_Candidate]],
    rng: random.Random,
    models: _Models | None = None,
) -> str:
    out = [
        LIBRARY_HEADER,
        f"# Generated by `rosreconf generate` (roles={roles}, candidates={candidates}, "
        f"seed={seed}).",
        "format: rosreconf/component-library",
        "version: 1",
        "name: generated",
        f"description: Generated layered library, {roles} roles x {candidates} candidates.",
        "components:",
    ]
    for layer in layers:
        for role in layer:
            for c in cands[role]:
                out.append(f"  - name: {c.name}")
                out.append(f"    abstraction: {role}")
                if c.provides:
                    out.append("    provides:")
                    for fam in c.provides:
                        out.append(f"      - {{topic: {role}_{fam}, type: {FAMILY_TYPES[fam]}}}")
                if c.requires:
                    out.append("    requires:")
                    for p, fams in c.requires.items():
                        opts = [f"{{topic: {p}_{f}, type: {FAMILY_TYPES[f]}}}" for f in fams]
                        item = opts[0] if len(opts) == 1 else "{any_of: [" + ", ".join(opts) + "]}"
                        out.append(f"      - {item}")
                if c.needs:
                    out.append(f"    needs: [{', '.join(sorted(c.needs))}]")
                if c.excludes:
                    out.append(f"    excludes: [{', '.join(sorted(c.excludes))}]")
                out.append(f"    failure_probability: {rng.uniform(0.001, 0.05):.4f}")
                cost, settle = rng.uniform(1.0, 10.0), rng.uniform(0.1, 2.0)
                out.append(f"    metrics: {{cost: {cost:.2f}, settling_time: {settle:.3f}}}")
                if models is not None:
                    out.extend(models.lines[c.name])
    return "\n".join(out) + "\n"


def _schema_text(
    roles: int,
    candidates: int,
    seed: int,
    layers: list[list[str]],
    edges: list[tuple[str, list[str]]],
    nominal: dict[str, str],
    models: _Models | None = None,
) -> str:
    out = [
        SCHEMA_HEADER,
        f"# Generated by `rosreconf generate` (roles={roles}, candidates={candidates}, "
        f"seed={seed}).",
        "format: rosreconf/interoperability-schema",
        "version: 1",
        "name: generated",
        "title: Generated System",
        "skill: Carry sensor readings through perception and control to the actuators.",
        "environment: A synthetic benchmark world.",
        "roles:",
    ]
    names = {"sen": "sensor", "per": "perception", "ctl": "control", "act": "actuator"}
    for layer in layers:
        for role in layer:
            out.append(f"  - {{name: {role}, abstraction: {role}, description: {names[role[:3]]}}}")
    if edges:
        out.append("edges:")
        for consumer, providers in edges:
            out.append(f"  - {{consumer: {consumer}, providers: [{', '.join(providers)}]}}")
    out.append("nominal:")
    out.extend(f"  {role}: {comp}" for role, comp in nominal.items())
    if models is not None:
        out += [
            "simulation:",
            "  duration: 10.0",
            "  requirements: {settling_time: 5.0, steady_state_error: 0.02, overshoot: 30.0}",
            "  loops:",
        ]
        for name, forward, feedback in models.loops:
            out.append(f"    - name: {name}")
            out.append(f"      forward: [{', '.join(forward)}]")
            out.append("      plant: {transfer_function: {num: [1.0], den: [0.5, 1.0]}}")
            out.append(f"      feedback: [{', '.join(feedback)}]")
    return "\n".join(out) + "\n"


def check_file_sizes(generated: Generated) -> None:
    """Refuse files that ``validate`` would refuse for their size, before either is written.

    ``MAX_COMPONENTS`` bounds the components, not the bytes: 100,000 roles of 2 candidates
    with dynamics made a 79.6 MB library that every other command refuses.

    Raises:
        ValueError: a file is over ``resources.MAX_YAML_BYTES``; says its size and the limit.
    """
    for kind, text in (("library", generated.library), ("schema", generated.schema)):
        size = len(text.encode("utf-8"))
        if size > MAX_BYTES:
            raise ValueError(
                f"the {kind} would be {size:,} bytes ({size / 2**20:.1f} MiB), over the "
                f"{MAX_BYTES:,} bytes ({MAX_BYTES // 2**20} MiB) rosreconf reads "
                "(fewer roles or candidates); nothing was written"
            )


def write(generated: Generated, directory: Path) -> tuple[Path, Path]:
    """Write ``libraries/generated.yaml`` and ``schemas/generated.yaml`` under ``directory``.

    Each file is written to a temporary name beside it and renamed, so a reader never sees
    half a file; files too large for rosreconf to read are refused first (ValueError).
    """
    check_file_sizes(generated)
    paths = (
        directory / "libraries" / "generated.yaml",
        directory / "schemas" / "generated.yaml",
    )
    for path, text in zip(paths, (generated.library, generated.schema), strict=True):
        write_atomic(output_folder(path.parent) / path.name, text)
    return paths
