"""``rosreconf simulate`` on the bundled examples: ranks, requirements, cache, Dask, plots."""

from __future__ import annotations

import dataclasses
import json
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import distributed
import pytest
from conftest import DC_CAMERA_1
from typer.testing import CliRunner

from rosreconf.analysis.choice import choose, shortfall
from rosreconf.analysis.simulate import performance_of, simulate_schema
from rosreconf.cli.app import app
from rosreconf.formats.loader import load_bundled
from rosreconf.model import ComponentLibrary, Configuration
from rosreconf.planning.planners import FastDownward, PlanStatus
from rosreconf.planning.replan import plan
from rosreconf.solve.solver import Objective, best_configuration


def run(runner: CliRunner, where: Path, *args: str) -> tuple[int, str, str]:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(where)  # an empty folder: the bundled example
        result = runner.invoke(app, ["simulate", *args])
    assert not isinstance(result.exception, Exception) or isinstance(
        result.exception, SystemExit
    ), result.exception
    return result.exit_code, result.stdout, result.stderr


def document(runner: CliRunner, where: Path, *args: str) -> dict[str, Any]:
    code, out, err = run(runner, where, "--json", *args)
    assert code == 0, err
    doc: dict[str, Any] = json.loads(out)
    return doc


def by_name(doc: dict[str, Any], name: str) -> dict[str, Any]:
    return next(s for s in doc["schemas"] if s["name"] == name)


def test_the_four_arm_configurations_differ_in_settling_time_and_error(
    runner: CliRunner, tmp_path: Path
) -> None:
    doc = document(runner, tmp_path, "--only", "object_repositioning", "--workers", "1")
    arm = by_name(doc, "object_repositioning")
    configs = arm["configurations"]
    assert len(configs) == arm["configurations_simulated"] == 4
    settling = [c["figures"]["settling_time"] for c in configs]
    errors = {c["figures"]["steady_state_error"] for c in configs}
    assert len(set(settling)) == 4 and len(errors) == 2
    # Ranked: those meeting the requirements first, then by settling time.
    meets = [c["meets_requirements"] for c in configs]
    assert meets == sorted(meets, reverse=True)
    passing = [c["figures"]["settling_time"] for c in configs if c["meets_requirements"]]
    assert passing == sorted(passing)
    # The nominal servo arm with camera 1 is the best; the DC arm with the slow camera and
    # perception settles too slowly in the shoulder loop.
    assert configs[0]["assignment"]["shoulder_joint"] == "NSM2"
    assert configs[0]["assignment"]["camera"] == "NCA1"
    [failing] = [c for c in configs if not c["meets_requirements"]]
    assert (failing["assignment"]["shoulder_joint"], failing["assignment"]["camera"]) == (
        "NDC2",
        "NCA2",
    )
    shoulder = next(loop for loop in failing["loops"] if loop["name"] == "shoulder_position")
    assert shoulder["settling_time"] > arm["requirements"]["settling_time"]
    assert not shoulder["meets_requirements"]
    # A configuration's figure is the worst over its loops.
    for c in configs:
        assert c["figures"]["settling_time"] == max(loop["settling_time"] for loop in c["loops"])


def test_valid_but_unstable_configuration_is_reported_and_loops_are_simulated_once(
    runner: CliRunner, tmp_path: Path
) -> None:
    doc = document(runner, tmp_path, "--only", "indoor_navigation", "--workers", "1")
    nav = by_name(doc, "indoor_navigation")
    assert nav["configurations_simulated"] == 24  # every one connects (enumerate's count)
    # The heading loop has three roles with two candidates each: 8 loops, 6 of them are
    # reachable by valid configurations, each simulated once for 24 configurations.
    assert nav["distinct_loops"] == nav["loops_simulated"] == 6
    unstable = [c for c in nav["configurations"] if not c["stable"]]
    assert unstable and all(not c["meets_requirements"] for c in unstable)
    for c in unstable:
        assert (c["assignment"]["base"], c["assignment"]["odometry"]) == (
            "ROBOCLAW_BASE",
            "WHEEL_ODOM",
        )
        assert c["figures"]["settling_time"] is None  # never Infinity in JSON
    assert nav["configurations"][-1] in unstable  # ranked last


def test_pareto_lists_only_the_front(runner: CliRunner, tmp_path: Path) -> None:
    doc = document(
        runner, tmp_path, "--only", "indoor_navigation", "--workers", "1",
        "--pareto", "settling_time,overshoot",
    )  # fmt: skip
    front = by_name(doc, "indoor_navigation")["configurations"]
    points = [(c["figures"]["settling_time"], c["figures"]["overshoot"]) for c in front]
    assert all(c["pareto"] for c in front)
    # Nothing on the front is beaten on both metrics by anything listed.
    for a in points:
        assert not any(b[0] <= a[0] and b[1] <= a[1] and b != a for b in points)
    full = document(runner, tmp_path, "--only", "indoor_navigation", "--workers", "1")
    everyone = by_name(full, "indoor_navigation")["configurations"]
    best_settling = min(c["figures"]["settling_time"] or 1e9 for c in everyone)
    assert min(p[0] for p in points) == best_settling


def test_usage_errors(runner: CliRunner, tmp_path: Path) -> None:
    code, _, err = run(runner, tmp_path, "--only", "disc_loading")
    assert code == 2 and "has no simulation block" in err
    code, _, err = run(runner, tmp_path, "--pareto", "speed")
    assert code == 2 and "unknown metric 'speed'" in err
    code, _, err = run(runner, tmp_path, "--plot", str(tmp_path / "x.gif"))
    assert code == 2 and ".svg or .png" in err
    assert not (tmp_path / "x.gif").exists()


def test_unreachable_cluster_is_exit_3(runner: CliRunner, tmp_path: Path) -> None:
    code, _, err = run(runner, tmp_path, "--cluster", "tcp://127.0.0.1:9")
    assert code == 3 and "cannot reach the scheduler" in err


def test_unity_gain_roles_are_named() -> None:
    loaded = load_bundled()
    library = loaded.library
    no_model = ComponentLibrary(
        library.name,
        tuple(dataclasses.replace(c, dynamics=None) if c.name == "NCO1" else c for c in library),
    )
    schema = next(s for s in loaded.schemas if s.name == "object_repositioning")
    report = simulate_schema(no_model, schema)
    unity = {
        (o.loop, r) for p in report.ranked for o in p.loops for r in o.unity
    }  # NCO1 serves only configurations with NVP1
    assert unity == {("gripper_force", "gripper_sensor")}


def test_plot_png_and_svg(runner: CliRunner, tmp_path: Path) -> None:
    png = tmp_path / "steps.png"
    code, _, err = run(
        runner, tmp_path, "--workers", "1", "--pareto", "settling_time,cost", "--plot", str(png)
    )
    assert code == 0, err
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    svg = tmp_path / "steps.svg"
    code, _, err = run(runner, tmp_path, "--workers", "1", "--plot", str(svg))
    assert code == 0, err
    root = ET.parse(svg).getroot()
    assert root.tag.endswith("svg")
    text = svg.read_text(encoding="utf-8")
    assert "loop shoulder_position" in text and "settling time &lt;= 6 s" in text


def same(a: Any, b: Any) -> bool:
    """Tell whether two JSON documents are equal, floats to 1e-6 relative (round-off).

    Dask workers run BLAS single-threaded (Dask's default environment), which changes the
    order of floating-point sums inside the step responses; every decision (stability,
    ranking, requirements met, the grid-quantised settling time) must still be identical.
    """
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float):
        return a == pytest.approx(b, rel=1e-6, abs=1e-9)
    return bool(a == b)


@pytest.fixture(scope="module")
def cluster() -> Any:
    """Start a real Dask LocalCluster (two worker processes) on the loopback interface."""
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address=":0",  # a free port: concurrent runs must not share 8787
    ) as local:  # fmt: skip
        yield local


def test_cluster_answers_equal_local_ones(runner: CliRunner, tmp_path: Path, cluster: Any) -> None:
    local = document(runner, tmp_path, "--workers", "1")
    before = cluster.scheduler.transition_counter
    remote = document(runner, tmp_path, "--cluster", cluster.scheduler_address)
    assert same(remote, local)
    assert cluster.scheduler.transition_counter > before  # the scheduler handed out the work


def test_choose_passes_over_the_fewest_change_configuration_that_does_not_perform() -> None:
    """DC arm on camera 1, camera 1 fails: the DC arm on camera 2 settles too slowly."""
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "object_repositioning")
    fewest = best_configuration(
        loaded.library, schema, Objective(current=DC_CAMERA_1), failed={"NCA1"}
    )
    assert fewest is not None and fewest.mapping["positioning"] == "NFB11"
    choice = choose(loaded.library, schema, fewest, DC_CAMERA_1, {}, {"NCA1"})
    assert choice.passed_over == fewest
    assert choice.passed_over_performance is not None
    assert "shoulder_position: settling_time" in shortfall(schema, choice.passed_over_performance)
    assert choice.configuration is not None and choice.performance is not None
    assert choice.performance.meets_requirements
    assert choice.configuration.mapping["shoulder_joint"] == "NSM2"
    assert choice.configuration.mapping["camera"] == "NCA2"
    # Without failures the running configuration performs and stands.
    running = Configuration.of(schema.name, DC_CAMERA_1, schema.graph.roles)
    assert choose(loaded.library, schema, running, DC_CAMERA_1, {}).passed_over is None


def test_a_simulated_objective_is_optimised_over_the_performing_configurations() -> None:
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "indoor_navigation")
    nominal = dict(schema.nominal)
    fewest = best_configuration(loaded.library, schema, Objective(current=nominal))
    assert fewest is not None
    # Fewest changes first: nothing fails, so the nominal stays even if another settles faster.
    weights = {"overshoot": 1.0}
    choice = choose(loaded.library, schema, fewest, nominal, weights)
    assert choice.configuration == fewest
    # With no running configuration, the least overshoot among those that perform wins.
    free = choose(loaded.library, schema, fewest, {}, weights)
    report = simulate_schema(loaded.library, schema)
    least = min(p.figures["overshoot"] for p in report.ranked if p.meets_requirements)
    assert free.performance is not None and free.performance.figures["overshoot"] == least


@pytest.mark.planner
def test_plan_never_chooses_a_configuration_that_fails_the_requirements() -> None:
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "object_repositioning")
    result = plan(loaded.library, schema, {"NCA1"}, DC_CAMERA_1, FastDownward(), timeout=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.configuration is not None
    mapping = result.configuration.mapping
    assert (mapping["shoulder_joint"], mapping["camera"]) == ("NSM2", "NCA2")
    assert result.explanation[0].startswith("The fewest-change configuration was passed over")
    assert performance_of(loaded.library, schema, result.configuration).meets_requirements


def test_whatif_on_the_cluster_equals_local(
    runner: CliRunner, tmp_path: Path, cluster: Any
) -> None:
    args = ["whatif", "--only", "object_repositioning", "--json"]
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path)
        local = runner.invoke(app, [*args, "--workers", "1"])
        remote = runner.invoke(app, [*args, "--cluster", cluster.scheduler_address])
    assert local.exit_code == remote.exit_code == 0, remote.stderr
    assert json.loads(remote.stdout) == json.loads(local.stdout)


def test_the_table_shows_the_best_top_configurations(runner: CliRunner, tmp_path: Path) -> None:
    code, out, _ = run(runner, tmp_path, "--only", "indoor_navigation", "--workers", "1")
    assert code in (0, 1)
    words = " ".join(out.split())
    assert "the best 20 of 24 shown" in words
    code, out, _ = run(
        runner, tmp_path, "--only", "indoor_navigation", "--workers", "1", "--top", "3"
    )
    words = " ".join(out.split())
    assert "the best 3 of 24 shown" in words
    ranks = [line.split()[1] for line in out.splitlines() if line.startswith("│ ")]
    assert [r for r in ranks if r.isdigit()] == ["1", "2", "3"]
    code, out, _ = run(
        runner, tmp_path, "--only", "indoor_navigation", "--workers", "1", "--top", "0"
    )
    assert "shown (--top" not in " ".join(out.split())


STATE_SPACE_LIB = """\
format: rosreconf/component-library
version: 1
name: ss
components:
  - name: PI
    abstraction: controller
    provides: [{topic: /cmd, type: std_msgs/Float64}]
    requires: [{topic: /pos, type: std_msgs/Float64}]
    dynamics: {transfer_function: {num: [2.0, 1.0], den: [1.0, 0.0]}}
  - name: DRIVE
    abstraction: actuator
    requires: [{topic: /cmd, type: std_msgs/Float64}]
    provides: [{topic: /pos, type: std_msgs/Float64}]
    dynamics: DRIVE_MODEL
"""

STATE_SPACE_TASK = """\
format: rosreconf/interoperability-schema
version: 1
name: hold
skill: hold a position
environment: a joint
roles:
  - {name: ctrl, abstraction: controller}
  - {name: act, abstraction: actuator}
edges:
  - {consumer: ctrl, providers: [act]}
  - {consumer: act, providers: [ctrl]}
simulation:
  duration: 20.0
  requirements: {settling_time: 15.0}
  loops:
    - name: joint
      forward: [ctrl, act]
      plant: PLANT_MODEL
"""

# 2 / (s^2 + 3 s + 2) and 1 / (0.5 s + 1): as transfer functions and in state space.
DRIVE_TF = "{transfer_function: {num: [2.0], den: [1.0, 3.0, 2.0]}, delay: 0.05}"
DRIVE_SS = (
    "{state_space: {A: [[0.0, 1.0], [-2.0, -3.0]], B: [[0.0], [1.0]], C: [[2.0, 0.0]], "
    "D: [[0.0]]}, delay: 0.05}"
)
PLANT_TF = "{transfer_function: {num: [1.0], den: [0.5, 1.0]}}"
PLANT_SS = "{state_space: {A: [[-2.0]], B: [[1.0]], C: [[2.0]], D: [[0.0]]}}"


def test_state_space_models_simulate_as_their_transfer_functions(
    runner: CliRunner, tmp_path: Path
) -> None:
    figures = []
    for drive, plant in ((DRIVE_TF, PLANT_TF), (DRIVE_SS, PLANT_SS)):
        where = tmp_path / ("ss" if "state_space" in drive else "tf")
        (where / "libraries").mkdir(parents=True)
        (where / "schemas").mkdir()
        lib = STATE_SPACE_LIB.replace("DRIVE_MODEL", drive)
        (where / "libraries" / "lib.yaml").write_text(lib)
        task = STATE_SPACE_TASK.replace("PLANT_MODEL", plant)
        (where / "schemas" / "task.yaml").write_text(task)
        with pytest.MonkeyPatch.context() as mp:
            mp.chdir(where)
            checked = runner.invoke(app, ["validate"])
        assert checked.exit_code == 0, checked.stdout
        [config] = by_name(document(runner, where, "--workers", "1"), "hold")["configurations"]
        figures.append(config["loops"][0])
    tf, ss = figures
    assert tf["stable"] and ss["stable"]
    for key in ("settling_time", "steady_state_error", "overshoot", "final_value"):
        assert ss[key] == pytest.approx(tf[key], rel=1e-6, abs=1e-9), key
