"""The value checks skip components whose plain values are clean: same problems as the tree walk."""

from __future__ import annotations

from conftest import examples
from hypothesis import example, given, settings
from hypothesis import strategies as st

from rosreconf.formats import yamlsource as ys
from rosreconf.formats.values import value_problems

NUMBERS = [
    "0", "1", "0.5", "-0.0", "1.0001", "-1", ".nan", ".inf", "-.inf", "1e12", "1e12001",
    "1000000000001", "9" * 401, "true", "null", "'0.5'", "[1]", "{a: 1}",
]  # fmt: skip
PARAMETERS = [
    "1", "2147483647", "2147483648", "-2147483648", "-2147483649", "1.5", ".nan", ".inf",
    "true", "x", "'$(find p)'", "a $(env X)", "{substitution: '$(find p)'}", "[1]", "null",
]  # fmt: skip


def _library(components: list[tuple[str, str, str]]) -> str:
    """Return a component library's text with these (probability, metric, parameter) values."""
    lines = ["format: rosreconf/component-library", "version: 1", "name: l", "components:"]
    for i, (probability, metric, parameter) in enumerate(components):
        lines += [
            f"  - name: C{i}",
            "    abstraction: a",
            f"    failure_probability: {probability}",
            f"    metrics: {{cost: {metric}, other: 1}}",
            f"    ros: {{package: p, executable: e, parameters: {{k: {parameter}}}}}",
        ]
    return "\n".join(lines) + "\n"


@settings(max_examples=examples(200))
@given(
    components=st.lists(
        st.tuples(st.sampled_from(NUMBERS), st.sampled_from(NUMBERS), st.sampled_from(PARAMETERS)),
        min_size=1,
        max_size=4,
    )
)
@example(components=[("0.5", "1", "1"), (".nan", "1", "1"), ("0.5", "9" * 401, "'$(x)'")])
def test_skipping_clean_components_changes_no_problem(
    components: list[tuple[str, str, str]],
) -> None:
    tree, plain = ys.parse_plain(_library(components).encode(), "l.yaml")
    assert isinstance(tree, ys.YMapping)
    assert value_problems(tree, plain) == value_problems(tree)


def test_clean_components_are_not_walked_and_the_others_are() -> None:
    # A plain value that disagrees with its tree shows which of the two was read.
    text = _library([("0.5", "1", "1"), ("0.5", "1", "1")])
    tree, plain = ys.parse_plain(text.encode(), "l.yaml")
    assert isinstance(tree, ys.YMapping) and isinstance(plain, dict)
    assert isinstance(plain["components"], list) and isinstance(plain["components"][1], dict)
    tree_only = ys.parse(_library([("0.5", "1", "1"), (".nan", "1", "1")]).encode(), "l.yaml")
    assert isinstance(tree_only, ys.YMapping)
    assert len(value_problems(tree_only, plain)) == 0  # the plain values said clean
    plain["components"][1]["failure_probability"] = float("nan")
    assert [p.code for p in value_problems(tree_only, plain)] == ["not-finite"]
