"""The two chapter 4.1–4.2 scenes on a real (loopback) viser server, without a browser.

What is drawn is checked as geometry: the term arrows at B run tip to tail and the resultant closes the chain
(v_A + ω × r_B/A = v_B; a_A + α × r_B/A + ω × (ω × r_B/A) = a_B; φ̇K + θ̇i′ + ψ̇k = ω), to 1e-5 m of arrow
(float32 points of order 1 m: about 100 ulp). The readout's magnitudes are the model's at the scene's time.
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.systems.ch04 import eulerian_angles, rigid_body_points
from app.scenes.ch04.eulerian_angles import EulerianAnglesScene
from app.scenes.ch04.rigid_body_points import RigidBodyPointsScene
from app.scenes.kit import FRAME_DT_S

ARROW_ATOL_M = 1e-5


def arrow_batch(client, prefix: str) -> np.ndarray:
    names = [n for n in client.scene.handles if n.startswith(prefix + "/") and "_labels" not in n]
    return np.asarray(client.scene.handles[max(names, key=lambda n: int(n.rsplit("/", 1)[1]))].points, float)


def values(scene) -> dict:
    return {q.name: q.value if q.value is not None else q.text for q in scene.readout().quantities}


@pytest.mark.parametrize("view", ["velocity", "acceleration"])
def test_the_terms_at_B_run_tip_to_tail_and_close_on_the_resultant(client, view):
    # Steady rates: every term is longer than its arrowhead (shorter ones are left out of the batch).
    params = RigidBodyPointsScene.parameters.validate({"arrows": view, "spin_acceleration_rad_s2": 0.0, "turntable_acceleration_rad_s2": 0.0})
    scene = RigidBodyPointsScene(client, params)
    for _ in range(15):
        scene.advance(FRAME_DT_S)
    batch = scene.velocity_arrows if view == "velocity" else scene.acceleration_arrows
    drawn = dict(zip(batch._drawn, arrow_batch(client, f"/{view}")))
    state = rigid_body_points.DiskOnTurntable.from_params(params).at(np.array([scene.t_s]))
    B = state.point[0]
    if view == "velocity":
        assert set(drawn) == {"center", "relative", "total", "omega"}
        chain = ("center", "relative")
        assert values(scene)["v_B_magnitude"] == pytest.approx(np.linalg.norm(state.point_velocity[0]), rel=1e-12)
    else:
        assert set(drawn) == {"center", "tangential", "centripetal", "total", "alpha"}
        chain = ("center", "tangential", "centripetal")
        assert values(scene)["a_B_magnitude"] == pytest.approx(np.linalg.norm(state.point_acceleration[0]), rel=1e-12)
    assert np.allclose(drawn[chain[0]][0], B, atol=ARROW_ATOL_M) and np.allclose(drawn["total"][0], B, atol=ARROW_ATOL_M)
    for before, after in zip(chain, chain[1:]):
        assert np.allclose(drawn[before][1], drawn[after][0], atol=ARROW_ATOL_M)  # each term starts at the last one's tip
    assert np.allclose(drawn[chain[-1]][1], drawn["total"][1], atol=ARROW_ATOL_M)  # the resultant closes the chain
    assert values(scene)["t_s"] == pytest.approx(15 * FRAME_DT_S)
    scene.close()


def test_B_at_the_centre_moves_like_A(client):
    scene = RigidBodyPointsScene(client, RigidBodyPointsScene.parameters.validate({"point_radius_fraction": 0.0}))
    got = values(scene)
    assert got["v_B_magnitude"] == pytest.approx(got["v_A_magnitude"], abs=1e-12)
    assert got["omega_cross_r_magnitude"] == 0.0 and got["alpha_cross_r_magnitude"] == 0.0
    assert "m/s" in {q.unit for q in scene.readout().quantities}
    scene.close()


def test_the_rate_arrows_add_up_to_omega(client):
    scene = EulerianAnglesScene(client, EulerianAnglesScene.parameters.validate({"nutation_rate_rad_s": 1.0, "spin_acceleration_rad_s2": 2.0}))
    for _ in range(25):
        scene.advance(FRAME_DT_S)
    arrows = arrow_batch(client, "/rates")  # precession, nutation, spin, ω, α (each longer than its head)
    assert np.allclose(arrows[0, 0], 0.0, atol=ARROW_ATOL_M) and np.allclose(arrows[0, 1], arrows[1, 0], atol=ARROW_ATOL_M)
    assert np.allclose(arrows[1, 1], arrows[2, 0], atol=ARROW_ATOL_M)
    assert np.allclose(arrows[2, 1], arrows[3, 1], atol=ARROW_ATOL_M)
    k = eulerian_angles.EulerianAngleMotion.from_params(scene.params).at(np.array([scene.t_s])).kinematics
    assert values(scene)["angular_speed"] == pytest.approx(np.linalg.norm(k.omega_world_rad_s[0]), rel=1e-12)
    assert "away from the singularity" in scene.readout().message
    scene.close()


def test_at_theta_zero_the_readout_says_the_angles_are_singular(client):
    preset = next(p for p in EulerianAnglesScene.presets if p.name == "singular")
    scene = EulerianAnglesScene(client, EulerianAnglesScene.parameters.validate(preset.values))
    got = values(scene)
    assert got["singularity_distance"] == 0.0
    assert got["rates_from_omega"].startswith("undefined at θ = 0")
    assert "only φ ± ψ" in scene.readout().message
    scene.close()
