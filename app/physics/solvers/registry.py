"""Every integration method, by API name, with its facts as data (:class:`MethodSpec`).

The registry drives the automatic step choice, :func:`make_integrator`, the
scene controls (:mod:`.controls`), the request bound on work, the benchmark and
the convergence-order tests. The keys are API contracts.
"""

from __future__ import annotations

from app.physics.solvers.base import Integrator
from app.physics.solvers.dormand_prince import DOPRI5_SPEC
from app.physics.solvers.rk4 import RK4_SPEC
from app.physics.solvers.spec import MAX_STEPS_PER_FRAME, MethodSpec, Supports
from app.physics.solvers.splitting import SPLITTING_SPECS

METHODS: dict[str, MethodSpec] = {
    spec.name: spec
    for spec in (SPLITTING_SPECS[4], SPLITTING_SPECS[2], RK4_SPEC, DOPRI5_SPEC, SPLITTING_SPECS[6], SPLITTING_SPECS[8])
}

#: Largest h·ω_max each fixed-step method is allowed by the automatic step choice (from the specs).
STEP_RATIO: dict[str, float] = {name: spec.step_ratio for name, spec in METHODS.items() if spec.step_ratio is not None}

__all__ = [
    "MAX_STEPS_PER_FRAME",
    "METHODS",
    "STEP_RATIO",
    "MethodSpec",
    "Supports",
    "automatic_steps_per_frame",
    "make_integrator",
    "method_spec",
]


def method_spec(method: str) -> MethodSpec:
    """The spec of ``method`` (ValueError naming the field for an unknown one)."""
    try:
        return METHODS[method]
    except KeyError:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}") from None


def automatic_steps_per_frame(method: str, fastest_rate_rad_s: float, frame_dt_s: float) -> int:
    """Steps per frame so that ``h · fastest_rate ≤ STEP_RATIO[method]`` (at most 4096)."""
    return method_spec(method).automatic_steps_per_frame(fastest_rate_rad_s, frame_dt_s)


def make_integrator(
    method: str,
    *,
    steps_per_frame: int | None = None,
    rtol: float | None = None,
    fastest_rate_rad_s: float = 0.0,
    frame_dt_s: float = 1 / 60,
) -> Integrator:
    """Build an integrator by name; ``steps_per_frame=None`` picks it from the fastest rate."""
    return method_spec(method).build(
        steps_per_frame=steps_per_frame, rtol=rtol, fastest_rate_rad_s=fastest_rate_rad_s, frame_dt_s=frame_dt_s
    )
