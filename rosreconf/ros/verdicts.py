"""Read one conformance check per component: failed, missing or seen (the watcher's verdicts).

What the live graph says of each component of the configuration, before anything is done:

    finding of the component                          verdict
    ------------------------------------------------  ------------------------------------------
    ``dead-node`` (registered, not answering: a         failed ("registered but not answering")
    SIGKILLed ROS 1 node lingers in the master)
    ``missing-node``, and this watcher saw it alive     failed ("gone")
    ``missing-node``, never seen                        missing (it may still be starting)
    anything else                                       seen

Components judged elsewhere are passed over: one a person was asked to restart (the
actuator's ``awaited``) and one whose name another node holds (``clashes``). What is missing
is said once per set of stuck components and reason (``Missing``). Nothing here prints; the
watcher says what it acts on.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from dataclasses import dataclass, field

from rosreconf.ros.actuator import Actuator
from rosreconf.ros.conformance import Conformance


@dataclass(frozen=True)
class Verdicts:
    """What one check says of each component (see the module docstring).

    Attributes:
        failed: component -> why it failed, in configuration order.
        missing: components never seen and not running.
        seen: components running as they should.
    """

    failed: dict[str, str] = field(default_factory=dict)
    missing: list[str] = field(default_factory=list)
    seen: set[str] = field(default_factory=set)


def judge(
    check: Conformance,
    components: Collection[str],
    seen_before: Collection[str],
    judged_elsewhere: Collection[str],
) -> Verdicts:
    """Return the verdict on each of ``components`` from ``check``."""
    out = Verdicts()
    for comp in components:
        if comp in judged_elsewhere:
            continue
        codes = {f.code for f in check.findings if f.component == comp}
        if "dead-node" in codes:
            out.failed[comp] = "registered but not answering"
        elif "missing-node" in codes and comp in seen_before:
            out.failed[comp] = "gone"
        elif "missing-node" in codes:
            out.missing.append(comp)
        else:
            out.seen.add(comp)
    return out


@dataclass
class Missing:
    """Say which components are not running and why, once per change of either.

    Attributes:
        said: the stuck components last said, and why.
    """

    said: tuple[str, ...] = ()

    def report(
        self,
        missing: list[str],
        actuator: Actuator,
        apply: bool,
        say: Callable[..., None],
    ) -> list[str]:
        """Say what is stuck (launched and never up, or not started without ``apply``);
        return the others, to start now: what never came up is not launched on every poll.
        """
        stuck, why = actuator.not_running(missing)
        if not apply:
            stuck, why = missing, "use --apply to start"
        if stuck and (*stuck, why) != self.said:
            self.said = (*stuck, why)
            say("missing", f"not running: {', '.join(stuck)} ({why})", components=stuck)
        return [c for c in missing if c not in stuck]
