"""Repair a valid configuration after failures by swapping in interchangeable candidates.

Two candidates of one role that no rule of validity tells apart (``instance.interchangeable``:
the same interfaces provided and required, named by no rule, fit for one role only) can
stand in for each other in any valid configuration: the configuration with one swapped for
the other is valid too. So when a failure set hits a known valid configuration only in
components that have a working twin, that configuration with the twins swapped in is a
valid configuration that avoids every failure, found without a solver. It proves survival
only: when some failed component has no working twin, nothing is concluded and the caller
asks a solver (``whatif -k 1`` on a hub of 10^4 consumers made one clingo solve
per failure, over 300 s, though every consumer had a twin).
"""

from __future__ import annotations

from collections.abc import Collection, Iterator, Sequence
from typing import overload

from rosreconf.model import Configuration
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import Instance, interchangeable

__all__ = ["Swapped", "Swaps"]


class Swapped(Sequence[str]):
    """A configuration's components (role order): a known one with a few swapped.

    It shares the known configuration's tuple and set, so thousands of repairs of a
    configuration of 10^4 components cost a few entries each, and membership is O(1).
    """

    __slots__ = ("_base", "_members", "_swap")

    def __init__(self, base: Swaps, swap: dict[int, str]) -> None:
        self._base, self._members, self._swap = base.components, base.members, swap

    def __len__(self) -> int:
        return len(self._base)

    @overload
    def __getitem__(self, i: int) -> str: ...
    @overload
    def __getitem__(self, i: slice) -> Sequence[str]: ...
    def __getitem__(self, i: int | slice) -> str | Sequence[str]:
        if isinstance(i, slice):
            return tuple(self)[i]
        j = range(len(self._base))[i]
        return self._swap.get(j, self._base[j])

    def __iter__(self) -> Iterator[str]:
        swap = self._swap
        for j, c in enumerate(self._base):
            yield swap.get(j, c)

    def __contains__(self, name: object) -> bool:
        if name in self._swap.values():
            return True
        j = self._members.get(name) if isinstance(name, str) else None
        return j is not None and j not in self._swap

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Sequence) and tuple(self) == tuple(other)

    def __hash__(self) -> int:
        return hash(tuple(self))

    def __repr__(self) -> str:
        return f"Swapped({tuple(self)!r})"


class Swaps:
    """A valid configuration and, per chosen component, the twins that may replace it.

    Attributes:
        components: the configuration's components in role order (no empty roles).
        members: component -> its position in ``components``.
        twins: component -> its class of interchangeable candidates (itself included,
            library order); absent when it has no twin.
    """

    def __init__(self, inst: Instance, config: Configuration) -> None:
        """Index ``config``, a valid configuration of ``inst`` (compiled without failures)."""
        self.components = config.components
        self.members = {c: j for j, c in enumerate(self.components)}
        names = [[c.name for c in dom] for dom in inst.domains]
        self.twins: dict[str, tuple[str, ...]] = {}
        classes = interchangeable(inst, names)
        for (role, pick), mine in zip(config.assignment, classes, strict=True):
            pick = as_candidate(role, pick)
            for members in mine:
                if len(members) > 1 and pick in members:
                    self.twins[pick] = tuple(members)

    def avoiding(self, failed: Collection[str]) -> Sequence[str] | None:
        """Return a valid configuration without ``failed`` (components in role order), or None.

        None says only that swapping twins cannot avoid ``failed``: the schema may still
        survive with another configuration.
        """
        swap = {}
        for name in failed:
            j = self.members.get(name)
            if j is None:
                continue
            twin = next((t for t in self.twins.get(name, ()) if t not in failed), None)
            if twin is None:
                return None
            swap[j] = twin
        return Swapped(self, swap)

    @property
    def whole(self) -> Swapped:
        """Return the configuration itself, as a view that answers ``in`` in O(1)."""
        return Swapped(self, {})
