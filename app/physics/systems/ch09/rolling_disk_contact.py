"""Where a disk rolling on a floor stops being one: the floor's normal force, lift-off and the fall.

Both rolling-disk models (chapter 9's independent speeds, :mod:`.rolling_disk_model`; chapter 8's multiplier rows,
:mod:`app.physics.systems.ch08.rolling_disk_constrained_model`) keep the rim on the floor by construction, so they
would go on "rolling" where a real disk cannot. This module is their one rule for where the model ends:

* the floor can only push. Its normal force N (N, up) follows from the centre's height z_G = r cos θ:
  N − m g = m z̈_G = −m r (θ̈ sin θ + θ̇² cos θ). Where N < 0 the floor would have to pull the disk down: the disk
  lifts off (the centre would have to drop faster than gravity can make it) — status ``lift_off``;
* past :data:`FALLEN_LEAN_DEG` of lean the disk has fallen: a real one slaps down flat and slides, the equations
  would keep it glued to the floor by its edge (and through it) — status ``fallen``.

θ̈ of the uniform thin disk (moments m r²/4 transverse, m r²/2 axial about its centre) rolling without slip comes from
the lean row of its equations in redundant coordinates (:mod:`app.physics.systems.ch08.rolling_disk_constrained`):
(m r²/4 + m r²) θ̈ = f_θ + m r² cos θ ψ̇ φ̇ once ẍ, ÿ are taken from the differentiated rolling rows, that is

    θ̈ = sin θ cos θ ψ̇² + (6/5) cos θ ψ̇ φ̇ + (4 g / 5 r) sin θ       (rad/s²)

(ψ̇ heading rate, φ̇ spin rate; the tests check it against the derived Kane equations). At θ = 0 this leaves
N = m (g − r θ̇²): a disk rocked upright faster than √(g/r) leaves the floor at once.

States are the models' shared layout (x, y, ψ, θ, φ, ẋ, ẏ, ψ̇, θ̇, φ̇) in m, rad, m/s, rad/s.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.solvers.integrated_model import ModelLimit

#: Lean (deg) past which the disk has fallen and the rolling model no longer describes it.
FALLEN_LEAN_DEG = 85.0
#: ``stats.status`` of a run stopped by the fall, and by the floor's giving way (it would have to pull).
FALLEN, LIFT_OFF = "fallen", "lift_off"
#: A normal force below −this fraction of its scale m (|g| + r (θ̇² + |θ̈|)) is a pull, not rounding around zero.
PULL_TOLERANCE = 1e-9
#: Indices into the state.
LEAN, HEADING_RATE, LEAN_RATE, SPIN_RATE = 3, 7, 8, 9


def _mass_radius_g(params: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(params["mass_kg"]), float(params["radius_m"]), float(params["g_m_s2"])


def lean_acceleration_rad_s2(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """θ̈ (N,) rad/s² of the uniform thin disk rolling without slip, along ``states`` (N, 10) (the module's formula)."""
    _, r, g = _mass_radius_g(params)
    states = np.atleast_2d(states)
    lean, heading_rate, spin_rate = states[:, LEAN], states[:, HEADING_RATE], states[:, SPIN_RATE]
    s, c = np.sin(lean), np.cos(lean)
    return s * c * heading_rate**2 + 1.2 * c * heading_rate * spin_rate + 0.8 * g / r * s


def normal_force_N(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """The floor's normal force on the disk N = m (g − r (θ̈ sin θ + θ̇² cos θ)) (N, up; (N,)) along ``states`` (N,
    10)."""
    m, r, g = _mass_radius_g(params)
    states = np.atleast_2d(states)
    lean, lean_rate = states[:, LEAN], states[:, LEAN_RATE]
    return m * (g - r * (lean_acceleration_rad_s2(params, states) * np.sin(lean) + lean_rate**2 * np.cos(lean)))


def contact_limit(params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
    """The first frame of ``states`` (N, 10) at ``t_s`` (N,) where the disk has fallen or the floor would have to pull,
    as a :class:`ModelLimit` keeping the frames before it (and always the start); None while it rolls on its rim."""
    states = np.atleast_2d(states)
    m, r, g = _mass_radius_g(params)
    with np.errstate(invalid="ignore", over="ignore"):
        fallen = np.abs(np.degrees(states[:, LEAN])) >= FALLEN_LEAN_DEG
        normal = normal_force_N(params, states)
        scale = m * (abs(g) + r * (states[:, LEAN_RATE] ** 2 + np.abs(lean_acceleration_rad_s2(params, states))))
        pulled = normal < -PULL_TOLERANCE * scale
    broken = fallen | pulled
    if not broken.any():
        return None
    k = int(np.argmax(broken))
    t = float(t_s[k])
    if fallen[k]:
        return ModelLimit(max(k, 1), FALLEN, fallen_message(t, FALLEN_LEAN_DEG))
    return ModelLimit(
        max(k, 1),
        LIFT_OFF,
        lift_off_message(t, float(normal[k]), float(np.degrees(states[k, LEAN])), float(states[k, LEAN_RATE])),
    )


def fallen_message(t_s: float, lean_deg: float) -> str:
    """What a student reads when the disk has fallen."""
    return (
        f"Stopped at t = {t_s:.2f} s: the disk has fallen (lean past {lean_deg:.0f}°). Lying on the floor it is "
        "no longer "
        "a disk rolling on its rim, so the rolling model stops here."
    )


def lift_off_message(t_s: float, normal_N: float, lean_deg: float, lean_rate_rad_s: float) -> str:
    """What a student reads when the floor would have to pull the disk down."""
    when = "At the start" if t_s == 0.0 else f"Stopped at t = {t_s:.2f} s"
    return (
        f"{when}: the floor would have to pull the disk down (normal force N = {normal_N:.3g} N, at lean "
        f"{lean_deg:.1f}° "
        f"and lean rate {lean_rate_rad_s:.3g} rad/s). A floor can only push: to stay on its rim the centre would "
        "have to "
        "drop faster than gravity can make it, so the disk leaves the floor, which the rolling model cannot describe."
    )
