"""Worked example ``moving-hoop-virtual-displacement`` (section 7.3): a bead on a hoop that is pushed to and fro —
its virtual displacement, its actual one, and the work of the hoop's push in each.

The system is :class:`~app.physics.systems.ch07.configuration_space.SlidingHoop` (the scene
``configuration-space-constraints``, rheonomic case): a hoop of radius R lies flat on a smooth horizontal table (no
gravity in the plane); its centre is driven along x as ``x_c = A sin Ωt``; the bead is carried round the centre at
the steady rate ω, ``φ = ω t``, so ``r = (x_c + R cos φ, R sin φ)``.

Virtual displacement (time frozen): ``δr = ∂r/∂φ δφ = R(−sin φ, cos φ) δφ``; kinematically, the same follows from the
velocity ``ṙ = ṙ_c + R φ̇ e_φ`` with the hoop's motion frozen (ṙ_c → 0) and φ̇ → δφ. The bead's acceleration
``a = (ẍ_c, 0) − R ω² e_r`` needs a push ``N e_r`` normal to the hoop (N = m a·e_r) and a push ``F_t e_φ`` along
it (F_t = m a·e_φ = −m ẍ_c sin φ, the hand that keeps φ̇ steady). N does no virtual work but does real work at the
rate ``N e_r·ṙ = N ẋ_c cos φ``. The check: ``∇g·δr = 0``, ``∇g·ṙ + ∂g/∂t = 0``, and the pushes' power equals
dT/dt written out from T(t) directly.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch07.configuration_space import SlidingHoop

INPUTS = ParameterSet(
    (
        Parameter("hoop_radius_m", "m", 1.0, 0.2, 3.0, "Radius R of the moving hoop", "R", step=0.05),
        Parameter(
            "hoop_amplitude_m",
            "m",
            0.8,
            0.0,
            2.0,
            "Amplitude A of the hoop centre's motion x_c = A sin Ωt",
            "A",
            step=0.05,
        ),
        Parameter(
            "hoop_rate_rad_s",
            "rad/s",
            1.5,
            0.0,
            5.0,
            "Circular frequency Ω of the hoop centre's motion",
            "Ω",
            step=0.05,
        ),
        Parameter(
            "bead_rate_rad_s",
            "rad/s",
            0.6,
            -3.0,
            3.0,
            "Steady rate ω of the bead's angle φ round the hoop's centre",
            "ω",
            step=0.05,
        ),
        Parameter(
            "time_s", "s", 0.5, 0.0, 20.0, "The instant t at which the displacements are compared", "t", step=0.05
        ),
        Parameter("bead_mass_kg", "kg", 0.2, 0.001, 10.0, "Mass m of the bead", "m", step=0.01),
    )
)


def hoop(inputs: Mapping[str, Any]) -> SlidingHoop:
    return SlidingHoop(
        float(inputs["hoop_radius_m"]),
        float(inputs["hoop_amplitude_m"]),
        float(inputs["hoop_rate_rad_s"]),
        float(inputs["bead_rate_rad_s"]),
    )


def solve(inputs: Mapping[str, Any]) -> Solution:
    system = hoop(inputs)
    t, m = float(inputs["time_s"]), float(inputs["bead_mass_kg"])
    R, A, Omega, omega = system.radius_m, system.amplitude_m, system.centre_rate_rad_s, system.rate_rad_s
    snap = system.snapshot(t)
    phi = omega * t
    radial = np.array([math.cos(phi), math.sin(phi)])
    tangent = np.array([-radial[1], radial[0]])
    x_c = float(system.centre(t)[0])
    xd_c = float(system.centre_velocity(t)[0])
    xdd_c = -A * Omega * Omega * math.sin(Omega * t)
    virtual = R * tangent  # ∂r/∂φ, m per rad of δφ
    frozen = R * tangent  # ṙ with ẋ_c → 0 and φ̇ → 1: the kinematical route
    partial_t = np.array([xd_c, 0.0])
    velocity = snap.velocity
    acceleration = np.array([xdd_c, 0.0]) - R * omega * omega * radial
    normal = m * float(acceleration @ radial)
    along = m * float(acceleration @ tangent)
    normal_virtual = normal * float(radial @ virtual)
    normal_power = normal * float(radial @ velocity)
    along_power = along * float(tangent @ velocity)
    # dT/dt from T = ½ m (ẋ_c² − 2 ẋ_c R ω sin φ + R² ω²), differentiated in t by hand
    kinetic_rate = m * (xd_c * xdd_c - R * omega * (xdd_c * math.sin(phi) + xd_c * omega * math.cos(phi)))
    speed_scale = abs(A * Omega) + abs(R * omega)
    angle = math.radians(snap.angle_between_deg)
    steps = (
        Step(
            "Configuration at the instant t",
            r"\varphi = \omega t,\quad x_c = A\sin\Omega t,\quad \dot x_c = A\Omega\cos\Omega t,\quad \bar r = "
            r"(x_c + R\cos\varphi,\ R\sin\varphi)",
            {"phi": phi, "x_c": x_c, "xdot_c": xd_c, "r": snap.position},
            {"phi": "rad", "x_c": "m", "xdot_c": "m/s", "r": "m"},
        ),
        Step(
            "Virtual displacement, analytically: differentiate r with time frozen",
            r"\delta\bar r = \frac{\partial\bar r}{\partial\varphi}\,\delta\varphi = R(-\sin\varphi,\ \cos\varphi)"
            r"\,\delta\varphi\qquad(\delta t = 0)",
            {"dr/dphi": virtual},
            {"dr/dphi": "m/rad"},
        ),
        Step(
            "Kinematically: the velocity by relative motion, then the hoop frozen and φ̇ → δφ",
            r"\dot{\bar r} = \dot x_c\,\bar i + R\dot\varphi\,\bar e_\varphi\ \xrightarrow{\ \dot x_c \to 0,\ "
            r"\dot\varphi \to \delta\varphi\ }\ \delta\bar r = R\,\bar e_\varphi\,\delta\varphi;\quad "
            r"\text{actual: } d\bar r = \Big(\frac{\partial\bar r}{\partial\varphi}\dot\varphi + "
            r"\frac{\partial\bar r}{\partial t}\Big)dt",
            {"dr/dphi_kinematic": frozen, "dr/dt_partial": partial_t, "rdot": velocity, "angle": angle},
            {"dr/dphi_kinematic": "m/rad", "dr/dt_partial": "m/s", "rdot": "m/s", "angle": "rad"},
        ),
        Step(
            "The hoop's pushes that carry the bead (no gravity in the table's plane)",
            r"\bar a = \ddot x_c\,\bar i - R\omega^2\,\bar e_r,\quad N = m\,\bar a\cdot\bar e_r,\quad F_t = m\,\bar a"
            r"\cdot\bar e_\varphi = -m\,\ddot x_c\sin\varphi",
            {"xddot_c": xdd_c, "a": acceleration, "N": normal, "F_t": along},
            {"xddot_c": "m/s²", "a": "m/s²", "N": "N", "F_t": "N"},
        ),
        Step(
            "Work of the normal push: none in the virtual displacement, some in the real motion",
            r"N\,\bar e_r\cdot\frac{\delta\bar r}{\delta\varphi} = 0,\qquad P_N = N\,\bar e_r\cdot\dot{\bar r} = "
            r"N\,\dot x_c\cos\varphi",
            {"N_virtual_work": normal_virtual, "P_N": normal_power},
            {"N_virtual_work": "J/rad", "P_N": "W"},
            scales={"N_virtual_work": abs(normal) * R},
        ),
        Step(
            "Check: δr is tangent to the frozen hoop, dr keeps the bead on the moving one, and the pushes' power is "
            "dT/dt",
            r"\nabla g\cdot\delta\bar r = 0,\quad \nabla g\cdot\dot{\bar r} + \frac{\partial g}{\partial t} = 0,"
            r"\quad P_N + F_t\,\bar e_\varphi\cdot\dot{\bar r} = \frac{d}{dt}\,\tfrac12 m\big(\dot x_c^2 - 2\dot x_c"
            r"R\omega\sin\varphi + R^2\omega^2\big)",
            {
                "grad_g_dot_dr": float(snap.gradient @ virtual),
                "grad_g_dot_rdot": snap.gradient_along_velocity,
                "dg/dt_partial": snap.time_rate,
                "dg/dt_total": snap.actual_variation,
                "power": normal_power + along_power,
                "dT/dt": kinetic_rate,
            },
            {
                "grad_g_dot_dr": "1/rad",
                "grad_g_dot_rdot": "1/s",
                "dg/dt_partial": "1/s",
                "dg/dt_total": "1/s",
                "power": "W",
                "dT/dt": "W",
            },
            scales={
                "grad_g_dot_dr": 2.0,
                "dg/dt_total": 2.0 * speed_scale / R,
                "grad_g_dot_rdot": 2.0 * speed_scale / R,
                "dg/dt_partial": 2.0 * speed_scale / R,
            },
        ),
    )
    outputs = {
        "virtual_displacement_m_per_rad": virtual,
        "velocity_m_s": velocity,
        "angle_rad": angle,
        "normal_force_N": normal,
        "tangential_force_N": along,
        "normal_power_W": normal_power,
        "kinetic_energy_rate_W": kinetic_rate,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="moving-hoop-virtual-displacement",
    title="A bead on a moving hoop: virtual and actual displacements, and the work of the hoop's push",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "virtual_displacement_m_per_rad": "m/rad",
        "velocity_m_s": "m/s",
        "angle_rad": "rad",
        "normal_force_N": "N",
        "tangential_force_N": "N",
        "normal_power_W": "W",
        "kinetic_energy_rate_W": "W",
    },
    section="7.3",
    story=ExampleStory(
        situation=(
            "A hoop of radius $R$ lies flat on a smooth horizontal table, and its centre is pushed to and fro "
            "along $x$ as $x_c = A\\sin\\Omega t$. A bead of mass $m$ threaded on it is carried round the centre at "
            "the steady rate $\\omega$, so its angle is $\\varphi = \\omega t$. The hoop's motion is prescribed, so "
            "the constraint $g = ((x - x_c)^2 + y^2)/R^2 - 1 = 0$ contains the time: it is rheonomic."
        ),
        wanted=(
            "At the instant $t$: the bead's virtual displacement for a change $\\delta\\varphi$, its actual "
            "velocity and the angle between the two, the pushes the hoop must exert to carry the bead, and the "
            "work the hoop's normal push does in the virtual displacement and, per second, in the real motion."
        ),
        approach=(
            "One coordinate, $\\varphi$, fixes the bead on the hoop, and the time fixes the hoop, so "
            "$\\bar r = \\bar r(\\varphi, t)$. The analytical route differentiates that position with time frozen; "
            "the kinematical route writes the velocity by relative motion, then freezes the hoop and replaces "
            "$\\dot\\varphi$ by $\\delta\\varphi$. Both must give the same tangent to the hoop as it stands at $t$. "
            "Working in Cartesian $x, y$ with the constraint kept as an equation would give the same tangent, "
            "but only after solving $\\nabla g\\cdot\\delta\\bar r = 0$ by hand at every instant. The pushes then "
            "follow from Newton's law with the acceleration we already know."
        ),
        check=(
            "Three things must hold and the last step computes each. The virtual displacement is tangent to the "
            "frozen hoop, $\\nabla g\\cdot\\delta\\bar r = 0$. The real velocity keeps the bead on the moving hoop, "
            "so $\\nabla g\\cdot\\dot{\\bar r}$ is cancelled exactly by $\\partial g/\\partial t$. And the two "
            "pushes' power equals $dT/dt$, differentiated by hand from $T(t)$: the normal push's share is real "
            "work, even though its virtual work is zero."
        ),
        what_if=(
            "With the scene's constraint set to *rheonomic*, set the hoop's amplitude **A** to 0 (the preset *Hoop at "
            "rest*). The constraint stops "
            "moving, $\\partial g/\\partial t$ vanishes, the actual velocity lines up with the virtual displacement "
            "(the angle goes to 0), and the normal push's power $P_N$ drops to zero: a fixed smooth wire does no "
            "work. Then raise **Ω** and watch $P_N$ and the angle between the green and orange arrows grow."
        ),
    ),
)
