"""Integrators: one per module, each a small object separate from the model it steps.

* :mod:`.rk4` — classical fixed-step RK4 with a projection hook;
* :mod:`.dormand_prince` — adaptive 5(4) pair with dense output and events;
* :mod:`.splitting` — geometric splitting for rigid bodies (order 2 and 4);
* :mod:`.solve` — the one place a model, an integrator and a step choice meet.

Hot loops are numba kernels (cached on disk, warmed at server start) with a
pure-Python twin of the same source (:mod:`.kernels`).
"""

from app.physics.solvers.base import FixedStepIntegrator, FramesOutcome, Integrator
from app.physics.solvers.dormand_prince import DormandPrince
from app.physics.solvers.rk4 import RK4
from app.physics.solvers.solve import (
    METHODS,
    LiveRun,
    SimulationResult,
    automatic_steps_per_frame,
    make_integrator,
    simulate,
)
from app.physics.solvers.splitting import RigidBodySplitting
from app.physics.solvers.system import OdeSystem

__all__ = [
    "METHODS",
    "DormandPrince",
    "FixedStepIntegrator",
    "FramesOutcome",
    "Integrator",
    "LiveRun",
    "OdeSystem",
    "RK4",
    "RigidBodySplitting",
    "SimulationResult",
    "automatic_steps_per_frame",
    "make_integrator",
    "simulate",
]
