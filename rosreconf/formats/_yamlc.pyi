"""yamlfast's loop over libyaml's events, in C (rosreconf/formats/_yamlc.c)."""

from collections.abc import Callable

from rosreconf.formats.yamltree import Plain, Scalar, YMapping, YNode, YScalar, YSequence
from rosreconf.model import Span

def read(
    text: str,
    file: str,
    max_depth: int,
    span: type[Span] | None,
    scalar: type[YScalar] | None,
    mapping: type[YMapping] | None,
    sequence: type[YSequence] | None,
    resolve_plain: Callable[[str], Scalar],
    header_comment: Callable[[str, int], object],
    /,
) -> tuple[YNode | None, Plain] | None:
    """Return (tree, plain data) for ``text``, or None where ``yamlfast`` declines.

    With the four types all None, only the plain data is built and the tree is None.
    """
