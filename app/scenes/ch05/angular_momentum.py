"""Scene: a body spinning on a shaft that is not a principal axis — ω, H, its cone, and the bearings' moment.

World frame +Z up; the shaft is vertical through the centre of mass G and the
bearings A (below) and B (above) sit half the span from G. Everything that
moves with the shaft hangs under ``/rig``, placed at G (which travels at v_G in
the particles view); the body under ``/rig/body`` turns with R_world_body(t).
Arrows from G: ω (blue, along the shaft), H_G (red) and dH/dt = ω × H_G (green,
the moment the bearings supply); at the bearings the two opposite forces (orange).
The faint red circle and lines are the cone H sweeps once a turn. Each vector is
scaled to fit the body (the readout carries the numbers); their directions are
exact. Particles view: the equivalent point masses (same mass, centre and tensor)
with their velocities (purple), p = m v_G from G (magenta) and H_O from the world
origin O (dark red); the motion restarts every few seconds so it stays in view.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np

from app.physics.systems.ch05 import angular_momentum as physics
from app.scenes.kit import (
    LabelAnchor,
    Preset,
    Quantity,
    Readout,
    Scene,
    arrow_segments,
    circle_segments,
)

OMEGA_COLOR = (40, 90, 230)
MOMENTUM_COLOR = (215, 40, 40)
RATE_COLOR = (30, 150, 60)
FORCE_COLOR = (240, 140, 20)
VELOCITY_COLOR = (140, 60, 200)
LINEAR_MOMENTUM_COLOR = (220, 40, 180)
ORIGIN_MOMENTUM_COLOR = (120, 20, 30)
BODY_COLOR = (150, 170, 200)
#: The particles view replays its first seconds (at most this long, and while G travels two body sizes),
#: so a travelling body stays in the picture.
REPLAY_S = 4.0
CONE_GENERATORS = 12

PRESETS = (
    Preset(
        "tilted-plate",
        "Tilted plate",
        {"view": "rigid body", "body": "plate", "tilt_deg": 30.0, "spin_rate_rad_s": 4.0},
        "The plate's normal 30° off the shaft: H leans away from ω and the bearings feel a turning couple.",
    ),
    Preset(
        "principal",
        "Shaft along a principal axis",
        {"view": "rigid body", "body": "plate", "tilt_deg": 0.0},
        "Tilt 0: the shaft is the plate's normal, a principal axis. ω and H line up and the bearings carry nothing.",
    ),
    Preset(
        "skewed-disk",
        "Skewed disk",
        {"view": "rigid body", "body": "disk", "tilt_deg": 10.0, "spin_rate_rad_s": 20.0},
        "A disk mounted 10° askew at 20 rad/s: a small error in mounting, a large bearing load.",
    ),
    Preset(
        "particles",
        "Particles, moving centre",
        {"view": "particles", "body": "box", "tilt_deg": 30.0},
        "The body as eight point masses, carried along at v_G: momentum, H about O and the energy split.",
    ),
)


class AngularMomentumScene(Scene):
    id = "angular-momentum"
    title = "Angular momentum of a body on a non-principal shaft"
    chapter = 5
    model = physics.ShaftSpinModel
    presets = PRESETS
    animated = True

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._span = 1.0
        self.rig = scene.add_frame("/rig", show_axes=False)
        self.body_frame = scene.add_frame("/rig/body", show_axes=False)
        self.shaft = scene.add_line_segments(
            "/rig/shaft", np.zeros((1, 2, 3), np.float32), (90, 90, 90), thickness=4.0, thickness_units="screen"
        )
        self.cone = scene.add_line_segments(
            "/rig/cone", np.zeros((1, 2, 3), np.float32), (235, 150, 150), thickness=1.5, thickness_units="screen"
        )
        self.arrows = scene.add_arrows(
            "/rig/arrows",
            np.zeros((5, 2, 3), np.float32),
            np.array([OMEGA_COLOR, MOMENTUM_COLOR, RATE_COLOR, FORCE_COLOR, FORCE_COLOR], np.uint8),
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.labels = {
            name: scene.add_label(f"/rig/label_{key}", name, anchor=cast(LabelAnchor, anchor))
            for key, name, anchor in (
                ("omega", "ω", "bottom-left"),
                ("h", "H_G", "bottom-right"),
                ("rate", "dH/dt (bearing moment)", "bottom-left"),
                ("a", "F_A", "bottom-left"),
                ("b", "F_B", "bottom-left"),
            )
        }
        self.origin = scene.add_point_cloud(
            "/origin", np.zeros((1, 3), np.float32), (30, 30, 30), point_size=0.03, point_shape="circle"
        )
        self.origin_label = scene.add_label("/origin/label", "O", anchor="top-right")
        self.legend = scene.add_label("/legend", "", anchor="top-left")
        self.particles_legend = scene.add_label(
            "/particles_legend", "purple vᵢ · magenta p = m v_G · dark red H_O (from O)", anchor="top-left"
        )

    def camera_view(self):
        span = self._span
        return (0.95 * span, -1.45 * span, 0.55 * span), (0.0, 0.0, 0.0)

    # -- parameters ------------------------------------------------------------------------------
    def update(self) -> None:
        self.spin = physics.ShaftSpin.from_params(self.params)
        self.particles_view = self.params["view"] == "particles"
        body = self.spin.body
        size = body.radius_m
        half_span = 0.5 * self.spin.bearing_span_m
        self._size = size
        self._span = max(size, half_span) * 1.2
        # A viewer keeps its camera when the view changes, so the particles' replay stays near the shaft's picture.
        speed = float(np.linalg.norm(self.spin.centre_velocity_m_s))
        self._replay_s = min(REPLAY_S, 2.0 * size / speed) if speed > 0.0 else REPLAY_S
        scene = self.client.scene
        self.t_s = 0.0

        # The body: a mesh in its own axes, or its equivalent particles joined to G by spokes.
        for name in ("/rig/body/mesh", "/rig/body/particles", "/rig/body/spokes", "/particle_arrows", "/momenta"):
            scene.remove_by_name(name)
        if self.particles_view:
            local, masses = physics.equivalent_particles(np.diag(body.inertia_body_kg_m2), body.mass_kg)
            scene.add_point_cloud(
                "/rig/body/particles",
                local.astype(np.float32),
                (60, 60, 70),
                point_size=0.06 * size,
                point_shape="circle",
            )
            spokes = np.stack([np.zeros_like(local), local], axis=1).astype(np.float32)
            scene.add_line_segments(
                "/rig/body/spokes", spokes, (150, 150, 160), thickness=1.5, thickness_units="screen"
            )
            self.particle_arrows = scene.add_arrows(
                "/particle_arrows",
                np.zeros((len(masses), 2, 3), np.float32),
                VELOCITY_COLOR,
                shaft_radius=0.012 * size,
                head_radius=0.03 * size,
                head_length=0.06 * size,
            )
            self.momenta = scene.add_arrows(
                "/momenta",
                np.zeros((2, 2, 3), np.float32),
                np.array([LINEAR_MOMENTUM_COLOR, ORIGIN_MOMENTUM_COLOR], np.uint8),
                shaft_radius=0.015 * size,
                head_radius=0.04 * size,
                head_length=0.08 * size,
            )
        elif body.shape == "disk":
            scene.add_cylinder(
                "/rig/body/mesh", radius=0.5 * body.dimensions_m[0], height=0.04 * size, color=BODY_COLOR, opacity=0.75
            )
        else:
            a, b, c = body.dimensions_m
            scene.add_box("/rig/body/mesh", color=BODY_COLOR, dimensions=(a, b, max(c, 0.02 * size)), opacity=0.75)
        self.origin.visible = self.origin_label.visible = self.particles_view
        self.origin.point_size = 0.04 * size

        # The shaft through both bearings, and the arrow sizes.
        reach = half_span + 0.25 * size
        self.shaft.points = np.array([[[0.0, 0.0, -reach], [0.0, 0.0, reach]]], np.float32)
        self.arrows.shaft_radius, self.arrows.head_radius, self.arrows.head_length = (
            0.015 * size,
            0.04 * size,
            0.08 * size,
        )
        scene.remove_by_name("/rig/bearings")
        for key, z in (("a", -half_span), ("b", half_span)):
            scene.add_cylinder(
                f"/rig/bearings/{key}",
                radius=0.08 * size,
                height=0.12 * size,
                color=(70, 70, 80),
                position=(0.0, 0.0, z),
            )
        # Each vector drawn to fit the body: ω 1.1 size, H size, dH/dt 0.8 size, bearing forces 0.6 size.
        spin = self.spin
        h_size = spin.angular_momentum_magnitude_kg_m2_s
        self._h_scale = size / h_size if h_size > 0.0 else 0.0
        self._omega_tip = np.array(
            [0.0, 0.0, 1.1 * size * math.copysign(1.0, spin.spin_rate_rad_s) if spin.spin_rate_rad_s else 0.0]
        )
        moment = spin.bearing_moment_N_m
        self._moment_scale = 0.8 * size / moment if moment > 0.0 else 0.0
        force = moment / spin.bearing_span_m
        self._force_scale = 0.6 * size / force if force > 0.0 else 0.0
        self._half_span = half_span
        # H's cone: the circle its tip runs round, and a few of the lines from G to it.
        h0 = spin.at(np.zeros(1)).angular_momentum_G[0] * self._h_scale
        radius, height = float(np.hypot(h0[0], h0[1])), float(h0[2])
        if radius > 1e-9 * size:
            circle = circle_segments(radius=radius, center=(0.0, 0.0, height), segments=96)
            ends = circle[:: 96 // CONE_GENERATORS, 0]
            generators = np.stack([np.zeros_like(ends), ends], axis=1)
            self.cone.points = np.concatenate([circle, generators]).astype(np.float32)
            self.cone.visible = True
        else:
            self.cone.visible = False
        self.legend.position = (-1.3 * self._span, 0.0, -reach - 0.6 * self._span)  # well below the shaft's lower end
        self.legend.text = "blue ω · red H_G · green dH/dt = ω × H · orange bearing forces (scaled to fit)"
        self.particles_legend.position = (-1.3 * self._span, 0.0, -reach - 0.8 * self._span)
        self.particles_legend.visible = self.particles_view
        self._draw()

    # -- animation -------------------------------------------------------------------------------
    def step_motion(self, dt_s: float) -> bool:
        """The particles' view replays from t = 0 after ``_replay_s``."""
        self.t_s += dt_s
        if self.particles_view and self.t_s > self._replay_s:
            self.t_s = 0.0
        return True

    def _draw(self) -> None:
        spin = self.spin
        t = np.array([self.t_s])
        state = spin.at(t)
        self._state = state
        self.rig.position = tuple(state.centre_m[0])
        self.body_frame.wxyz = spin.attitude_wxyz(self.t_s)
        h_tip = state.angular_momentum_G[0] * self._h_scale
        rate_tip = state.bearing_moment[0] * self._moment_scale
        force_b = state.bearing_force_B[0] * self._force_scale
        bearing_a, bearing_b = np.array([0.0, 0.0, -self._half_span]), np.array([0.0, 0.0, self._half_span])
        tails = np.array([np.zeros(3), np.zeros(3), np.zeros(3), bearing_a, bearing_b])
        vectors = np.array([self._omega_tip, h_tip, rate_tip, -force_b, force_b])
        self.arrows.points = arrow_segments(tails, vectors, 1.0)
        self.labels["ω"].position = tuple(self._omega_tip + np.array([0.06 * self._size, 0.0, 0.0]))
        self.labels["H_G"].position = tuple(h_tip * 1.05)
        self.labels["dH/dt (bearing moment)"].position = tuple(rate_tip * 1.08)
        self.labels["F_A"].position = tuple(bearing_a - 1.05 * force_b)
        self.labels["F_B"].position = tuple(bearing_b + 1.05 * force_b)
        if self.particles_view:
            self._draw_particles(state)

    def _draw_particles(self, state: physics.SpinState) -> None:
        particles = self.spin.particles_at(state)
        self._particles = particles
        velocity_scale = (
            0.5 * self._size / max(float(np.max(np.linalg.norm(particles.velocities_m_s[0], axis=-1))), 1e-12)
        )
        self.particle_arrows.points = arrow_segments(
            particles.positions_m[0], particles.velocities_m_s[0], velocity_scale
        )
        p = state.linear_momentum
        p_scale = 0.8 * self._size / max(float(np.linalg.norm(p)), 1e-12)
        h_o = state.angular_momentum_O[0]
        h_o_scale = self._h_scale if self._h_scale else 0.0
        self.momenta.points = arrow_segments(
            np.array([state.centre_m[0], np.zeros(3)]), np.array([p * p_scale, h_o * h_o_scale]), 1.0
        )

    def readout(self) -> Readout:
        spin, state = self.spin, self._state
        no_spin = spin.spin_rate_rad_s == 0.0
        angle = Quantity.or_text(
            "angle_omega_H",
            "angle between ω and H_G",
            None if no_spin else math.degrees(float(state.angle_between_omega_and_H[0])),
            "deg",
            physics.NO_SPIN_ANGLE,
        )
        force = float(state.bearing_moment_N_m[0]) / spin.bearing_span_m
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("spin_angle", "spin angle Ωt (mod 360°)", math.degrees(float(state.spin_angle[0])) % 360.0, "deg"),
            angle,
            Quantity("angular_momentum", "|H_G|", float(np.linalg.norm(state.angular_momentum_G[0])), "kg·m²/s"),
            Quantity(
                "angular_momentum_along_shaft", "H_G along the shaft", float(state.angular_momentum_G[0, 2]), "kg·m²/s"
            ),
            Quantity(
                "bearing_moment", "|dH/dt| = |ω × H_G| (bearing moment)", float(state.bearing_moment_N_m[0]), "N·m"
            ),
            Quantity("bearing_force", f"force at each bearing (span {spin.bearing_span_m:g} m)", force, "N"),
            Quantity("kinetic_energy", "kinetic energy T", float(state.kinetic_energy_J[0]), "J"),
            Quantity(
                "kinetic_energy_centre", "T of G's motion, ½ m v_G²", float(state.kinetic_energy_centre_J[0]), "J"
            ),
            Quantity(
                "kinetic_energy_about_centre", "T about G, ½ ω·H_G", float(state.kinetic_energy_about_centre_J[0]), "J"
            ),
        ]
        if self.particles_view:
            particles = self._particles
            h_o = state.angular_momentum_O[0]
            mismatch = max(
                float(np.max(np.abs(particles.angular_momentum(np.zeros(3))[0] - h_o))),
                float(np.max(np.abs(particles.angular_momentum(state.centre_m)[0] - state.angular_momentum_G[0]))),
            )
            energy_mismatch = abs(float(particles.kinetic_energy()[0] - state.kinetic_energy_J[0]))
            quantities += [
                Quantity(
                    "linear_momentum",
                    "|p| = |Σ mᵢ vᵢ| = m |v_G|",
                    float(np.linalg.norm(particles.linear_momentum()[0])),
                    "kg·m/s",
                ),
                Quantity("angular_momentum_O", "|H_O| = |H_G + r_G × m v_G|", float(np.linalg.norm(h_o)), "kg·m²/s"),
                Quantity(
                    "particle_sum_mismatch",
                    "largest |Σ rᵢ × mᵢ vᵢ − rigid-body H| (about G and O)",
                    mismatch,
                    "kg·m²/s",
                ),
                Quantity("particle_energy_mismatch", "|Σ ½ mᵢ vᵢ² − T|", energy_mismatch, "J"),
            ]
        return Readout(quantities, message=self._message(force))

    def _message(self, force_N: float) -> str:
        spin = self.spin
        words = []
        if spin.body.shaft_is_principal:
            words.append("ω and H are parallel: the shaft is a principal axis, so the bearings feel no moment.")
        if spin.spin_rate_rad_s == 0.0:
            words.append("No spin: ω = 0, so H = 0, T = ½ m v_G² and the bearings carry nothing.")
        elif not spin.body.shaft_is_principal:
            words.append(
                f"H_G leans {math.degrees(spin.angle_between_omega_and_H):.2f}° off the shaft and sweeps a cone "
                "once a turn; "
                f"the bearings must supply dH/dt = ω × H_G, two forces of {force_N:.4g} N turning with the body."
            )
        if self.particles_view:
            masses = self._particles.masses_kg
            words.append(
                f"The body is drawn as {len(masses)} point masses of {masses[0]:.4g} kg with its mass, centre "
                "and inertia. "
                "The shaft travels at constant v_G: p, H_O and T change with v_G, the bearing forces do not."
            )
        words.append(
            "Gravity is left out: on a vertical shaft the weight is an axial thrust and changes none of these moments."
        )
        return " ".join(words)
