"""ROS 2 quality of service: the profile of one endpoint, and whether two profiles can match.

A ROS 2 publisher and subscription on the same topic only exchange messages when the
publisher's *offered* QoS satisfies the subscription's *requested* QoS (DDS "request vs
offered"). A mismatch is silent at run time (no error, no data), which is why rosreconf checks
it before launch (``validate``) and on a live graph (``inspect --ros2``).

The rule is rmw_dds_common's ``qos_profile_check_compatible`` (src/qos.cpp), which every DDS
rmw uses for ``rmw_qos_profile_check_compatible``; each failed clause is one reason::

    clause                                              reason (``Incompatibility.policy``)
    --------------------------------------------------  -------------------------------------
    publisher best effort, subscription reliable        reliability
    publisher volatile, subscription transient local    durability
    subscription has a deadline, publisher has none     deadline
    both have deadlines, subscription's is shorter      deadline
    publisher automatic, subscription manual by topic   liveliness
    subscription has a lease duration, publisher none   lease_duration
    both have leases, subscription's is shorter         lease_duration

"No deadline" / "no lease" is ``None`` here: rmw's default ``{0, 0}`` when a profile is written
by hand, DDS's infinity when it was read from discovery (rmw_cyclonedds ``dds_duration_to_rmw``);
both mean the same and are compared the same. History and depth never make endpoints
incompatible; they are kept for the record.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Any


class Reliability(enum.StrEnum):
    """Whether lost samples are repaired (``reliable``) or not (``best_effort``)."""

    RELIABLE = "reliable"
    BEST_EFFORT = "best_effort"


class Durability(enum.StrEnum):
    """Whether late-joining subscriptions get earlier samples (``transient_local``)."""

    VOLATILE = "volatile"
    TRANSIENT_LOCAL = "transient_local"


class Liveliness(enum.StrEnum):
    """How a publisher shows it is alive; ROS 2 uses ``automatic`` and ``manual_by_topic``."""

    AUTOMATIC = "automatic"
    MANUAL_BY_TOPIC = "manual_by_topic"


class History(enum.StrEnum):
    """How many samples are kept: the last ``depth`` or all."""

    KEEP_LAST = "keep_last"
    KEEP_ALL = "keep_all"


QOS_KEYS = ("reliability", "durability", "deadline", "liveliness", "lease_duration", "depth")
"""The keys a QoS mapping (library file, snapshot) may have; ``depth: 0`` means keep all."""


@dataclass(frozen=True)
class QosProfile:
    """The QoS of one publisher or subscription, in the rmw's terms.

    The defaults are ``rmw_qos_profile_default`` (reliable, volatile, keep last 10, no
    deadline, automatic liveliness without lease), what rclcpp uses unless told otherwise.

    Attributes:
        reliability: reliable or best effort.
        durability: volatile or transient local.
        deadline: seconds between samples promised (publisher) or expected (subscription);
            None for none.
        liveliness: automatic or manual by topic.
        lease_duration: seconds within which liveliness must be asserted; None for none.
        history: keep last or keep all.
        depth: the keep-last depth (0 with keep all); None when unknown: DDS discovery does
            not carry the history, so a profile read from a live graph has None.
    """

    reliability: Reliability = Reliability.RELIABLE
    durability: Durability = Durability.VOLATILE
    deadline: float | None = None
    liveliness: Liveliness = Liveliness.AUTOMATIC
    lease_duration: float | None = None
    history: History = History.KEEP_LAST
    depth: int | None = 10

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON/YAML shape (``QOS_KEYS``; ``depth: 0`` for keep all, null unknown)."""
        return {
            "reliability": str(self.reliability),
            "durability": str(self.durability),
            "deadline": self.deadline,
            "liveliness": str(self.liveliness),
            "lease_duration": self.lease_duration,
            "depth": self.depth if self.depth is None or self.history is History.KEEP_LAST else 0,
        }

    @staticmethod
    def from_dict(doc: dict[str, Any]) -> QosProfile:
        """Build a profile from a (schema-checked) mapping; missing keys take the defaults.

        Raises:
            ValueError: a value is not one of the allowed ones (the message says which).
        """
        unknown = sorted(set(doc) - set(QOS_KEYS))
        if unknown:
            raise ValueError(f"unknown QoS key(s) {', '.join(unknown)} (allowed: {QOS_KEYS})")
        raw = doc.get("depth", 10)
        depth = None if raw is None else int(raw)
        return QosProfile(
            reliability=Reliability(doc.get("reliability", Reliability.RELIABLE)),
            durability=Durability(doc.get("durability", Durability.VOLATILE)),
            deadline=_seconds(doc.get("deadline"), "deadline"),
            liveliness=Liveliness(doc.get("liveliness", Liveliness.AUTOMATIC)),
            lease_duration=_seconds(doc.get("lease_duration"), "lease_duration"),
            history=History.KEEP_ALL if depth == 0 else History.KEEP_LAST,
            depth=depth,
        )

    def __str__(self) -> str:
        parts = [str(self.reliability), str(self.durability)]
        if self.deadline is not None:
            parts.append(f"deadline {self.deadline:g} s")
        parts.append(f"liveliness {self.liveliness}")
        if self.lease_duration is not None:
            parts.append(f"lease {self.lease_duration:g} s")
        return ", ".join(parts)


def _seconds(value: object, what: str) -> float | None:
    """Return a duration in seconds (None for none), refusing negatives and non-numbers."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{what} must be a number of seconds or null, not {value!r}")
    if not math.isfinite(value) or value <= 0:
        raise ValueError(f"{what} must be a positive, finite number of seconds (or null)")
    return float(value)


@dataclass(frozen=True)
class Incompatibility:
    """One reason a publisher's QoS cannot serve a subscription's.

    Attributes:
        policy: ``reliability``, ``durability``, ``deadline``, ``liveliness`` or
            ``lease_duration``.
        message: the reason in rmw's words, with both sides' values.
    """

    policy: str
    message: str


def incompatibilities(offered: QosProfile, requested: QosProfile) -> tuple[Incompatibility, ...]:
    """Return why a publisher with ``offered`` QoS cannot match a subscription's ``requested``.

    Empty when they match. The clauses and their order are rmw_dds_common's
    ``qos_profile_check_compatible`` (errors only: its warnings concern "system default"
    values, which a profile here never has).
    """
    found: list[Incompatibility] = []
    if offered.reliability is Reliability.BEST_EFFORT and (
        requested.reliability is Reliability.RELIABLE
    ):
        found.append(
            Incompatibility("reliability", "best effort publisher and reliable subscription")
        )
    if offered.durability is Durability.VOLATILE and (
        requested.durability is Durability.TRANSIENT_LOCAL
    ):
        found.append(
            Incompatibility("durability", "volatile publisher and transient local subscription")
        )
    pd, sd = offered.deadline, requested.deadline
    if pd is None and sd is not None:
        found.append(
            Incompatibility(
                "deadline", f"subscription has a deadline ({sd:g} s), but publisher does not"
            )
        )
    elif pd is not None and sd is not None and sd < pd:
        found.append(
            Incompatibility(
                "deadline",
                f"subscription deadline ({sd:g} s) is less than publisher deadline ({pd:g} s)",
            )
        )
    if offered.liveliness is Liveliness.AUTOMATIC and (
        requested.liveliness is Liveliness.MANUAL_BY_TOPIC
    ):
        found.append(
            Incompatibility(
                "liveliness",
                "publisher's liveliness is automatic and subscription's is manual by topic",
            )
        )
    pl, sl = offered.lease_duration, requested.lease_duration
    if pl is None and sl is not None:
        found.append(
            Incompatibility(
                "lease_duration",
                f"subscription has a liveliness lease duration ({sl:g} s), but publisher does not",
            )
        )
    elif pl is not None and sl is not None and sl < pl:
        found.append(
            Incompatibility(
                "lease_duration",
                f"subscription liveliness lease duration ({sl:g} s) is less than "
                f"publisher's ({pl:g} s)",
            )
        )
    return tuple(found)
