"""Integrators: one per module, each a small object separate from the model it steps.

* :mod:`.rk4` — classical fixed-step RK4 with a projection hook;
* :mod:`.dormand_prince` — adaptive 5(4) pair with dense output and events;
* :mod:`.splitting` — geometric splitting for rigid bodies (order 2 and 4);
* :mod:`.registry` — every method's facts as data (:class:`MethodSpec`);
* :mod:`.status` — how a run ended: codes, names, the text a student reads;
* :mod:`.system` — the contract a model fills: right-hand side, events with
  reset maps, constraints, the rigid-body torque capability;
* :mod:`.constraints` — projection onto ``g(q) = 0`` and Lagrange multipliers;
* :mod:`.solve` — the one place a model, an integrator and a step choice meet;
* :mod:`.step_choice` — pilot runs that measure a method's error constant;
* :mod:`.step_policy` — which integrator and step answer a model's controls
  (the controller, apart from the model and the integrators);
* :mod:`.integrated_model` — the model contract of :mod:`app.physics.core.model`
  for motion found by integration.

Hot loops are numba kernels (cached on disk, warmed at server start) with a
pure-Python twin of the same source (:mod:`.kernels`).
"""

from app.physics.solvers.base import EventRecord, FixedStepIntegrator, FramesOutcome, Integrator
from app.physics.solvers.dormand_prince import DormandPrince
from app.physics.solvers.registry import METHODS, MethodSpec, automatic_steps_per_frame, make_integrator
from app.physics.solvers.rk4 import RK4
from app.physics.solvers.solve import LiveRun, SimulationResult, simulate
from app.physics.solvers.splitting import RigidBodySplitting
from app.physics.solvers.system import Constraints, Events, OdeSystem

__all__ = [
    "METHODS",
    "Constraints",
    "DormandPrince",
    "EventRecord",
    "Events",
    "FixedStepIntegrator",
    "FramesOutcome",
    "Integrator",
    "LiveRun",
    "MethodSpec",
    "OdeSystem",
    "RK4",
    "RigidBodySplitting",
    "SimulationResult",
    "automatic_steps_per_frame",
    "make_integrator",
    "simulate",
]
