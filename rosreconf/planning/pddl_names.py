"""Turn model names into PDDL names and back, never letting two model names share one.

PDDL is case-insensitive and has one object namespace; model names are
``[A-Za-z][A-Za-z0-9_]*`` and interface labels may contain ``/``. A role and a component may
have the same name (a role named like its only component), and two roles may differ only in
case: such a name is given a prefix with ``-`` (which no model name has), so every library
``validate`` passes can be planned. See docs/pddl.md.
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
        kind: ``choose``, ``connect``, ``finish``, ``restart`` (a kept component finished by
            restarting it, rewired) or ``avoid`` (proof that a forbidden configuration is not
            reached; not a step for the operator).
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
    """Turn model names into PDDL names and back; never give two model names one PDDL name.

    PDDL is case-insensitive, so every name is lower-cased; interface labels may contain ``/``
    (ROS graph resource names), which becomes ``__``, and a leading ``/`` becomes ``root__``.
    Roles, components and requirements share PDDL's one object namespace: a role or component
    whose lower-cased name is already another's becomes ``role-NAME`` or ``component-NAME``
    (then ``role2-NAME`` ...), deterministic in the order names are registered (``render``
    registers the roles first, in schema order). Model names never hold ``-``, so a prefixed
    name cannot be any other role's or component's.

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

    def _claim(self, what: str, model: str) -> str:
        """Return the PDDL name of ``model``, registering a free one on first sight."""
        known = self._of.get((what, model))
        if known is not None:
            return known
        base = model.lower()
        pddl, n = base, 1
        while pddl in self.objects:  # taken by another role or component (or a requirement)
            pddl = f"{what}{n if n > 1 else ''}-{base}"
            n += 1
        self.objects[pddl] = (what, model)
        self._of[(what, model)] = pddl
        return pddl

    def role(self, name: str) -> str:
        """Return (and register) the PDDL name of the role ``name``."""
        return self._claim("role", name)

    def component(self, name: str) -> str:
        """Return (and register) the PDDL name of the component ``name``."""
        return self._claim("component", name)

    def requirement(self, req: Requirement, *, qualified: bool) -> str:
        """Return (and register) the PDDL name of a requirement: its labels joined by ``-or-``.

        ``qualified`` adds each option's message type, for libraries where two different
        requirements share labels.
        """
        parts = [label(o.label) + (f"-{label(o.type)}" if qualified else "") for o in req.options]
        pddl = "-or-".join(parts)
        if pddl not in self.requirements and pddl in self.objects:
            pddl = f"req-{pddl}"  # a role or component has the label's name ('-': no model name)
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
