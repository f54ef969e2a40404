"""The chapter-7 catalogue scenes: readouts that say the physics.

Their cost per frame is a benchmark, not a test: ``dynlab bench`` measures every scene's frame
(``live_scenes`` in docs/bench/work_precision.json) against the 50 µs budget.
"""

from __future__ import annotations

import math

import pytest

from app.scenes import SCENES

CATALOGUE = ("double-pendulum", "pendulum-on-cart", "bead-on-rotating-hoop")


def built(client, scene_id: str, **values):
    cls = SCENES[scene_id]
    return cls(client, cls.parameters.validate(values))


def values(readout) -> dict:
    return {q.name: q.value if q.value is not None else q.text for q in readout.quantities}


@pytest.mark.parametrize("scene_id", CATALOGUE)
def test_formulations_agree_on_the_running_state(client, scene_id):
    """Every formulation's ẏ matches the running one to 1e-12 relative (derivations agree to ~1e-15)."""
    scene = built(client, scene_id)
    try:
        for _ in range(40):
            scene.advance(1 / 30)
        shown = values(scene.readout())
        assert shown["formulation_agreement"] < 1e-12
        assert sum(name.startswith("agreement_") for name in shown) >= 3
    finally:
        scene.close()


def test_hoop_readout_marks_the_bifurcation(client):
    scene = built(client, "bead-on-rotating-hoop", hoop_speed_rad_s=6.0)
    try:
        shown = values(scene.readout())
        assert shown["critical_spin_rad_s"] == pytest.approx(math.sqrt(9.81 / 0.5), rel=1e-12)
        assert shown["bottom_stability"] == "unstable"
        assert math.cos(math.radians(shown["off_bottom_equilibrium_deg"])) == pytest.approx(9.81 / (0.5 * 36.0), rel=1e-12)
        scene.set_params(SCENES["bead-on-rotating-hoop"].parameters.validate({"hoop_speed_rad_s": 3.0}))
        shown = values(scene.readout())
        assert shown["bottom_stability"] == "stable" and "below" in shown["off_bottom_equilibrium_deg"]
    finally:
        scene.close()


def test_cart_readout_balances_energy_against_work(client):
    """With the drive on, ΔE − W stays at integration error (RK4, automatic step): below 1e-4 of the work."""
    scene = built(client, "pendulum-on-cart", force_amplitude_N=5.0, force_frequency_rad_s=2.0, theta_0_deg=0.0)
    try:
        for _ in range(90):
            scene.advance(1 / 30)
        shown = values(scene.readout())
        assert abs(shown["force_work_J"]) > 0.1
        assert abs(shown["energy_balance_residual_J"]) < 1e-4 * abs(shown["force_work_J"])
    finally:
        scene.close()
