"""The inertia explorer in its own code path (a real headless viewer): turned-frame components, the
degenerate and nearly degenerate cases, and the presets.

Tolerances: the components on the turned axes are ``Rᵀ I R`` and the principal moments come from a
symmetric eigensolver; both are backward stable, with errors of a few machine epsilons (≈ 1e-15)
relative to the largest moment. 1e-12 relative leaves a margin of 100× and would still catch any
wrong transpose, sign or axis order (those change components by O(1)).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from app.physics.bodies import inertia
from app.physics.bodies.composite import SHAPES, combine, parts_from_records
from app.physics.math.rotations import SEQUENCES, matrix_from_angles
from app.physics.systems.ch05 import composite_body
from app.scenes.ch05 import inertia_explorer
from app.scenes.ch05.inertia_explorer import PRESET_BODIES, InertiaExplorerScene

RELATIVE = 1e-12
PRODUCTS = ((0, 1, "xy"), (0, 2, "xz"), (1, 2, "yz"))


@pytest.fixture
def scene(client):
    built = InertiaExplorerScene(client, InertiaExplorerScene.parameters.validate({}))
    yield built
    built.close()


def set_params(scene, **values):
    scene.set_params(InertiaExplorerScene.parameters.validate(values, base=scene.params))


def tensor_from_readout(readout) -> np.ndarray:
    """The tensor on the turned axes rebuilt from the readout's moments and products (entries −I_ab)."""
    tensor = np.diag([readout.value(f"I_{c}{c}") for c in "xyz"])
    for i, j, pair in PRODUCTS:
        tensor[i, j] = tensor[j, i] = -readout.value(f"I_{pair}")
    return tensor


def principal_from_readout(readout) -> np.ndarray:
    return np.array([readout.value(f"I_{k}") for k in (1, 2, 3)])


@pytest.mark.parametrize("sequence", list(SEQUENCES))
def test_turning_the_frame_changes_the_components_but_not_the_principal_moments(scene, sequence):
    I_G = scene.body.inertia_cm_kg_m2
    scale = float(np.max(scene.body.principal.moments_kg_m2))
    start = tensor_from_readout(scene.readout())
    principal = principal_from_readout(scene.readout())
    for angles in ([35.0, -20.0, 70.0], [120.0, 45.0, -150.0], [0.0, 90.0, 0.0]):
        set_params(scene, frame_sequence=sequence, frame_angles_deg=angles)
        readout = scene.readout()
        turned = tensor_from_readout(readout)
        # Independently: the moment about a turned axis is eᵀ I e, the product about two is −eᵀ I f.
        axes = matrix_from_angles(np.radians(angles), sequence).T
        for i in range(3):
            assert turned[i, i] == pytest.approx(inertia.inertia_about_axis(I_G, axes[i]), abs=RELATIVE * scale)
        for i, j, _ in PRODUCTS:
            assert turned[i, j] == pytest.approx(float(axes[i] @ I_G @ axes[j]), abs=RELATIVE * scale)
        assert np.max(np.abs(turned - start)) > 1e-3 * scale, "the components must change as the frame turns"
        np.testing.assert_allclose(np.linalg.eigvalsh(turned), principal, rtol=0, atol=RELATIVE * scale)
        np.testing.assert_allclose(principal_from_readout(readout), principal, rtol=0, atol=RELATIVE * scale)
        assert readout.value("trace") == pytest.approx(float(np.sum(principal)), abs=RELATIVE * scale)


def test_turning_the_frame_does_not_recompute_the_body(scene, monkeypatch):
    calls = []
    original = composite_body.composite_from_inputs
    monkeypatch.setattr(composite_body, "composite_from_inputs", lambda inputs: calls.append(1) or original(inputs))
    for k in range(5):
        set_params(scene, frame_angles_deg=[10.0 * k, 5.0, 0.0], show_ellipsoid="no" if k % 2 else "yes")
    assert calls == []
    set_params(scene, about_point_m=[0.1, 0.0, 0.0])
    assert calls == []
    set_params(scene, bodies=PRESET_BODIES["dumbbell"])
    assert calls == [1]


@pytest.mark.parametrize("preset", ["sphere", "cube"])
def test_triple_degenerate_bodies_take_the_frame_axes_without_flicker(scene, client, preset):
    set_params(scene, bodies=PRESET_BODIES[preset])
    readout = scene.readout()
    assert "every axis is principal" in readout.quantities[[q.name for q in readout.quantities].index("degeneracy")].text
    moment = readout.value("I_1")
    assert readout.value("I_2") == readout.value("I_3") == moment
    np.testing.assert_array_equal(scene.body.principal.axes, np.eye(3))
    G = scene.body.centre_of_mass_m
    arrows = np.array(scene.principal_arrows.points, float)
    np.testing.assert_allclose(arrows[:, 0], np.repeat(G[None], 3, axis=0), atol=1e-7)
    directions = arrows[:, 1] - arrows[:, 0]
    np.testing.assert_allclose(directions / np.linalg.norm(directions, axis=1, keepdims=True), np.eye(3), atol=1e-7)
    semi = np.array(scene.ellipsoid.scale, float)
    assert np.all(np.isfinite(semi)) and np.ptp(semi) == 0.0  # a sphere
    for angles in itertools.product((0.0, 33.0, 181.0), (0.0, -47.0), (12.0,)):
        set_params(scene, frame_angles_deg=list(angles))
        np.testing.assert_array_equal(np.array(scene.principal_arrows.points, float), arrows)  # no flicker
        turned = tensor_from_readout(scene.readout())
        # Any frame is principal: the diagonal is the one moment, the products vanish (noise rounded to 0).
        np.testing.assert_allclose(np.diag(turned), moment, rtol=RELATIVE)
        assert all(scene.readout().value(f"I_{pair}") == 0.0 for _, _, pair in PRODUCTS)


def test_nearly_equal_moments_are_named_and_their_axes_stay_well_defined(scene):
    # A block 0.3 × 0.3(1 + 1e-6) × 0.1 m turned off the reference axes: I_1 and I_2 differ by about 1e-6 of I_3.
    angles = [25.0, 15.0, 5.0]
    block = {"shape": "box", "mass_kg": 5.0, "length_m": 0.3, "width_m": 0.3 * (1 + 1e-6), "height_m": 0.1,
             "position_m": [0.0, 0.0, 0.0], "sequence": "3-2-1", "angles_deg": angles, "hole": False}  # fmt: skip
    set_params(scene, bodies=[block])
    principal = scene.body.principal
    assert principal.degeneracy == "distinct"
    i, j, gap = inertia_explorer.nearly_equal_pair(principal)
    assert (i, j) == (0, 1) and 1e-7 < gap < 1e-5
    readout = scene.readout()
    text = readout.quantities[[q.name for q in readout.quantities].index("degeneracy")].text
    assert "nearly equal" in text
    # Eigenvector error ≈ ε‖I‖ / gap ≈ 2e-16 / 1e-6 = 2e-10: the axes are the block's own to 1e-8.
    own_axes = matrix_from_angles(np.radians(angles), "3-2-1").T  # rows: length, width, height directions
    expected = own_axes[[1, 0, 2]]  # least inertia about the longer side (width), most about the height
    np.testing.assert_allclose(np.abs(np.sum(principal.axes * expected, axis=1)), 1.0, atol=1e-8)
    assert np.linalg.det(principal.axes) == pytest.approx(1.0, abs=1e-12)
    for handle in (scene.principal_arrows.points, scene.ellipsoid.scale, scene.ellipsoid.wxyz):
        assert np.all(np.isfinite(np.asarray(handle, float)))


@pytest.mark.parametrize("preset", InertiaExplorerScene.presets, ids=lambda p: p.name)
def test_every_preset_is_a_real_body(preset):
    values = InertiaExplorerScene.parameters.validate(preset.values)
    records = values["bodies"]
    body = combine(parts_from_records(records))
    signed = sum(-r["mass_kg"] if r["hole"] else r["mass_kg"] for r in records)
    assert body.mass_kg == pytest.approx(signed, rel=1e-15)
    inertia.check_inertia_tensor(body.inertia_cm_kg_m2)  # positive definite, triangle inequality
    for record in records:
        if record["hole"]:  # a hole removes exactly the material of the plate it is cut from (100 kg/m²)
            host = next(r for r in records if r["shape"] == "plate")
            host_density = host["mass_kg"] / (host["length_m"] * host["width_m"])
            assert record["mass_kg"] == pytest.approx(host_density * np.pi * record["radius_m"] ** 2, rel=1e-4)


def test_preset_bodies_show_their_physics():
    def body(name):
        return combine(parts_from_records(PRESET_BODIES[name]))

    bent = body("bent-bar").principal.moments_kg_m2
    assert bent[2] == pytest.approx(bent[0] + bent[1], rel=1e-12)  # a flat body: the perpendicular-axis theorem
    assert body("dumbbell").principal.degeneracy == "axisymmetric"
    skewed = body("skewed-disk").inertia_cm_kg_m2
    assert abs(skewed[0, 2]) > 1e-3 * skewed[0, 0]  # the shaft (x) is no longer a principal axis
    assert body("sphere").principal.degeneracy == body("cube").principal.degeneracy == "spherical"
    assert PRESET_BODIES["plate-with-hole"] == composite_body.DEFAULT_BODIES


def test_holes_are_drawn_red_and_proud_of_their_plate(scene):
    drawn = list(zip(scene.body.parts, scene._part_handles))
    hole, hole_handle = next((part, handle) for part, handle in drawn if part.hole)
    plate_handle = next(handle for part, handle in drawn if part.shape.name == "plate")
    assert tuple(hole_handle.color) == inertia_explorer.HOLE_COLOR
    assert hole_handle.radius > hole.dimensions_m["radius_m"]  # covers the removed disk's edge
    assert hole_handle.height > plate_handle.dimensions[2]  # shows through both faces of the plate


def test_every_shape_is_drawn_in_its_place(scene, client):
    # One of each shape, side by side along x, each turned by a 3-1-3 sequence.
    dims = {"radius_m": 0.05, "inner_radius_m": 0.03, "length_m": 0.1, "width_m": 0.08, "height_m": 0.1}
    bodies = []
    for k, shape in enumerate(SHAPES.values()):
        record = {"shape": shape.name, "mass_kg": 1.0, "position_m": [0.2 * k, 0.0, 0.0], "sequence": "3-1-3", "angles_deg": [10.0, 20.0, 30.0]}
        bodies.append(record | {d: dims[d] for d in shape.dimensions})
    set_params(scene, bodies=bodies)
    assert len(scene._part_handles) == len(SHAPES)
    for part, handle in zip(scene.body.parts, scene._part_handles):
        np.testing.assert_allclose(np.asarray(handle.position, float), part.position_m, atol=1e-12)
        # The drawn orientation is the part's own: wxyz turns the mesh's z onto the part's own z.
        w, x, y, z = np.asarray(handle.wxyz, float)
        own_z = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
        np.testing.assert_allclose(own_z, part.rotation[:, 2], atol=1e-7)


def test_the_lessons_numbers_are_what_the_scene_shows_at_its_defaults(scene):
    # Lesson 5.2 quotes these to 5 significant figures (0.5 in the last digit).
    readout = scene.readout()
    shown = {"mass": 12.9894, "I_1": 0.18316, "I_2": 0.38959, "I_3": 0.41715, "I_xx": 0.28767, "I_yy": 0.41397,
             "I_zz": 0.28825, "I_xy": -0.01625, "I_xz": -0.10375, "I_yz": 0.00580, "trace": 0.98990,
             "I_xx_P": 0.33176, "I_yy_P": 0.50668, "I_zz_P": 0.33843, "centre_of_mass_x": -0.06167}  # fmt: skip
    for name, value in shown.items():
        assert readout.value(name) == pytest.approx(value, abs=5e-6), name
    set_params(scene, frame_sequence="3-2-1", frame_angles_deg=[30.0, 0.0, 0.0])
    turned = {"I_xx": 0.33332, "I_yy": 0.36832, "I_zz": 0.28825, "I_xy": -0.06281, "I_xz": -0.08695, "I_yz": 0.05690}
    for name, value in turned.items():
        assert scene.readout().value(name) == pytest.approx(value, abs=5e-6), name
