"""What a method is, as data: order, cost, step rule and what it supports.

Each integrator module declares the :class:`MethodSpec` of the method(s) it
implements next to the code; :mod:`.registry` collects them. Everything that
needs a fact about a method (the automatic step, the controls, the request
bound on work, the benchmark, the convergence tests) reads it here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from app.physics.solvers.base import Integrator
    from app.physics.solvers.system import OdeSystem

#: Most steps per frame the automatic choice (and the controls) allow.
MAX_STEPS_PER_FRAME = 4096


def steps_for_ratio(step_ratio: float, fastest_rate_rad_s: float, frame_dt_s: float) -> int:
    """Fewest steps per frame with ``h · fastest_rate ≤ step_ratio`` (1 … :data:`MAX_STEPS_PER_FRAME`)."""
    if not (math.isfinite(fastest_rate_rad_s) and fastest_rate_rad_s >= 0.0):
        raise ValueError(
            f"the fastest rate must be a finite number ≥ 0 rad/s to choose a step (got {fastest_rate_rad_s!r})"
        )
    needed = math.ceil(fastest_rate_rad_s * frame_dt_s / step_ratio - 1e-9)
    return int(min(max(needed, 1), MAX_STEPS_PER_FRAME))


@dataclass(frozen=True)
class Supports:
    """What a method can do with an :class:`~app.physics.solvers.system.OdeSystem`."""

    #: Event functions (located; terminal ones stop the run).
    events: bool = False
    #: Reset maps at events (impacts, mode switches); integration restarts from the reset state.
    reset_maps: bool = False
    #: The model's ``project`` hook after each step.
    projection: bool = False
    #: Position/velocity projection onto ``g(q) = 0`` built from the constraint and its Jacobian.
    constraints: bool = False


@dataclass(frozen=True)
class MethodSpec:
    """The facts of one integration method (``name`` is the API identifier)."""

    name: str
    #: Label in the one-line description of a run (``stats.description``).
    label: str
    #: Shorter label for plots (the benchmark).
    short_label: str
    #: One sentence for the method menu (shown in ``GET /api/scenes``).
    description: str
    #: Global order of accuracy (measured by tests/physics/solvers/test_registry.py).
    order: int
    #: Right-hand-side (or torque) evaluations per step (per accepted attempt for adaptive methods).
    evals_per_step: int
    #: Inner sub-steps per step, for the request bound on work (splitting4: five Strang steps).
    substeps_per_step: int
    adaptive: bool
    #: Preserves the geometry of the flow (rotations stay rotations, energy error bounded).
    geometric: bool
    #: Largest ``h · ω_max`` the automatic step choice allows (fixed-step methods only).
    step_ratio: float | None
    supports: Supports
    #: Needs a rigid body about a fixed point: the system's ``torque`` kernel.
    needs_torque: bool
    #: Builds the integrator: ``factory(steps_per_frame=…)`` (fixed step) or ``factory(rtol=…)`` (adaptive).
    factory: Callable[..., Integrator]

    def __post_init__(self) -> None:
        if self.adaptive == (self.step_ratio is not None):
            raise ValueError(f"{self.name}: step_ratio is for fixed-step methods only, and they need one")

    def automatic_steps_per_frame(self, fastest_rate_rad_s: float, frame_dt_s: float) -> int:
        """Steps per frame so that ``h · fastest_rate ≤ step_ratio``."""
        if self.step_ratio is None:
            raise ValueError(f"{self.name} is adaptive: it chooses its own steps")
        return steps_for_ratio(self.step_ratio, fastest_rate_rad_s, frame_dt_s)

    def build(
        self,
        *,
        steps_per_frame: int | None = None,
        rtol: float | None = None,
        fastest_rate_rad_s: float = 0.0,
        frame_dt_s: float = 1 / 60,
    ) -> Integrator:
        """The integrator; ``steps_per_frame=None`` picks it from the fastest rate, ``rtol=None`` means 1e-8."""
        if self.adaptive:
            return self.factory(rtol=1e-8 if rtol is None else rtol)
        if steps_per_frame is None:
            steps_per_frame = self.automatic_steps_per_frame(fastest_rate_rad_s, frame_dt_s)
        return self.factory(steps_per_frame=steps_per_frame)

    def check_system(self, system: OdeSystem) -> None:
        """Raise ValueError naming what ``system`` needs that this method cannot do."""
        if self.needs_torque and system.torque is None:
            raise ValueError(
                f"method {self.name} needs a rigid body about a fixed point (a system with a torque kernel); "
                "choose rk4 or dopri5 for this model"
            )
        if system.events is not None and not self.supports.events:
            raise ValueError(
                f"method {self.name} does not handle events; the system has {system.events.count} (use dopri5)"
            )
        if system.events is not None and system.events.has_resets and not self.supports.reset_maps:
            raise ValueError(f"method {self.name} does not apply reset maps at events (use dopri5)")
        if system.constraints is not None and system.constraints.project and not self.supports.constraints:
            raise ValueError(f"method {self.name} cannot project onto the system's constraints (use rk4 or dopri5)")
