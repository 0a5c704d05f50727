"""Write the fast JSON Schema validators the package ships (rosreconf/formats/fastschema_*.py).

Run after changing a JSON Schema in rosreconf/data or the writer in
``rosreconf.formats.schemacode`` (then bump its ``GENERATOR_VERSION``):
``python scripts/fast_validators.py``. tests/test_fast_paths.py fails while a shipped module
differs from what this writes (and until then ``structure.fast_validator`` ignores it, which
costs time, never a verdict).
"""

from __future__ import annotations

from pathlib import Path

from rosreconf.formats.structure import FAST_MODULES, DocumentKind, fast_validator_module

FORMATS = Path(__file__).resolve().parent.parent / "rosreconf" / "formats"


def main() -> None:
    """Write one module per document kind."""
    for kind in DocumentKind:
        path = FORMATS / f"{FAST_MODULES[kind]}.py"
        path.write_text(fast_validator_module(kind), encoding="utf-8")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
