"""Deep and wide system graphs (issue 22): a chain of roles, a fan-in, a hub.

Each role has ``k`` candidates (a failure probability each, so that reliability is computed);
every candidate of a role provides the same topic, so each shape has ``k ** roles`` valid
configurations and its analysis answers are known in closed form.
"""

from __future__ import annotations

from pathlib import Path

HEADER = ["format: rosreconf/component-library", "version: 1", "name: {name}", "components:"]


def _topic(label: str) -> str:
    return "{topic: /" + label + ", type: std_msgs/Empty}"


def _write(
    folder: Path,
    name: str,
    roles: list[tuple[str, list[str], list[str]]],
    edges: list[tuple[str, list[str]]],
    k: int,
) -> Path:
    """Write roles (name, provided topics, required topics) and edges as a library + schema."""
    (folder / "libraries").mkdir(parents=True, exist_ok=True)
    (folder / "schemas").mkdir(parents=True, exist_ok=True)
    lib = [line.format(name=name) for line in HEADER]
    for role, provides, requires in roles:
        for j in range(k):
            lib.append(f"  - name: {role.upper()}_C{j}")
            lib.append(f"    abstraction: {role}")
            if provides:
                lib.append("    provides: [" + ", ".join(_topic(t) for t in provides) + "]")
            if requires:
                lib.append("    requires: [" + ", ".join(_topic(t) for t in requires) + "]")
            lib.append(f"    failure_probability: {0.01 * (1 + j % 5)}")
    sch = [
        "format: rosreconf/interoperability-schema",
        "version: 1",
        f"name: {name}",
        "skill: Carry a signal through the graph.",
        "environment: A synthetic world.",
        "roles:",
        *(f"  - {{name: {r}, abstraction: {r}}}" for r, _, _ in roles),
        "edges:",
        *(f"  - {{consumer: {c}, providers: [{', '.join(ps)}]}}" for c, ps in edges),
    ]
    (folder / "libraries" / f"{name}.yaml").write_text("\n".join(lib) + "\n")
    (folder / "schemas" / f"{name}.yaml").write_text("\n".join(sch) + "\n")
    return folder


def write_chain(folder: Path, n: int, k: int = 2) -> Path:
    """Write a chain r0 <- r1 <- ... <- r(n-1): each role requires its predecessor's topic."""
    roles: list[tuple[str, list[str], list[str]]]
    roles = [(f"r{i}", [f"t{i}"], [f"t{i - 1}"] if i else []) for i in range(n)]
    edges = [(f"r{i}", [f"r{i - 1}"]) for i in range(1, n)]
    return _write(folder, "chain", roles, edges, k)


def write_fan_in(folder: Path, n: int, k: int = 2) -> Path:
    """Write ``n`` provider roles p0..p(n-1) whose topics one sink role requires, all of them."""
    roles: list[tuple[str, list[str], list[str]]] = [(f"p{i}", [f"t{i}"], []) for i in range(n)]
    roles.append(("sink", [], [f"t{i}" for i in range(n)]))
    return _write(folder, "fanin", roles, [("sink", [f"p{i}" for i in range(n)])], k)


def write_hub(folder: Path, n: int, k: int = 2) -> Path:
    """Write one hub role whose topic ``n`` consumer roles c0..c(n-1) each require."""
    roles: list[tuple[str, list[str], list[str]]] = [("hub", ["h"], [])]
    roles += [(f"c{i}", [], ["h"]) for i in range(n)]
    return _write(folder, "hub", roles, [(f"c{i}", ["hub"]) for i in range(n)], k)
