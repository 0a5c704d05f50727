"""Library parameters reach a real rclpy node with the library's types (issue 32, N2).

``watch --ros2 --apply`` starts an executable with ``--ros-args -p name:=value``
(``launchfiles.ros2_node_arguments``), and rcl types each value with rules of its own
(rcl_yaml_param_parser): ``y`` and ``on`` are bools, ``1e3``, ``inf``, ``nan`` and ``.5``
doubles, ``0x1F`` an integer. Before, rosreconf quoted only what PyYAML would misread, so
the string ``"y"`` arrived as a bool and ``"1e3"`` as a double. The reference is the type a
real rclpy node (tests/ros2_param_probe.py, Jazzy and Kilted) declares each override with,
started with exactly the arguments rosreconf builds; the expected types are this table's,
and the library file read by rosreconf must give the same values first.

The library's parameters are scalars (its JSON Schema: string, integer, number, boolean),
so there are no arrays to carry.
"""

from __future__ import annotations

import json
import math
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import ros2_real
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_paths
from rosreconf.ros.launchfiles import ros2_node_arguments

PROBE = Path(__file__).with_name("ros2_param_probe.py")

HOSTILE: dict[str, tuple[str, str | int | float | bool]] = {
    # name: (as written in the library file, the value the library means)
    "s_y": ('"y"', "y"),
    "s_n_upper": ('"N"', "N"),
    "s_yes": ('"yes"', "yes"),
    "s_on": ('"on"', "on"),
    "s_off": ('"off"', "off"),
    "s_true": ('"true"', "true"),
    "s_1e3": ('"1e3"', "1e3"),
    "s_inf": ('"inf"', "inf"),
    "s_minus_inf": ('"-inf"', "-inf"),
    "s_dot_inf": ('".inf"', ".inf"),
    "s_nan": ('"nan"', "nan"),
    "s_minus_1e_5": ('"-1e-5"', "-1e-5"),
    "s_hex": ('"0x1F"', "0x1F"),
    "s_octal": ('"017"', "017"),
    "s_underscores": ('"1_000"', "1_000"),
    "s_dot5": ('".5"', ".5"),
    "s_one": ('"1"', "1"),
    "s_one_point_zero": ('"1.0"', "1.0"),
    "s_tilde": ('"~"', "~"),
    "s_null": ('"null"', "null"),
    "s_empty": ('""', ""),
    "s_space": ('" "', " "),
    "s_leading_spaces": ('"  5"', "  5"),
    "s_quotes": ("'it''s \"quoted\"'", 'it\'s "quoted"'),
    "s_colon": ('"a: b"', "a: b"),
    "s_hash": ('"x #y"', "x #y"),
    "s_list_like": ('"[1, 2]"', "[1, 2]"),
    "s_map_like": ('"{a: 1}"', "{a: 1}"),
    "s_backslash": ('"c:\\\\dir\\\\n"', "c:\\dir\\n"),
    "s_newline_tab": ('"a\\nb\\tc"', "a\nb\tc"),
    "s_unicode": ('"é ü 日本 😀"', "é ü 日本 😀"),
    "s_dash": ('"-"', "-"),
    "s_percent": ('"%s=1"', "%s=1"),
    "b_true": ("true", True),
    "b_false": ("false", False),
    "i_zero": ("0", 0),
    "i_negative": ("-42", -42),
    "i_int32_max": ("2147483647", 2147483647),
    "i_int32_min": ("-2147483648", -2147483648),
    "d_one": ("1.0", 1.0),
    "d_half": ("0.5", 0.5),
    "d_negative_small": ("-1.0e-5", -1e-5),
    "d_huge": ("1.0e300", 1e300),
    "d_smallest_normal": ("2.2250738585072014e-308", 2.2250738585072014e-308),
    "d_third": ("0.3333333333333333", 1 / 3),
}

RCL_TYPE = {str: "STRING", bool: "BOOL", int: "INTEGER", float: "DOUBLE"}
"""Python type of a library value -> rclpy ``Parameter.Type`` name."""


def _library(tmp_path: Path) -> Path:
    """Write a one-component library whose parameters are the hostile table."""
    lines = [f"        {name}: {text}" for name, (text, _) in HOSTILE.items()]
    path = tmp_path / "lib.yaml"
    path.write_text(
        "format: rosreconf/component-library\nversion: 1\nname: params\ncomponents:\n"
        "  - name: PROBE\n    abstraction: probe\n"
        "    provides: [{topic: out, type: std_msgs/String}]\n"
        "    ros:\n      package: probe\n      executable: probe\n      node: param_probe\n"
        "      parameters:\n" + "\n".join(lines) + "\n",
        encoding="utf-8",
    )
    return path


def _same(got: object, want: object) -> bool:
    """Tell equal values apart from merely close ones (a float must come back exactly)."""
    if isinstance(want, float) and isinstance(got, float):
        return got == want or (math.isnan(got) and math.isnan(want))
    return type(got) is type(want) and got == want


@pytest.mark.parametrize("distro", ros2_real.DISTROS)
def test_each_parameter_reaches_a_real_node_with_the_library_type(
    distro: str, domain_id: int, tmp_path: Path
) -> None:
    library = load_paths([_library(tmp_path)]).library
    given = dict(library["PROBE"].launch.parameters)  # type: ignore[union-attr]
    assert given == {name: value for name, (_, value) in HOSTILE.items()}
    argv = ros2_node_arguments(library, "PROBE", {})
    env = ros2_real.node_env(domain_id, tmp_path / "home")
    done = subprocess.run(
        [str(ros2_real.python_of(distro)), str(PROBE), *argv],
        env=env,
        capture_output=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 0, done.stderr.decode(errors="replace")[-2000:]
    report = json.loads(done.stdout.decode().strip().splitlines()[-1])
    wrong = {
        name: (report.get(name), RCL_TYPE[type(value)], value)
        for name, (_, value) in HOSTILE.items()
        if report.get(name, [None])[0] != RCL_TYPE[type(value)] or not _same(report[name][1], value)
    }
    assert wrong == {}, f"received vs (wanted type, value): {wrong}"


def test_the_ros2_launch_file_names_each_parameter_type(tmp_path: Path) -> None:
    """launch_ros reads an untyped ``<param value>`` with YAML twice, so ``'y'`` was a bool.

    With ``type`` (launch_ros, Humble and later: ``str``, ``int``, ``float``, ``bool``),
    launch_xml takes the text as that type (``launch.utilities.type_utils.coerce_to_type``):
    a ``str`` as it is, an ``int`` or ``float`` by Python's own constructor, a ``bool`` as
    YAML's ``true``/``false``; launch and launch_ros are not on PyPI, so this checks the
    file against those rules as their source states them.
    """
    lib, sch, out = _library(tmp_path), tmp_path / "one.yaml", tmp_path / "one.launch.xml"
    sch.write_text(
        "format: rosreconf/interoperability-schema\nversion: 1\nname: one\nskill: probe\n"
        "environment: anywhere\nroles:\n  - {name: probe, abstraction: probe}\n",
        encoding="utf-8",
    )
    args = ["launch", "-l", str(lib), "-s", str(sch), "--only", "one", "--ros2", "-o", str(out)]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    root = ET.parse(out).getroot()
    params = {p.get("name"): p for p in root.iter("param")}
    assert set(params) == set(HOSTILE)
    for name, (_, value) in HOSTILE.items():
        p = params[name]
        kind = {str: "str", bool: "bool", int: "int", float: "float"}[type(value)]
        assert p.get("type") == kind, name
        text = p.get("value")
        assert text is not None
        read = {
            "str": lambda t: t,
            "int": int,
            "float": float,
            "bool": {"true": True, "false": False}.get,
        }[kind](text)
        assert _same(read, value), (name, text)


def test_a_subnormal_parameter_is_refused(tmp_path: Path) -> None:
    """rcl's ``strtod`` underflows on 5e-324 and the node got the string "5e-324" (found here)."""
    lib = _library(tmp_path)
    lib.write_text(lib.read_text(encoding="utf-8") + "        d_tiny: 5.0e-324\n", encoding="utf-8")
    result = CliRunner().invoke(app, ["validate", str(lib)])
    assert result.exit_code == 1, result.output
    assert "parameter 'd_tiny' is 5.0e-324, a subnormal number" in result.output
