"""A system built of parts (:mod:`app.physics.mechanics.multibody`) as the DAE algorithms see it."""

from __future__ import annotations

from collections.abc import Mapping

from app.physics.constrained.system import ConstrainedSystem
from app.physics.mechanics.multibody.compiled import CompiledSystem


def multibody_constrained_system(model: CompiledSystem, params: Mapping[str, float]) -> ConstrainedSystem:
    """M v̇ = f + Cᵀλ with the configuration constraints' rows first and the rolling rows after (the generated
    ``dynamics`` and ``constraints`` kernels); coordinate partitioning keeps the coordinates of the independent
    speeds."""
    system = model.system
    dynamics, constraints = model.kernels()
    dependent = {system.index(name) for name in system.dependent_speeds}
    return ConstrainedSystem(
        dynamics=dynamics,
        constraints=constraints,
        parameters=model.parameter_array(params),
        coordinate_names=tuple(c.name for c in system.coordinates),
        n_holonomic=len(system.dependent_coordinates),
        n_nonholonomic=len(system.dependent_speeds) - len(system.dependent_coordinates),
        independent=tuple(i for i in range(model.n) if i not in dependent),
    )
