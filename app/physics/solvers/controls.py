"""Integration controls a student can touch: method, steps per frame, tolerance.

The same three :class:`Parameter` definitions serve the scene controls, the
``simulate`` API fields and their validation, so the names and limits are
written once.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from app.physics.core.parameters import Parameter
from app.physics.solvers.base import Integrator
from app.physics.solvers.registry import METHODS, make_integrator

AUTO = "auto"
CONTROL_NAMES = ("method", "steps_per_frame", "rtol", "integrator", "baumgarte_alpha_1_s", "baumgarte_beta_1_s")


def integration_parameters(methods: tuple[str, ...], *, default_method: str) -> tuple[Parameter, ...]:
    """``method`` (with ``auto``), ``steps_per_frame`` (0 = automatic) and ``rtol``."""
    unknown = set(methods) - set(METHODS)
    if unknown:
        raise ValueError(f"unknown methods {sorted(unknown)}")
    described = "; ".join(f"{m}: {METHODS[m].description}" for m in methods)
    rk4_ratio = METHODS["rk4"].step_ratio
    return (
        Parameter(
            "method", "", AUTO, kind="choice", choices=(AUTO, *methods), label="integrator",
            description=f"Integration method ({AUTO} = {default_method}). {described}",
        ),
        Parameter(
            "steps_per_frame", "", 0, 0, 4096, kind="int", step=1, label="steps per frame",
            description=f"Fixed steps per displayed frame; 0 chooses h from the fastest time scale (RK4: h·ω_max ≤ {rk4_ratio:g})",
        ),
        Parameter(
            "rtol", "", 1e-8, 1e-12, 1e-3, scale="log", label="tolerance",
            description=f"Relative tolerance of the adaptive method ({_adaptive_methods()} only)",
        ),
    )


def _adaptive_methods() -> str:
    return ", ".join(name for name, spec in METHODS.items() if spec.adaptive)


def integrator_from_controls(
    controls: Mapping[str, Any], *, default_method: str, fastest_rate_rad_s: float, frame_dt_s: float
) -> Integrator:
    """Build the integrator the validated controls ask for (``auto`` → ``default_method``)."""
    method = controls.get("method", AUTO)
    if method == AUTO:
        method = default_method
    steps = controls.get("steps_per_frame", 0) or None
    return make_integrator(
        method, steps_per_frame=steps, rtol=controls.get("rtol"),
        fastest_rate_rad_s=fastest_rate_rad_s, frame_dt_s=frame_dt_s,
    )
