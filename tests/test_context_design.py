"""``--context`` at design time: counts, plans and reasons, against a brute force.

The counts under ``--context`` are checked against an independent brute force: every
configuration listed without context (``--ignore-context``), kept when each of its
components' conditions holds under the values, as written in the library file (read here
with PyYAML, not through rosreconf's model). Plans use the real Fast Downward.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import yaml
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.resources import Bundle, bundled

REPO = Path(__file__).resolve().parent.parent
EXAMPLE = REPO / "docs" / "examples" / "suave"
FILES = ["-l", str(EXAMPLE / "library.yaml"), "-s", str(EXAMPLE / "schema.yaml")]
CONDITIONS: dict[str, dict[str, Any]] = {
    c["name"]: c.get("when", {})
    for c in yaml.safe_load((EXAMPLE / "library.yaml").read_text(encoding="utf-8"))["components"]
}


def _run(runner: CliRunner, *args: str) -> tuple[int, str, str]:
    result = runner.invoke(app, [*args, *FILES])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in result.stdout + result.stderr
    return result.exit_code, result.stdout, result.stderr


def _json(runner: CliRunner, verb: str, *args: str) -> dict[str, Any]:
    code, out, err = _run(runner, verb, "--json", *args)
    assert code in (0, 1), err
    doc: dict[str, Any] = json.loads(out)
    schema = json.loads(bundled(Bundle.DATA, f"output-{verb}.schema.json").read_text("utf-8"))
    jsonschema.validate(doc, schema)
    return doc


def _holds(component: str, values: dict[str, float]) -> bool:
    """The brute force's own reading of a component's conditions (bounds inclusive)."""
    for name, cond in CONDITIONS[component].items():
        v = values[name]
        if "at_least" in cond and not v >= cond["at_least"]:
            return False
        if "at_most" in cond and not v <= cond["at_most"]:
            return False
    return True


VALUES = [
    {"visibility": 4.0, "battery": 0.9},
    {"visibility": 3.25, "battery": 0.3},  # exactly at the bounds: included
    {"visibility": 3.2499, "battery": 0.2999},
    {"visibility": 2.0, "battery": 0.8},
    {"visibility": 1.25, "battery": 0.0},
    {"visibility": 1.0, "battery": 1.0},  # no search path: no configuration
]


def _flags(values: dict[str, float]) -> list[str]:
    return [a for name, v in values.items() for a in ("--context", f"{name}={v}")]


@pytest.mark.parametrize("values", VALUES, ids=lambda v: ",".join(map(str, v.values())))
def test_counts_and_listings_match_the_brute_force(
    runner: CliRunner, values: dict[str, float]
) -> None:
    everything = _json(runner, "enumerate", "--ignore-context")["schemas"][0]["configurations"]
    assert len(everything) == 6
    expected = sorted(
        c["components"] for c in everything if all(_holds(n, values) for n in c["components"])
    )
    doc = _json(runner, "enumerate", *_flags(values))
    listed = sorted(c["components"] for c in doc["schemas"][0]["configurations"])
    assert listed == expected
    code, out, _ = _run(runner, "enumerate", "--count", *_flags(values))
    assert code == (0 if expected else 1)
    assert f"  {len(expected)} configuration(s)" in out or not expected
    ruled = {r["component"] for r in doc["context"]["ruled_out"]}
    assert ruled == {n for n in CONDITIONS if not _holds(n, values)}
    assert set(doc["failed"]) == ruled
    assert doc["context"]["values"] == values


def test_no_configuration_says_the_unmet_conditions_not_a_failure(runner: CliRunner) -> None:
    """Every search path ruled out: enumerate's why-not named each as "has failed" (text and
    JSON) though none was given as failed; it says each one's unmet condition now."""
    flags = _flags({"visibility": 1.0, "battery": 1.0})
    code, out, _ = _run(runner, "enumerate", "--count", *flags)
    doc = _json(runner, "enumerate", *flags)
    why_not = doc["schemas"][0]["why_not"]
    assert code == 1 and why_not in out
    for name in ("spiral_high", "spiral_medium", "spiral_low"):
        bound = CONDITIONS[name]["visibility"]["at_least"]
        assert f"{name} is ruled out: {name} needs visibility >= {bound}; it is 1.0" in why_not
    assert "has failed" not in out + why_not


def test_every_report_says_why(runner: CliRunner) -> None:
    flags = _flags({"visibility": 2.0, "battery": 0.1})
    code, out, _ = _run(runner, "enumerate", *flags)
    assert code == 0
    assert out.startswith(
        "context: visibility = 2.0, battery = 0.1\n"
        "  ruled out: spiral_high needs visibility >= 3.25; it is 2.0\n"
        "  ruled out: spiral_medium needs visibility >= 2.25; it is 2.0\n"
        "  ruled out: controller_fast needs battery >= 0.3; it is 0.1\n\n"
    )
    assert "1. spiral_low, controller_slow, thrusters" in out
    for verb in ("analyse", "simulate", "whatif"):
        code, out, _ = _run(runner, verb, *flags)
        assert "ruled out: spiral_high needs visibility >= 3.25; it is 2.0" in out, verb
    doc = _json(runner, "enumerate", *flags)
    assert doc["context"]["ruled_out"][0] == {
        "component": "spiral_high",
        "conditions": ["visibility >= 3.25"],
        "reason": "spiral_high needs visibility >= 3.25; it is 2.0",
    }


def test_simulate_analyse_and_whatif_treat_ruled_out_as_failed(runner: CliRunner) -> None:
    flags = _flags({"visibility": 2.5, "battery": 0.1})
    sim = _json(runner, "simulate", "--workers", "1", *flags)
    simulated = [c["assignment"] for c in sim["schemas"][0]["configurations"]]
    assert sorted(c["search"] for c in simulated) == ["spiral_low", "spiral_medium"]
    assert {c["control"] for c in simulated} == {"controller_slow"}
    assert sim["failed"] == ["spiral_high", "controller_fast"]
    ana = _json(runner, "analyse", *flags)
    assert ana["schemas"][0]["valid"] == 2
    what = _json(runner, "whatif", "--workers", "1", *flags)
    sets = [s["failed"] for s in what["schemas"][0]["failure_sets"]]
    assert not any({"spiral_high", "controller_fast"} & set(s) for s in sets)
    assert what["context"]["values"] == {"visibility": 2.5, "battery": 0.1}


def test_plan_replans_away_from_a_ruled_out_component(runner: CliRunner) -> None:
    flags = _flags({"visibility": 2.0, "battery": 0.8})
    code, out, err = _run(runner, "plan", *flags)
    assert code == 0, err
    assert "stop spiral_high, start spiral_low as search" in out
    assert (
        "spiral_high (search) is ruled out: spiral_high needs visibility >= 3.25; it is 2.0." in out
    )
    assert "1 part(s) change: the fewest possible." in out
    doc = _json(runner, "plan", *_flags({"visibility": 2.5, "battery": 0.1}))
    assignment = doc["schemas"][0]["configurations"][0]["assignment"]
    assert assignment == {
        "search": "spiral_medium",
        "control": "controller_slow",
        "thrusters": "thrusters",
    }
    assert doc["schemas"][0]["fewest_changes"] == 2
    assert any(
        "controller_fast needs battery >= 0.3; it is 0.1" in line
        for line in doc["schemas"][0]["explanation"]
    )


def test_plan_with_nothing_ruled_out_asks_for_a_failure(runner: CliRunner) -> None:
    code, _, err = _run(runner, "plan", *_flags({"visibility": 9.0, "battery": 0.9}))
    assert code == 2
    assert "give at least one --fail COMPONENT (--context rules none out)" in err


def test_fail_and_context_together(runner: CliRunner) -> None:
    doc = _json(
        runner, "enumerate", "--fail", "spiral_low", *_flags({"visibility": 2.0, "battery": 0.9})
    )
    assert doc["schemas"][0]["configurations"] == []
    assert doc["failed"] == ["spiral_low", "spiral_high", "spiral_medium"]


@pytest.mark.parametrize("verb", ["enumerate", "analyse", "plan", "simulate", "whatif"])
def test_a_condition_on_a_value_not_given_is_an_error(runner: CliRunner, verb: str) -> None:
    code, out, err = _run(runner, verb, "--context", "battery=0.5")
    assert code == 2 and not out
    assert err == (
        "rosreconf: error: spiral_high is usable only under a condition on context "
        "'visibility', which was not given: add --context visibility=VALUE, or "
        "--ignore-context to take conditions on values not given to hold\n"
    )


def test_ignore_context_takes_unset_conditions_to_hold(runner: CliRunner) -> None:
    doc = _json(runner, "enumerate", "--ignore-context", "--context", "battery=0.1")
    assert len(doc["schemas"][0]["configurations"]) == 3
    assert doc["context"]["ignored"] == ["visibility"]
    code, out, _ = _run(runner, "enumerate", "--ignore-context")
    assert code == 0 and "  6 configuration(s)" in out
    assert "conditions taken to hold (--ignore-context): battery, visibility" in out


BAD = [
    ("visibility", "--context visibility: write NAME=VALUE, e.g. visibility=2.0"),
    ("visibility=", "--context visibility=: write NAME=VALUE, e.g. visibility=2.0"),
    ("=2.0", "--context =2.0: write NAME=VALUE, e.g. visibility=2.0"),
    (
        "visibility=clear",
        "--context visibility=clear: visibility is a number: write e.g. visibility=2.0",
    ),
    (
        "visibility=nan",
        "--context visibility=nan: visibility is a number: write e.g. visibility=2.0",
    ),
    (
        "visibility=inf",
        "--context visibility=inf: visibility is a number: write e.g. visibility=2.0",
    ),
    (
        "visibilty=2",
        "--context visibilty=2: the library declares no context 'visibilty' "
        "(did you mean visibility?)",
    ),
    (
        "depth=2",
        "--context depth=2: the library declares no context 'depth' "
        "(declared: visibility, battery)",
    ),
]


@pytest.mark.parametrize("item, message", BAD, ids=[b[0] for b in BAD])
def test_a_bad_context_option_is_a_usage_error(runner: CliRunner, item: str, message: str) -> None:
    code, out, err = _run(runner, "enumerate", "--ignore-context", "--context", item)
    assert code == 2 and not out
    assert err == f"rosreconf: error: {message}\n"


def test_a_library_without_context_is_unchanged(runner: CliRunner) -> None:
    result = runner.invoke(app, ["enumerate", "--json", "--count"])
    assert "context" not in json.loads(result.stdout)
    result = runner.invoke(app, ["enumerate", "--context", "visibility=2"])
    assert result.exit_code == 2
    assert "the library declares no context 'visibility'" in result.stderr
