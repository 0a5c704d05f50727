"""The M-solution's models (Section 4): component dynamics and a schema's simulation block.

The paper's M-solution "assumes that there are dynamical models available for each of the
components" and "typical environmental models", and judges a configuration by simulating
its control loop. Here a component's model is a transfer function with optional dead time,
and a schema's ``Simulation`` says which roles form each loop (forward path, feedback path),
what the environment (plant) is, and what performance the schema requires.

Positions for error messages live in the owners' ``where`` maps (``Component.where``,
``InteroperabilitySchema.where``), so these classes stay plain values that hash by content:
two equal loops are one simulation.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

METRICS = ("settling_time", "steady_state_error", "overshoot")
"""The simulated figures, each a maximum in a schema's requirements; lower is better."""


@dataclass(frozen=True)
class TransferFunction:
    """A linear model in the Laplace domain with optional dead time: ``e^(-delay s) num/den``.

    Attributes:
        num: numerator coefficients, highest power of s first (as python-control and MATLAB).
        den: denominator coefficients, highest power first; not all zero, and at least as
            long as the numerator once leading zeros are dropped (a proper model).
        delay: dead time in seconds (>= 0).
    """

    num: tuple[float, ...]
    den: tuple[float, ...]
    delay: float = 0.0

    def __str__(self) -> str:
        text = f"({_poly(self.num)}) / ({_poly(self.den)})"
        return f"{text} e^(-{self.delay:g} s)" if self.delay else text


Matrix = tuple[tuple[float, ...], ...]
"""A matrix as its rows."""


@dataclass(frozen=True)
class StateSpace:
    """A linear model in state-space form with optional dead time, single input and output.

    ``x' = A x + B u``, ``y = C x + D u`` (python-control's ``ss(A, B, C, D)``), delayed by
    ``delay``. Validation (``formats.simchecks``) holds the shapes: ``A`` n x n, ``B`` n x 1,
    ``C`` 1 x n, ``D`` 1 x 1; simulation uses its transfer function (``analysis.lti.ss2tf``).

    Attributes:
        a, b, c, d: the matrices, each as its rows.
        delay: dead time in seconds (>= 0).
    """

    a: Matrix
    b: Matrix
    c: Matrix
    d: Matrix
    delay: float = 0.0

    def __str__(self) -> str:
        text = f"state space of order {len(self.a)}"
        return f"{text} e^(-{self.delay:g} s)" if self.delay else text


Dynamics = TransferFunction | StateSpace
"""A component's or plant's model: either form."""

UNITY = TransferFunction((1.0,), (1.0,))
"""The block of a role whose component has no dynamics: it passes its input through."""


def _poly(coefficients: Sequence[float]) -> str:
    order = len(coefficients) - 1
    terms = []
    for i, c in enumerate(coefficients):
        power = order - i
        if c == 0 and len(coefficients) > 1:
            continue
        s = "" if power == 0 else ("s" if power == 1 else f"s^{power}")
        terms.append(f"{c:g}" + (f" {s}" if s else ""))
    return " + ".join(terms) if terms else "0"


@dataclass(frozen=True)
class ControlLoop:
    """One control loop of a schema (the paper's Fig. 2), by role names.

    Attributes:
        name: the loop's name, unique within the schema.
        forward: the roles from the error signal to the plant input, in order
            (e.g. controller, actuator).
        plant: the environment model the loop acts on.
        feedback: the roles from the plant output back to the comparison, in order
            (e.g. sensor, perception).
    """

    name: str
    forward: tuple[str, ...]
    plant: Dynamics
    feedback: tuple[str, ...] = ()

    @property
    def roles(self) -> tuple[str, ...]:
        """Return the loop's roles, forward path first."""
        return (*self.forward, *self.feedback)


@dataclass(frozen=True)
class PerformanceRequirements:
    """A schema's performance requirements: maxima, each optional.

    Attributes:
        settling_time: the longest acceptable settling time, seconds.
        steady_state_error: the largest acceptable ``|1 - y_final / reference|``.
        overshoot: the largest acceptable overshoot, percent.
    """

    settling_time: float | None = None
    steady_state_error: float | None = None
    overshoot: float | None = None

    def limits(self) -> dict[str, float]:
        """Return metric -> maximum for the requirements that are set."""
        return {m: v for m in METRICS if (v := getattr(self, m)) is not None}


@dataclass(frozen=True)
class Simulation:
    """A schema's simulation block: its loops, the reference step, the horizon, requirements.

    Attributes:
        loops: the control loops, in file order.
        reference: the size of the reference step.
        duration: how long to simulate, seconds.
        requirements: the maxima every loop must meet.
    """

    loops: tuple[ControlLoop, ...]
    reference: float = 1.0
    duration: float = 10.0
    requirements: PerformanceRequirements = PerformanceRequirements()
