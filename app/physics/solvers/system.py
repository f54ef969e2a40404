"""What an integrator needs to know about a model: its compiled pieces and parameters.

Beyond the right-hand side a system may declare

* :class:`Events` — several event functions, each with a direction, terminal or
  not, and optionally a reset map applied at the event (an impact, a mode
  switch) after which integration continues from the reset state;
* :class:`Constraints` — position constraints ``g(q) = 0`` with their Jacobian
  ``G = ∂g/∂q``, for projection after each step (see :mod:`.constraints` for the
  shared projection and the Lagrange-multiplier helper a right-hand side uses);
* a discrete *mode* (stick or slip, say): a state slot with zero derivative
  that the right-hand side reads and only a reset map changes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.solvers.kernels import Kernel

#: What happens at an event (the codes the kernels see).
EVENT_RECORD, EVENT_STOP, EVENT_RESET = 0, 1, 2


@dataclass(frozen=True)
class Events:
    """``m`` event functions computed by one kernel ``functions(t, y, p, g_out)`` (``g_out`` shape (m,)).

    Event ``i`` happens where ``g_i`` changes sign in ``directions[i]`` (+1
    rising, −1 falling, 0 either; a start exactly on ``g_i = 0`` does not
    count). Then, if ``terminal[i]``, the run stops there; if ``resets[i]``,
    ``reset(t, y, p, i)`` changes the state in place and integration restarts
    from it; otherwise the event is only recorded.

    Sign changes are looked for at each step's ends and middle, so an excursion
    of ``g_i`` away from zero and back that fits inside half a step is missed
    (as in every sign-change event finder): ``max_step_s`` bounds the step for
    models where that can happen (a bouncing ball's flights shrink geometrically).
    """

    functions: Kernel
    directions: tuple[int, ...]
    terminal: tuple[bool, ...]
    reset: Kernel | None = None
    #: Which events apply the reset map (default: none).
    resets: tuple[bool, ...] | None = None
    #: Longest step (s) an integrator may take while watching these events.
    max_step_s: float = math.inf

    def __post_init__(self) -> None:
        m = len(self.directions)
        if m == 0:
            raise ValueError("events: give at least one event function (or no Events at all)")
        if any(d not in (-1, 0, 1) for d in self.directions):
            raise ValueError(f"events: every direction must be +1, -1 or 0 (got {self.directions})")
        if len(self.terminal) != m:
            raise ValueError(f"events: terminal has {len(self.terminal)} entries for {m} event functions")
        resets = self.resets if self.resets is not None else (False,) * m
        if len(resets) != m:
            raise ValueError(f"events: resets has {len(resets)} entries for {m} event functions")
        if any(resets) and self.reset is None:
            raise ValueError("events: resets asks for a reset map but reset is None")
        if not self.max_step_s > 0.0:
            raise ValueError(f"events: max_step_s must be a positive time in s (got {self.max_step_s!r})")
        if any(r and t for r, t in zip(resets, self.terminal)):
            raise ValueError("events: an event either stops the run (terminal) or resets the state, not both")

    @property
    def count(self) -> int:
        return len(self.directions)

    @property
    def has_resets(self) -> bool:
        return self.resets is not None and any(self.resets)

    def direction_array(self) -> np.ndarray:
        """Directions as the int64 array the kernels take."""
        return np.array(self.directions, dtype=np.int64)

    def action_array(self) -> np.ndarray:
        """Per event: ``EVENT_STOP``, ``EVENT_RESET`` or ``EVENT_RECORD`` (int64, shape (m,))."""
        resets = self.resets if self.resets is not None else (False,) * self.count
        return np.array(
            [EVENT_STOP if t else EVENT_RESET if r else EVENT_RECORD for t, r in zip(self.terminal, resets)],
            dtype=np.int64,
        )


@dataclass(frozen=True)
class Constraints:
    """``m`` position constraints ``g(q) = 0`` on ``q = y[0:n_positions]``.

    ``function(y, p, g_out, G_out)`` writes the residuals (m,) and the Jacobian
    ``G = ∂g/∂q`` (m, n_positions). The velocities are ``v = y[n_positions:2·n_positions]``,
    so ``ġ = G v``. With ``project`` the integrators move each step's end state
    back onto ``g = 0`` and ``G v = 0`` (minimum-norm corrections).
    """

    function: Kernel
    n_constraints: int
    n_positions: int
    project: bool = True

    def __post_init__(self) -> None:
        if self.n_constraints < 1 or self.n_positions < 1:
            raise ValueError("constraints: n_constraints and n_positions must be ≥ 1")
        if self.n_constraints > self.n_positions:
            raise ValueError(
                f"constraints: {self.n_constraints} constraints on {self.n_positions} positions over-determine them"
            )

    def residuals(self, states: np.ndarray, parameters: np.ndarray) -> np.ndarray:
        """``g(q)`` along ``states`` (N, n) → (N, m), with the pure-Python kernel."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        out = np.empty((states.shape[0], self.n_constraints))
        jacobian = np.empty((self.n_constraints, self.n_positions))
        for row, state in zip(out, states):
            self.function.python(np.ascontiguousarray(state), parameters, row, jacobian)
        return out


@dataclass(frozen=True)
class OdeSystem:
    """A first-order system ``dy/dt = rhs(t, y, p)`` ready for the integrators.

    ``parameters`` is the flat float array ``p`` handed to every kernel.
    ``project`` (optional) restores the model's own invariants after a step
    (unit quaternion, say). ``events`` and ``constraints`` are described above.

    ``torque`` is a capability: set by a rigid body about a fixed point
    (``p[0:3]`` = principal moments about it, state ``[q_wxyz, ω_body]``), it
    is what makes the geometric splitting method applicable; methods that need
    it (``MethodSpec.needs_torque``) refuse a system without it.
    """

    rhs: Kernel
    parameters: np.ndarray
    state_names: tuple[str, ...]
    project: Kernel | None = None
    events: Events | None = None
    constraints: Constraints | None = None
    torque: Kernel | None = None

    def __post_init__(self) -> None:
        if self.constraints is not None and 2 * self.constraints.n_positions > len(self.state_names):
            raise ValueError(
                f"constraints: {self.constraints.n_positions} positions and as many velocities need at least "
                f"{2 * self.constraints.n_positions} state slots (got {len(self.state_names)})"
            )

    @property
    def n_state(self) -> int:
        return len(self.state_names)
