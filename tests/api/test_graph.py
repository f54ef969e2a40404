"""A session's graphs through the API: every series, invariant and energy part of the kept motion, and its CSV.

One app for the module, one heavy-top page with a connected viewer (through the
relay), paused once it has run a second, so every request reads the same kept
frames. The values must be the model's own series, invariants and energy budget
evaluated on the kept states, to 1e-12 (the same numpy operations on the same
numbers; 1e-12 only leaves room for a different summation order in a reduction).
"""

from __future__ import annotations

import csv
import io
import json
import math
import secrets
from collections.abc import Iterator

import numpy as np
import pytest
import viser
from fastapi.testclient import TestClient

from app.main import create_app
from app.scenes.host.graph import csv_column
from app.scenes.viser_boundary import viewer_camera_message
from app.settings import Settings
from tests.conftest import wait_until

VISER = [f"viser-v{viser.__version__}"]


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(Settings())) as client:
        yield client


def _strict_json(text: str):
    """Parse JSON refusing NaN and infinities (what a browser's JSON.parse refuses too)."""
    def refuse(constant):
        raise AssertionError(f"non-finite number {constant} in the answer")
    return json.loads(text, parse_constant=refuse)


class Page:
    def __init__(self, client: TestClient, scene_id: str) -> None:
        self.client, self.scene_id = client, scene_id
        self.session_id, self.key = f"graph-{secrets.token_hex(6)}", secrets.token_hex(16)
        answer = client.put(f"/api/scenes/{scene_id}/sessions/{self.session_id}", json={"params": {}}, headers={"X-Session-Key": self.key})
        assert answer.status_code == 200, answer.text

    @property
    def base(self) -> str:
        return f"/api/scenes/{self.scene_id}/sessions/{self.session_id}"

    def graph(self, **query) -> dict:
        answer = self.client.get(f"{self.base}/graph", params=query)
        assert answer.status_code == 200, answer.text
        return _strict_json(answer.text)

    def kept_frames(self) -> list[tuple[float, dict]]:
        """The host's kept frames of the page's one viewer (read directly: what the route must have evaluated)."""
        session = self.client.app.state.scene_host._sessions[self.session_id]
        with session.lock:
            (history,) = session.histories.values()
            return history.since(-math.inf)


@pytest.fixture(scope="module")
def page(client) -> Iterator[Page]:
    page = Page(client, "heavy-top")
    with client.websocket_connect(f"/viewer/heavy-top/{page.session_id}", subprotocols=VISER) as viewer:
        viewer.send_bytes(viewer_camera_message())
        playback = f"{page.base}/playback"
        wait_until(lambda: (client.get(playback).json().get("t_s") or 0.0) > 1.0, timeout_s=20, what="the page's top to move")
        assert client.put(playback, json={"playing": False}, headers={"X-Session-Key": page.key}).status_code == 200
        yield page


def test_the_graph_is_the_models_series_invariants_and_energies_on_the_kept_states(page):
    answer = page.graph(max_points=2000)
    frames = page.kept_frames()
    assert len(frames) > 30 and answer["scene_id"] == "heavy-top" and answer["note"] is None
    t_s = np.array([t for t, _ in frames])
    states = np.array([motion["y"] for _, motion in frames])
    np.testing.assert_array_equal(answer["t_s"], t_s)
    assert answer["span_s"] == [t_s[0], t_s[-1]] and np.all(np.diff(t_s) > 0)
    scene = page.client.app.state.scene_host.instances(page.session_id)[0]
    model, params = scene.run_model, scene.physical_params()
    expected = {
        **model.series(params, t_s, states),
        **model.invariants(params, states),
        **{f"energy_{k}": v for k, v in model.energy_budget(params, states).items()},
    }
    kinds = {q["name"]: q["kind"] for q in answer["quantities"]}
    assert set(kinds) == set(expected) == set(answer["values"])
    assert {kinds["theta"], kinds["energy"], kinds["energy_total_J"]} == {"series", "invariant", "energy"}
    for name, values in answer["values"].items():
        assert len(values) == len(t_s), name
        np.testing.assert_allclose(np.array(values, dtype=float), expected[name], rtol=1e-12, atol=1e-12 * np.max(np.abs(expected[name])), err_msg=name)
    labels = {q["name"]: (q["label"], q["unit"]) for q in answer["quantities"]}
    assert labels["theta"] == ("θ", "rad") and labels["spin"] == ("ω₃", "rad/s")
    assert labels["energy_rotational_kinetic_J"] == ("kinetic, rotational", "J")


def test_energy_bars_are_the_latest_frames_parts_in_order(page):
    energy = page.graph()["energy"]
    names = [part["name"] for part in energy["parts"]]
    assert names == ["energy_translational_kinetic_J", "energy_rotational_kinetic_J", "energy_potential_J", "energy_dissipated_J"]
    values = {part["name"]: part["value_J"] for part in energy["parts"]}
    kinetic_plus_potential = values["energy_translational_kinetic_J"] + values["energy_rotational_kinetic_J"] + values["energy_potential_J"]
    assert energy["total_J"] == pytest.approx(kinetic_plus_potential, rel=1e-12)
    # The heavy top is conservative: what shows as dissipated is the integration's drift, well under 1e-6 of the energy.
    assert abs(values["energy_dissipated_J"]) < 1e-6 * abs(energy["total_J"])
    assert energy["note"] is None


def test_since_s_gives_only_the_newer_frames(page):
    whole = page.graph(max_points=2000)
    middle = whole["t_s"][len(whole["t_s"]) // 2]
    newer = page.graph(since_s=middle, max_points=2000)
    tail = [i for i, t in enumerate(whole["t_s"]) if t > middle]
    assert newer["t_s"] == [whole["t_s"][i] for i in tail] and newer["t_s"][0] > middle
    assert newer["values"]["energy_total_J"] == [whole["values"]["energy_total_J"][i] for i in tail]
    later = page.graph(since_s=whole["t_s"][-1])
    assert later["t_s"] == [] and later["span_s"] is None and later["energy"] is not None  # the bars still show the latest frame


def test_max_points_thins_evenly_and_keeps_the_first_and_last_frames(page):
    whole = page.graph(max_points=2000)
    thin = page.graph(max_points=10)
    assert len(thin["t_s"]) == 10 and all(len(v) == 10 for v in thin["values"].values())
    assert thin["t_s"][0] == whole["t_s"][0] and thin["t_s"][-1] == whole["t_s"][-1]
    assert set(thin["t_s"]) <= set(whole["t_s"])
    steps = np.diff([whole["t_s"].index(t) for t in thin["t_s"]])
    assert steps.max() - steps.min() <= 1  # evenly spread


def test_the_csv_holds_the_same_numbers(page):
    answer = page.graph(max_points=2000)
    response = page.client.get(f"{page.base}/graph.csv")
    assert response.status_code == 200 and response.headers["content-type"].startswith("text/csv")
    assert response.headers["content-disposition"] == 'attachment; filename="heavy-top-graph.csv"'
    rows = list(csv.reader(io.StringIO(response.text)))
    units = {q["name"]: q["unit"] for q in answer["quantities"]}
    assert rows[0] == ["t_s"] + [csv_column(q["name"], q["unit"]) for q in answer["quantities"]]
    # Each column names its unit once: in its name (energy_total_J), else in brackets (theta (rad)); none without one.
    assert "theta (rad)" in rows[0] and "energy_total_J" in rows[0] and units["quaternion_norm_error"] == ""
    assert "quaternion_norm_error" in rows[0] and not [h for h in rows[0] if h.endswith("_J (J)")]
    body = np.array([[float(cell) for cell in row] for row in rows[1:]])
    np.testing.assert_array_equal(body[:, 0], answer["t_s"])
    for column, quantity in enumerate(answer["quantities"], start=1):
        np.testing.assert_array_equal(body[:, column], answer["values"][quantity["name"]])  # repr round-trips floats exactly


def test_a_scene_that_is_not_integrated_answers_with_a_note(client):
    page = Page(client, "four-bar")
    answer = page.graph()
    assert answer["quantities"] == [] and answer["t_s"] == [] and answer["energy"] is None
    assert "closed form" in answer["note"]


def test_unknown_scene_or_session_is_404_and_bad_queries_422(client, page):
    assert client.get(f"/api/scenes/no-such-scene/sessions/{page.session_id}/graph").status_code == 404
    assert client.get("/api/scenes/heavy-top/sessions/never-seen-session/graph").status_code == 404
    assert client.get(f"/api/scenes/four-bar/sessions/{page.session_id}/graph").status_code == 404  # the session shows another scene
    assert client.get("/api/scenes/heavy-top/sessions/never-seen-session/graph.csv").status_code == 404
    for query, field in (({"max_points": 9}, "max_points"), ({"max_points": 2001}, "max_points"), ({"max_points": "many"}, "max_points"),
                         ({"since_s": "nan"}, "since_s"), ({"since_s": "inf"}, "since_s"), ({"since_s": "soon"}, "since_s")):
        answer = client.get(f"{page.base}/graph", params=query)
        assert answer.status_code == 422, (query, answer.text)
        assert answer.json()["detail"][0]["loc"][-1] == field
    assert client.get("/api/scenes/heavy-top/sessions/short/graph").status_code == 422
