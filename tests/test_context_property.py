"""Property: under any context values, the configurations are exactly those of the library
without context whose every component's conditions hold (a brute force over the listing).

Values are drawn around the example's bounds (the bounds themselves included, where
``at_least`` must hold) and the counts are those of ``Listing``, the solver every command
uses, through ``select`` as the CLI calls it.
"""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.formats.selection import select
from rosreconf.solve.listing import Listing

EXAMPLE = Path(__file__).resolve().parent.parent / "docs" / "examples" / "suave"
FILES = ([EXAMPLE / "library.yaml"], [EXAMPLE / "schema.yaml"])
EVERYTHING = select(*FILES, None, None, [], ignore_context=True)
SCHEMA = EVERYTHING.schemas[0]
ALL = [c.components for c in Listing(EVERYTHING.library, SCHEMA, ()).configurations()]

around = st.one_of(
    st.sampled_from([0.0, 1.25, 2.25, 3.25, 0.3, 1.2499, 3.2501]),
    st.floats(min_value=-1.0, max_value=5.0, allow_nan=False),
)


@settings(max_examples=40)
@given(visibility=around, battery=around)
def test_context_keeps_exactly_what_the_conditions_allow(visibility: float, battery: float) -> None:
    values = {"visibility": visibility, "battery": battery}
    sel = select(*FILES, None, None, [f"{k}={v!r}" for k, v in values.items()])
    lib = sel.library

    def usable(name: str) -> bool:  # written out here, not Condition.holds
        for w in lib[name].when:
            v = values[w.name]
            if (w.at_least is not None and v < w.at_least) or (
                w.at_most is not None and v > w.at_most
            ):
                return False
        return True

    expected = sorted(c for c in ALL if all(usable(n) for n in c))
    found = sorted(c.components for c in Listing(lib, SCHEMA, sel.failed).configurations())
    assert found == expected
    assert Listing(lib, SCHEMA, sel.failed, count_only=True).total == len(expected)
    assert {r.component for r in sel.ruled_out} == {c.name for c in lib if not usable(c.name)}
