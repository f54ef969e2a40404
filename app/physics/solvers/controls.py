"""Integration controls a student can touch: method, steps per frame, tolerance.

The same three :class:`Parameter` definitions serve the scene controls, the
``simulate`` API fields and their validation, so the names and limits are
written once.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from app.physics.core.parameters import Parameter
from app.physics.solvers.base import Integrator
from app.physics.solvers.registry import METHODS, make_integrator

if TYPE_CHECKING:
    from app.physics.solvers.step_choice import AccuracyTarget

AUTO = "auto"
CONTROL_NAMES = ("method", "steps_per_frame", "rtol", "integrator", "baumgarte_alpha_1_s", "baumgarte_beta_1_s")


def integration_parameters(
    methods: tuple[str, ...],
    *,
    default_method: str,
    target: AccuracyTarget | None = None,
    auto_methods: tuple[str, ...] | None = None,
) -> tuple[Parameter, ...]:
    """``method`` (with ``auto``), ``steps_per_frame`` (0 = automatic) and ``rtol``, described as the code chooses.

    Without an accuracy ``target``, ``auto`` is ``default_method`` and 0 steps per frame follow the fixed ratio h·ω_max
    (:func:`integrator_from_controls`). With one (:func:`~app.physics.solvers.step_policy.choose_integrator`),
    ``auto`` is the cheapest of ``auto_methods`` (default: ``methods``) meeting it, and 0 steps per frame the fewest
    that meet it.
    """
    unknown = set(methods) - set(METHODS)
    if unknown:
        raise ValueError(f"unknown methods {sorted(unknown)}")
    described = "; ".join(f"{m}: {METHODS[m].description}" for m in methods)
    if target is None:
        rk4_ratio = METHODS["rk4"].step_ratio
        automatic_method = f"{AUTO} = {default_method}"
        automatic_steps = f"0 chooses h from the fastest time scale (RK4: h·ω_max ≤ {rk4_ratio:g})"
    else:
        candidates = auto_methods or methods
        goal = f"the accuracy target of {target.format(target.error)} over the run ({target.measure})"
        automatic_method = (
            f"{AUTO} = {candidates[0]}"
            if len(candidates) == 1
            else f"{AUTO} = whichever of {', '.join(candidates)} meets {goal} at least cost"
        )
        automatic_steps = (
            f"0 chooses the fewest steps (the loosest tolerance) that meet {goal}, measured by two short pilot runs "
            "(a live scene uses h·ω_max until its pilot has run)"
        )
    return (
        Parameter(
            "method",
            "",
            AUTO,
            kind="choice",
            choices=(AUTO, *methods),
            label="integrator",
            description=f"Integration method ({automatic_method}). {described}",
        ),
        Parameter(
            "steps_per_frame",
            "",
            0,
            0,
            4096,
            kind="int",
            step=1,
            label="steps per frame",
            description=f"Fixed steps per displayed frame; {automatic_steps}",
        ),
        Parameter(
            "rtol",
            "",
            1e-8,
            1e-12,
            1e-3,
            scale="log",
            label="tolerance",
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
        method,
        steps_per_frame=steps,
        rtol=controls.get("rtol"),
        fastest_rate_rad_s=fastest_rate_rad_s,
        frame_dt_s=frame_dt_s,
    )
