"""What an integrator needs to know about a model: its compiled pieces and parameters."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.physics.solvers.kernels import Kernel


@dataclass(frozen=True)
class OdeSystem:
    """A first-order system ``dy/dt = rhs(t, y, p)`` ready for the integrators.

    ``parameters`` is the flat float array ``p`` handed to every kernel.
    ``project`` (optional) restores the model's constraints after a step (unit
    quaternion, constraint manifold). ``event`` (optional) stops an adaptive
    run where it changes sign in ``event_direction``. ``torque`` is set by rigid
    bodies about a fixed point (``p[0:3]`` = principal moments about it) and
    makes the geometric splitting integrator available.
    """

    rhs: Kernel
    parameters: np.ndarray
    state_names: tuple[str, ...]
    project: Kernel | None = None
    event: Kernel | None = None
    event_direction: int = 0
    torque: Kernel | None = None

    @property
    def n_state(self) -> int:
        return len(self.state_names)
