"""A library with many candidates for one role (issue 10: analyse and whatif must scale).

Four roles in a chain (sensor <- perception <- control <- actuator); the perception role
has ``n`` candidates whose provisions, requirements and failure probabilities cycle through
a few patterns: some require what only a component outside the schema provides (unusable),
a few exclude a sensor, a quarter have no failure probability (assumed never to fail).
"""

from __future__ import annotations

from pathlib import Path

SENSORS = [
    ("SEN_C0", ["sen_a"], 0.02),
    ("SEN_C1", ["sen_b"], 0.01),
    ("SEN_C2", ["sen_a", "sen_b"], 0.05),
]
CONTROLLERS = [
    ("CTL_C0", ["per_a"], ["ctl_a"], 0.03),
    ("CTL_C1", ["per_b"], ["ctl_a", "ctl_b"], 0.02),
    ("CTL_C2", ["per_a", "per_b"], ["ctl_b"], 0.04),
]
ACTUATORS = [("ACT_C0", ["ctl_a"], 0.01), ("ACT_C1", ["ctl_b"], 0.02)]
PER_PROVIDES = [["per_a"], ["per_b"], ["per_a", "per_b"]]
PER_REQUIRES = [["sen_a"], ["sen_b"], ["sen_a", "sen_b"], ["sen_c"]]


def _topic(label: str) -> str:
    return "{topic: " + label + ", type: gen_msgs/Msg}"


def _any_of(labels: list[str]) -> str:
    if len(labels) == 1:
        return _topic(labels[0])
    return "{any_of: [" + ", ".join(_topic(x) for x in labels) + "]}"


def _component(
    name: str,
    label: str,
    provides: list[str],
    requires: list[str],
    p: float | None,
    excludes: str = "",
) -> list[str]:
    out = [f"  - name: {name}", f"    abstraction: {label}"]
    if provides:
        out.append("    provides: [" + ", ".join(_topic(x) for x in provides) + "]")
    if requires:
        out.append(f"    requires: [{_any_of(requires)}]")
    if p is not None:
        out.append(f"    failure_probability: {p}")
    if excludes:
        out.append(f"    excludes: [{excludes}]")
    return out


def per_probability(i: int) -> float | None:
    """Return the failure probability of perception candidate ``i`` (None for every fourth)."""
    return None if i % 4 == 0 else round(0.001 * (1 + i % 7), 4)


def write_many(folder: Path, n: int) -> Path:
    """Write the library and schema with ``n`` perception candidates into ``folder``."""
    (folder / "libraries").mkdir(parents=True, exist_ok=True)
    (folder / "schemas").mkdir(parents=True, exist_ok=True)
    lines = ["format: rosreconf/component-library", "version: 1", "name: many", "components:"]
    for name, provides, p in SENSORS:
        lines += _component(name, "sen", provides, [], p)
    for i in range(n):
        lines += _component(
            f"PER_C{i}",
            "per",
            PER_PROVIDES[i % 3],
            PER_REQUIRES[(i // 3) % 4],
            per_probability(i),
            "SEN_C2" if i % 997 == 7 else "",
        )
    for name, requires, provides, p in CONTROLLERS:
        lines += _component(name, "ctl", provides, requires, p)
    for name, requires, p in ACTUATORS:
        lines += _component(name, "act", [], requires, p)
    lines += _component("AUX", "aux", ["sen_c"], [], 0.1)  # in no role: sen_c is never met
    (folder / "libraries" / "many.yaml").write_text("\n".join(lines) + "\n")
    (folder / "schemas" / "many.yaml").write_text(
        "\n".join(
            [
                "format: rosreconf/interoperability-schema",
                "version: 1",
                "name: many",
                "skill: Carry readings through perception and control to an actuator.",
                "environment: A synthetic world.",
                "roles:",
                "  - {name: sen, abstraction: sen}",
                "  - {name: per, abstraction: per}",
                "  - {name: ctl, abstraction: ctl}",
                "  - {name: act, abstraction: act}",
                "edges:",
                "  - {consumer: per, providers: [sen]}",
                "  - {consumer: ctl, providers: [per]}",
                "  - {consumer: act, providers: [ctl]}",
            ]
        )
        + "\n"
    )
    return folder
