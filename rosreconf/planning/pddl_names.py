"""Turn model names into PDDL names and back, refusing any two that would collide.

PDDL is case-insensitive and has one object namespace; model names are
``[A-Za-z][A-Za-z0-9_]*`` and interface labels may contain ``/``. See docs/pddl.md.
"""

from __future__ import annotations

from dataclasses import dataclass

from rosreconf.errors import RosreconfError
from rosreconf.model import Requirement


class PddlNameError(RosreconfError):
    """Say that two different model names would become the same PDDL name."""


@dataclass(frozen=True)
class Step:
    """One action of the task, as the model sees it.

    Attributes:
        kind: ``choose``, ``connect``, ``finish`` or ``avoid`` (proof that a forbidden
            configuration is not reached; not a step for the operator).
        role: the role the action fills or serves.
        component: the chosen component (choose, finish), the providing one (connect: empty
            in the name map, where only the provider role is known; ``planning`` fills it in).
        requirement: the requirement a connect action meets (None otherwise).
        provider_role: the providing role of a connect action (None otherwise).
    """

    kind: str
    role: str
    component: str
    requirement: Requirement | None = None
    provider_role: str | None = None


class PddlNames:
    """Turn model names into PDDL names and back; refuse any two names that would collide.

    PDDL is case-insensitive, so every name is lower-cased; interface labels may contain ``/``
    (ROS graph resource names), which becomes ``__``, and a leading ``/`` becomes ``root__``.
    Roles, components and requirements share PDDL's one object namespace.

    Attributes:
        objects: PDDL object name -> (kind, model name) for roles and components.
        requirements: PDDL object name -> the requirement it stands for.
        actions: PDDL action name -> the step it performs.
    """

    def __init__(self) -> None:
        self.objects: dict[str, tuple[str, str]] = {}
        self.requirements: dict[str, Requirement] = {}
        self.actions: dict[str, Step] = {}
        self._of: dict[tuple[str, str], str] = {}

    def _claim(self, pddl: str, what: str, model: str) -> None:
        owner = self.objects.get(pddl)
        if owner is not None and owner != (what, model):
            raise PddlNameError(
                f"{owner[0]} '{owner[1]}' and {what} '{model}' both become the PDDL name "
                f"'{pddl}' (PDDL ignores case and shares one namespace): rename one"
            )
        self.objects[pddl] = (what, model)
        self._of[(what, model)] = pddl

    def role(self, name: str) -> str:
        """Return (and register) the PDDL name of the role ``name``."""
        pddl = name.lower()
        self._claim(pddl, "role", name)
        return pddl

    def component(self, name: str) -> str:
        """Return (and register) the PDDL name of the component ``name``."""
        pddl = name.lower()
        self._claim(pddl, "component", name)
        return pddl

    def requirement(self, req: Requirement, *, qualified: bool) -> str:
        """Return (and register) the PDDL name of a requirement: its labels joined by ``-or-``.

        ``qualified`` adds each option's message type, for libraries where two different
        requirements share labels.
        """
        parts = [label(o.label) + (f"-{label(o.type)}" if qualified else "") for o in req.options]
        pddl = "-or-".join(parts)
        if pddl not in self.requirements and pddl in self.objects:
            pddl = f"req_{pddl}"  # a role or component has the label's name (role map, topic map)
        known = self.requirements.get(pddl)
        if (known is not None and known.options != req.options) or (
            known is None and pddl in self.objects
        ):
            raise PddlNameError(f"requirement {req} would become the taken PDDL name '{pddl}'")
        self.requirements[pddl] = req
        self.objects[pddl] = ("requirement", pddl)
        return pddl

    def action(self, pddl: str, step: Step) -> str:
        """Register the action ``pddl`` performing ``step``; refuse a second meaning."""
        if self.actions.get(pddl, step) != step:
            raise PddlNameError(f"two actions would be called '{pddl}'")
        self.actions[pddl] = step
        return pddl

    def step(self, action: str) -> Step | None:
        """Return the step a plan's action name stands for, or None for an unknown name."""
        return self.actions.get(action.lower())


def label(text: str) -> str:
    """Return the PDDL form of an interface label or message type (``a/b`` -> ``a__b``)."""
    root = text.startswith("/")
    body = text.lstrip("/").replace("/", "__").lower()
    return f"root__{body}" if root else body
