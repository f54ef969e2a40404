"""Composite bodies: parts placed, turned and subtracted, checked against quadrature of the assembled points."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.bodies.composite import combine, parts_from_records, validate_records
from app.physics.core.parameters import ParameterError
from app.physics.systems.ch05.composite_body import DEFAULT_BODIES
from tests.physics.bodies.quadrature import mass_properties, sample

SKEWED_DISK_ON_SHAFT = [
    {"shape": "disk", "mass_kg": 4.0, "radius_m": 0.25, "position_m": [0.02, 0.0, 0.3], "sequence": "3-2-1", "angles_deg": [20.0, 8.0, 0.0], "hole": False},
    {"shape": "cylinder", "mass_kg": 1.5, "radius_m": 0.02, "length_m": 0.8, "position_m": [0.0, 0.0, 0.4], "sequence": "1-2-3", "angles_deg": [0.0, 0.0, 0.0], "hole": False},
    {"shape": "cone", "mass_kg": 0.7, "radius_m": 0.05, "height_m": 0.12, "position_m": [0.0, 0.1, -0.05], "sequence": "3-1-3", "angles_deg": [40.0, 100.0, -30.0], "hole": False},
    {"shape": "box", "mass_kg": 2.0, "length_m": 0.1, "width_m": 0.2, "height_m": 0.05, "position_m": [-0.3, 0.2, 0.1], "sequence": "2-3-1", "angles_deg": [15.0, -25.0, 60.0], "hole": False},
    {"shape": "sphere", "mass_kg": 0.06, "radius_m": 0.02, "position_m": [-0.3, 0.2, 0.1], "sequence": "3-2-1", "angles_deg": [0.0, 0.0, 0.0], "hole": True},
]


def _quadrature_of(records: list[dict]) -> tuple[float, np.ndarray, np.ndarray]:
    """Assemble every part's own quadrature points in the reference frame (holes with negative weight) and integrate."""
    all_points, all_weights = [], []
    for part in parts_from_records(records):
        points, weights = sample(part.shape.name, **part.dimensions_m)
        all_points.append(points @ part.rotation.T + part.position_m)
        all_weights.append(weights * part.signed_mass_kg / np.sum(weights))
    return mass_properties(np.vstack(all_points), np.concatenate(all_weights))


@pytest.mark.parametrize("records", [DEFAULT_BODIES, SKEWED_DISK_ON_SHAFT], ids=["plate-with-hole-and-handle", "skewed-disk-on-shaft"])
def test_composite_matches_quadrature_of_its_assembled_points(records):
    """Mass, centre of mass and the tensor at G agree with the assembled quadrature to 1e-12 relative."""
    body = combine(parts_from_records(validate_records(records)))
    mass, centre, tensor_origin = _quadrature_of(records)
    assert body.mass_kg == pytest.approx(mass, rel=1e-13)
    assert np.max(np.abs(body.centre_of_mass_m - centre)) < 1e-13
    # Quadrature gives the tensor about the origin; take it to G by the definition (independent of parallel_axis).
    tensor_at_centre = tensor_origin - mass * (float(centre @ centre) * np.eye(3) - np.outer(centre, centre))
    assert np.max(np.abs(body.inertia_cm_kg_m2 - tensor_at_centre)) < 1e-12 * np.max(np.abs(tensor_at_centre))
    assert np.max(np.abs(body.inertia_about_kg_m2(np.zeros(3)) - tensor_origin)) < 1e-12 * np.max(np.abs(tensor_origin))


def test_a_hole_is_a_negative_body_by_monte_carlo_over_the_holed_plate():
    """The default plate with its hole, sampled directly (Sobol' points on the plate, those in the hole dropped): 2e-3 relative."""
    from scipy.stats import qmc

    a, b, density = 0.4, 0.3, 100.0
    hole_centre, hole_radius = np.array([0.1, 0.05]), 0.08
    u = qmc.Sobol(2, seed=3).random_base2(18)
    xy = (u - 0.5) * np.array([a, b])
    kept = xy[np.hypot(*(xy - hole_centre).T) > hole_radius]
    points = np.column_stack([kept, np.zeros(len(kept))])
    mass = density * a * b * len(kept) / len(xy)
    _, centre, tensor = mass_properties(points, np.full(len(kept), mass / len(kept)))
    plate_and_hole = [DEFAULT_BODIES[0], {**DEFAULT_BODIES[1], "mass_kg": density * math.pi * hole_radius**2}]
    body = combine(parts_from_records(validate_records(plate_and_hole)))
    assert body.mass_kg == pytest.approx(mass, rel=2e-3)
    assert np.max(np.abs(body.centre_of_mass_m - centre)) < 2e-3 * a
    tensor_at_centre = tensor - mass * (float(centre @ centre) * np.eye(3) - np.outer(centre, centre))
    assert np.max(np.abs(body.inertia_cm_kg_m2 - tensor_at_centre)) < 2e-3 * np.max(np.abs(tensor_at_centre))


def _with(index: int, **changes) -> list[dict]:
    records = [dict(r) for r in DEFAULT_BODIES]
    records[index].update(changes)
    return records


@pytest.mark.parametrize(
    "records, path, words",
    [
        (_with(0, mass_kg=-1.0), ("bodies", 0, "mass_kg"), "between"),
        (_with(2, mass_kg=math.inf), ("bodies", 2, "mass_kg"), "finite"),
        (_with(1, radius_m=0.5), ("bodies", 1), "does not lie inside"),  # hole bigger than its plate
        (_with(1, position_m=[0.3, 0.2, 0.0]), ("bodies", 1), "does not lie inside"),  # hole hanging off the edge
        (_with(1, mass_kg=5.0), ("bodies", 1, "mass_kg"), "more than"),  # denser than the plate it is cut from
        (_with(0, shape="tetrahedron"), ("bodies", 0, "shape"), "unknown shape"),
        (_with(0, sequence="3-3-1"), ("bodies", 0, "sequence"), "unknown rotation sequence"),
        (_with(2, position_m=[0.0, math.nan, 0.0]), ("bodies", 2, "position_m", 1), "finite"),
        (_with(2, position_m=[0.0, 1.0]), ("bodies", 2, "position_m"), "3 numbers"),
        (_with(0, colour="red"), ("bodies", 0, "colour"), "unknown field"),
        ([{"shape": "tube", "mass_kg": 1.0, "radius_m": 0.1, "inner_radius_m": 0.1, "length_m": 0.3}], ("bodies", 0, "inner_radius_m"), "less than"),
        ([{"shape": "cylinder", "mass_kg": 1.0, "radius_m": 0.1}], ("bodies", 0, "length_m"), "missing"),
        ([{**DEFAULT_BODIES[1]}], ("bodies",), "every entry is a hole"),
        ([], ("bodies",), "between 1 and"),
        (_with(1, hole="yes"), ("bodies", 1, "hole"), "true or false"),
    ],
)
def test_bodies_that_cannot_exist_are_refused_naming_the_entry_and_field(records, path, words):
    with pytest.raises(ParameterError) as caught:
        validate_records(records)
    assert caught.value.path == path
    assert words in caught.value.message


def test_a_solid_hole_cannot_be_cut_from_a_flat_plate():
    records = _with(1, shape="sphere", radius_m=0.01)
    with pytest.raises(ParameterError, match="same kind"):
        validate_records(records)


def test_records_are_normalised_with_defaults_filled():
    records = validate_records([{"shape": "sphere", "mass_kg": 2, "radius_m": 0.1}])
    assert records == [{"shape": "sphere", "mass_kg": 2.0, "radius_m": 0.1, "position_m": [0.0, 0.0, 0.0],
                        "sequence": "3-2-1", "angles_deg": [0.0, 0.0, 0.0], "hole": False}]


# -- issue 24, Found 12: two holes that overlap were subtracted twice -----------------------------------------------
PLATE = {"shape": "plate", "mass_kg": 12.0, "length_m": 0.4, "width_m": 0.3}


def _disk_hole(x: float, y: float = 0.0, radius: float = 0.08) -> dict:
    """A hole of the plate's density (12 kg / 0.12 m² = 100 kg/m²)."""
    return {"shape": "disk", "mass_kg": 100.0 * math.pi * radius**2, "radius_m": radius, "position_m": [x, y, 0.0], "hole": True}


def test_overlapping_holes_are_refused_naming_the_second_in_the_editors_words():
    """The issue's body: holes of radius 0.08 m at x = 0.05 and 0 m overlap over a lens of 0.0127 m²; subtracting both
    gave 7.9788 kg for a body of 9.2027 kg. It is refused, pointing at body 3 (the editor's row) and naming body 2."""
    records = [PLATE, _disk_hole(0.05), _disk_hole(0.0)]
    with pytest.raises(ParameterError) as caught:
        validate_records(records)
    assert caught.value.path == ("bodies", 2)
    assert "overlaps the hole at body 2" in caught.value.message and "removed twice" in caught.value.message


BLOCK = {"shape": "box", "mass_kg": 270.0, "length_m": 0.3, "width_m": 0.3, "height_m": 0.3}  # 1e4 kg/m³


def _solid_hole(record: dict) -> dict:
    """``record`` as a hole of the block's density (1e4 kg/m³)."""
    from app.physics.bodies.composite import SHAPES

    shape = SHAPES[record["shape"]]
    return {**record, "mass_kg": 1e4 * shape.measure(*(record[d] for d in shape.dimensions)), "hole": True}


@pytest.mark.parametrize(
    ("first", "second"),
    [
        # A small cube whose corner region enters a sphere: overlap depth 0.005 m of the cube's 0.02 m.
        ({"shape": "sphere", "radius_m": 0.05}, {"shape": "box", "length_m": 0.02, "width_m": 0.02, "height_m": 0.02, "position_m": [0.055, 0.0, 0.0]}),
        # Two bores crossing at right angles.
        ({"shape": "cylinder", "radius_m": 0.02, "length_m": 0.2},
         {"shape": "cylinder", "radius_m": 0.02, "length_m": 0.2, "sequence": "3-2-1", "angles_deg": [0.0, 90.0, 0.0]}),
    ],
)
def test_solid_holes_that_overlap_are_refused_too(first, second):
    with pytest.raises(ParameterError, match="overlaps the hole at body 2"):
        validate_records([BLOCK, _solid_hole(first), _solid_hole(second)])


@pytest.mark.parametrize("centres_x", [(0.08, -0.08), (-0.1, 0.06)])
def test_holes_that_only_touch_are_kept_and_each_removes_its_own_mass(centres_x):
    """Tangent disks (centres 0.16 m apart, radius 0.08 m) share no area: 12 − 2 × 2.0106 kg, checked against a Monte
    Carlo integral over the plate (400 000 points: standard error of the mass fraction 0.0008, so 5e-3 relative)."""
    records = [PLATE, *(_disk_hole(x) for x in centres_x)]
    body = combine(parts_from_records(validate_records(records)))
    assert body.mass_kg == pytest.approx(12.0 - 2 * 100.0 * math.pi * 0.08**2, rel=1e-12)
    rng = np.random.default_rng(5)
    points = np.column_stack([rng.uniform(-0.2, 0.2, 400_000), rng.uniform(-0.15, 0.15, 400_000)])
    solid = np.ones(len(points), bool)
    for x in centres_x:
        solid &= np.hypot(points[:, 0] - x, points[:, 1]) > 0.08
    assert body.mass_kg == pytest.approx(12.0 * solid.mean(), rel=5e-3)


def test_a_holes_samples_fill_it():
    """The lattice sampling a hole covers it: for a disk of radius 0.08 m, 64² cells over its bounding square, the cells
    kept times a cell's area is πr² to within the cells the rim cuts (~2πr / h of them: 4 %)."""
    from app.physics.bodies.composite import OVERLAP_CELLS, sample_points

    part = parts_from_records(validate_records([PLATE, _disk_hole(0.05)]))[1]
    cell = (0.16 / OVERLAP_CELLS["area"]) ** 2
    assert len(sample_points(part)) * cell == pytest.approx(math.pi * 0.08**2, rel=0.04)
    assert np.all(part.contains(sample_points(part)))
