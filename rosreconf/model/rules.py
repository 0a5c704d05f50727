"""Every rule of validity, listed once, with the places each of its five encodings implements it.

The definition is ``rosreconf.model.validity``; clingo, counting, elimination and PDDL encode
it again for speed. Listing the rules here, next to the definition and below every encoding,
is what lets tests/test_rules.py demand that a rule added to one is added to all (see
docs/formats.md, "The rules, once", for the checklist). Places are ``module:qualname``
strings, not imports, because the encodings live in stages above the model.
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass


class Encoding(enum.StrEnum):
    """The five encodings of validity that must agree."""

    DEFINITION = "definition"
    """``violations`` here: the brute-force reference."""
    CLINGO = "clingo"
    """The ASP program and facts of ``rosreconf.solve.solver`` (enumeration, clingo optimum)."""
    COUNTING = "counting"
    """The 0/1 tables of ``rosreconf.solve.factors`` summed out by ``rosreconf.solve.counting``."""
    ELIMINATION = "elimination"
    """The same tables minimised out by ``rosreconf.solve.optimum`` (the optimum)."""
    PDDL = "pddl"
    """The pre-grounded STRIPS task of ``rosreconf.planning.pddl`` (Fast Downward)."""


@dataclass(frozen=True)
class Rule:
    """One rule of validity, where the paper states it, and where each encoding implements it.

    Attributes:
        name: stable identifier (tests are named after it).
        paper: where the paper defines it (or "extension" with the reason).
        meaning: the rule in one sentence.
        codes: the ``Violation.code`` values the definition reports when it is broken (empty
            for a rule that only relaxes another, such as optional edges).
        places: per encoding, the ``module:function`` places that implement the rule. The
            compiled tables of ``rosreconf.solve.instance`` are shared by clingo, counting,
            elimination and PDDL, so a rule decided there is listed for each of them.
    """

    name: str
    paper: str
    meaning: str
    codes: tuple[str, ...]
    places: Mapping[Encoding, tuple[str, ...]]


_V = "rosreconf.model.validity:"
_I = "rosreconf.solve.instance:"
_S = "rosreconf.solve.solver:"
_F = "rosreconf.solve.factors:"
_P = "rosreconf.planning.pddl:"
_E = "rosreconf.solve.emptyroles:"
_CANDIDATES = {  # who may fill a role is decided once, by the candidate domains
    Encoding.CLINGO: (_I + "compile_instance", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _I + "prune"),
    Encoding.ELIMINATION: (_I + "compile_instance", _I + "prune"),
    Encoding.PDDL: (_I + "compile_instance", _P + "_choose_actions"),
}
_EDGES = {  # realised edges: the edge_ok tables of the required edges
    Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _F + "constraint_factors"),
    Encoding.ELIMINATION: (_I + "compile_instance", _F + "constraint_factors"),
    Encoding.PDDL: (_I + "compile_instance", _P + "_choose_actions"),
}
_REQUIREMENTS = {  # requirements met: the meets tables along every edge of the consumer
    Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
    Encoding.COUNTING: (_I + "compile_instance", _F + "_requirement_factors"),
    Encoding.ELIMINATION: (_I + "compile_instance", _F + "_requirement_factors"),
    Encoding.PDDL: (
        _I + "compile_instance",
        _P + "_connect_actions",
        _P + "_finish_actions",
    ),
}

RULES: tuple[Rule, ...] = (
    Rule(
        "complete",
        "Def. 8",
        "every role of the schema is filled, by a component of the library, and nothing else is",
        ("missing-role", "unknown-component"),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM",),
            Encoding.COUNTING: (_F + "eliminate",),
            Encoding.ELIMINATION: (_F + "eliminate",),
            Encoding.PDDL: (_P + "_finish_actions",),
        },
    ),
    Rule(
        "available",
        "Section 6 (reconfiguration after a failure)",
        "a failed component fills no role",
        ("failed",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "abstraction",
        "Def. 5 (the labelling nu)",
        "a role is filled by a component carrying the role's abstraction",
        ("wrong-abstraction",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "in-schema",
        'Table 1 ("In Schema")',
        "a component whose schemas list is not empty serves only in the schemas it names",
        ("not-in-schema",),
        {Encoding.DEFINITION: (_V + "_violations",), **_CANDIDATES},
    ),
    Rule(
        "one-role-each",
        "Def. 8 (one node per role)",
        "no component fills two roles",
        ("reused",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM",),
            Encoding.COUNTING: (_F + "constraint_factors",),
            Encoding.ELIMINATION: (_F + "constraint_factors",),
            Encoding.PDDL: (_P + "_Tables.earlier", _P + "_choose_actions"),
        },
    ),
    Rule(
        "edge-realised",
        "Def. 5 and 7 (the system graph's edges)",
        "along every required edge, some requirement option of the consumer's component is "
        "provided by the provider's component",
        ("edge-unrealised",),
        {Encoding.DEFINITION: (_V + "_violations", _V + "edge_interfaces"), **_EDGES},
    ),
    Rule(
        "edge-interfaces",
        "extension (an edge's interfaces list)",
        "an edge that lists interfaces is realised, and meets requirements, only by those labels",
        ("edge-unrealised", "requirement-unmet"),
        {
            Encoding.DEFINITION: (_V + "edge_interfaces", _V + "requirement_met"),
            Encoding.CLINGO: (_I + "compile_instance", _I + "_allows"),
            Encoding.COUNTING: (_I + "compile_instance", _I + "_allows"),
            Encoding.ELIMINATION: (_I + "compile_instance", _I + "_allows"),
            Encoding.PDDL: (_I + "compile_instance", _I + "_allows"),
        },
    ),
    Rule(
        "requirement-met",
        "Def. 3 and Lemma 4",
        "every requirement of every chosen component (a topic, service or action it uses) is "
        "provided by the component of a role the consumer's role has an edge to",
        ("requirement-unmet",),
        {Encoding.DEFINITION: (_V + "_violations", _V + "requirement_met"), **_REQUIREMENTS},
    ),
    Rule(
        "any-of",
        "Def. 3 (NREA uses whichever servo command the arm offers)",
        "a requirement with several options is met by any one of them",
        ("requirement-unmet",),
        {Encoding.DEFINITION: (_V + "requirement_met",), **_REQUIREMENTS},
    ),
    Rule(
        "needs",
        'Section 5 ("NVP1 needs NCO1 and NCA1")',
        "a chosen component's needs are chosen too",
        ("needs",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_F + "constraint_factors", _F + "_needs_met"),
            Encoding.ELIMINATION: (_F + "constraint_factors", _F + "_needs_met"),
            Encoding.PDDL: (_P + "_choose_actions", _P + "_finish_actions"),
        },
    ),
    Rule(
        "excludes",
        "Section 5 (components that cannot run together)",
        "a chosen component's excludes are not chosen (either way round)",
        ("excludes",),
        {
            Encoding.DEFINITION: (_V + "_violations",),
            Encoding.CLINGO: (_S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_F + "constraint_factors",),
            Encoding.ELIMINATION: (_F + "constraint_factors",),
            Encoding.PDDL: (_P + "_Tables", _P + "_choose_actions"),
        },
    ),
    Rule(
        "one-type-per-label",
        "Def. 1 (a topic or service vertex carries one message class, Gamma)",
        "no two chosen components provide one topic, service or action label with different "
        "types (compared by their key: pkg/msg/X is pkg/X) "
        "(raw and compressed images under one name are alternatives, never chosen together)",
        ("type-clash",),
        {
            Encoding.DEFINITION: (_V + "_violations", _V + "type_clash"),
            Encoding.CLINGO: (_I + "compile_instance", _S + "PROGRAM", _S + "_facts"),
            Encoding.COUNTING: (_I + "compile_instance", _F + "constraint_factors"),
            Encoding.ELIMINATION: (_I + "compile_instance", _F + "constraint_factors"),
            Encoding.PDDL: (_I + "compile_instance", _P + "_Tables", _P + "_choose_actions"),
        },
    ),
    Rule(
        "optional-edge",
        "extension (edges only some candidates use)",
        "an optional edge need not be realised, but requirements may still be met across it",
        (),
        {
            Encoding.DEFINITION: (_V + "_violations", _V + "requirement_met"),
            Encoding.CLINGO: (_I + "compile_instance",),
            Encoding.COUNTING: (_I + "compile_instance",),
            Encoding.ELIMINATION: (_I + "compile_instance",),
            Encoding.PDDL: (_I + "compile_instance",),
        },
    ),
    Rule(
        "optional-role",
        "extension (roles a stack may leave empty: an add-on EKF, a map server under SLAM)",
        "an optional role may be left empty; an edge touching an empty role imposes nothing, "
        "but every requirement of every chosen component is still met along the remaining "
        "edges (so a consumer only that role can serve forces it to be filled)",
        (),
        {
            Encoding.DEFINITION: (_V + "_violations", _V + "requirement_met"),
            Encoding.CLINGO: (_I + "compile_instance", _E + "with_empty_choices", _S + "_Reader"),
            Encoding.COUNTING: (_I + "compile_instance", _E + "with_empty_choices"),
            Encoding.ELIMINATION: (_I + "compile_instance", _E + "with_empty_choices"),
            Encoding.PDDL: (
                _I + "compile_instance",
                _E + "with_empty_choices",
                _P + "_choose_actions",
            ),
        },
    ),
)
"""Every rule of validity, once. Adding a rule: see docs/formats.md, "Adding a rule"."""
