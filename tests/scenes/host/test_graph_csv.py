"""The graph's CSV (app/scenes/host/graph.py): each column names its unit once.

A quantity whose name already ends in its unit (``energy_total_J``, ``spin_rate_rad_s``, ``driving_torque_N_m``,
``p_theta_kg_m2_s``) is headed by its name alone; one whose name does not (``theta``) gets the unit in brackets,
and a unitless one its name. The header once read ``energy_total_J (J)``: the unit twice.
"""

from __future__ import annotations

import csv
import io

import pytest

from app.scenes.host.graph import csv_column, graph_csv, name_carries_unit


@pytest.mark.parametrize(
    ("name", "unit", "heading"),
    [
        ("energy_total_J", "J", "energy_total_J"),
        ("energy_dissipated_J", "J", "energy_dissipated_J"),
        ("spin_rate_rad_s", "rad/s", "spin_rate_rad_s"),
        ("driving_torque_N_m", "N·m", "driving_torque_N_m"),
        ("p_theta_kg_m2_s", "kg·m²/s", "p_theta_kg_m2_s"),
        ("x_m", "m", "x_m"),
        ("theta", "rad", "theta (rad)"),
        ("energy", "J", "energy (J)"),  # a name that is not its unit's spelling keeps the unit in brackets
        ("jacobi_integral", "J/kg", "jacobi_integral (J/kg)"),
        ("multiplier", "N/m", "multiplier (N/m)"),
        ("swing_plane_bearing", "deg", "swing_plane_bearing (deg)"),
        ("bob_up", "m", "bob_up (m)"),  # ends in a letter m, but not in "_m"
        ("quaternion_norm_error", "", "quaternion_norm_error"),
    ],
)
def test_each_column_names_its_unit_once(name, unit, heading):
    assert csv_column(name, unit) == heading
    assert name_carries_unit(name, unit) == (heading == name and unit != "")


def test_the_header_of_a_graph_answer():
    answer = {
        "t_s": [0.0, 0.5],
        "quantities": [
            {"name": "theta", "unit": "rad"},
            {"name": "quaternion_norm_error", "unit": ""},
            {"name": "energy_total_J", "unit": "J"},
        ],
        "values": {"theta": [0.1, 0.2], "quaternion_norm_error": [0.0, None], "energy_total_J": [1.5, 1.5]},
    }
    rows = list(csv.reader(io.StringIO(graph_csv(answer))))
    assert rows[0] == ["t_s", "theta (rad)", "quaternion_norm_error", "energy_total_J"]
    assert rows[1:] == [["0.0", "0.1", "0.0", "1.5"], ["0.5", "0.2", "", "1.5"]]
