"""The pages about the heavy top say what its scene does (issue 29, item 10), against the served app.

- The Solver lab states the live scene's default integration from the scene's own choice
  (``IntegratedScene.live_default``, the function the scene's restart and pilot call): it must equal what the running
  scene's live panel says once its pilot has answered. It said "Splitting 4, 3 steps/frame" (the benchmark's choice for
  10 s at 60 frames/s) while the scene, choosing for a minute at 30 frames/s, ran splitting order 8 at 1 step/frame.
  The benchmark's own figures stay on the page, as its choice for its run.
- The heavy top's "Open as Python" script prints the readout's rows, with the readout's names and units, not only a
  2 s series. Run to the paused scene's time it must print what the served readout shows:
  the quadrature's numbers (nutation band, period, mean precession rate, locus) and the sleeping threshold to
  1e-9 relative (the same functions on the same numbers, printed to 12 figures), and the band θ swept by the
  integration to 2e-4 deg: the script's run and the scene's each meet the 1e-6 rad target (their integrators may
  differ: the script chooses for its span, the scene for a minute, and runs the fixed step rule until its pilot
  answers), so their θ differ by at most 2e-6 rad = 1.15e-4 deg at the same frames (the scene's frames, k/30 s).
"""

from __future__ import annotations

import html
import math
import re
import secrets

import pytest

from tests.api.conftest import live_viewer
from tests.conftest import wait_until
from tests.course.test_scripts import Printed, run_script

SCENE = "heavy-top"
#: The swept band's tolerance (deg): two runs each within 1e-6 rad of the exact motion, with margin.
SWEPT_TOL_DEG = 2e-4
#: The quadrature's numbers and the threshold: the same functions, printed to 12 significant figures.
SAME_FUNCTIONS_REL = 1e-9
FRAME_RATE_HZ = 30.0


def _measured(client, session_id: str) -> dict:
    """The live answer once the scene's step choice is measured (its pilot has answered)."""
    answers: list[dict] = []

    def measured() -> bool:
        answer = client.get(f"/api/scenes/{SCENE}/sessions/{session_id}/live")
        if answer.status_code != 200:
            return False
        answers.append(answer.json())
        return answers[-1].get("accuracy", {}).get("status") not in (None, "estimating")

    wait_until(measured, timeout_s=60, what="the heavy top's pilot to answer")
    return answers[-1]


def test_the_solver_lab_states_the_live_scenes_own_default(client):
    session_id = f"lab-{secrets.token_hex(6)}"
    with live_viewer(client, SCENE, session_id):
        live = _measured(client, session_id)
    page = client.get("/solver-lab")
    assert page.status_code == 200
    stated = [html.unescape(s) for s in re.findall(r'<span class="live-default" data-scene="heavy-top">(.*?)</span>', page.text)]
    # Once in the prose, once beside the benchmark's heavy-top case: both the scene's own words.
    assert len(stated) == 2, stated
    assert all(s == live["description"] for s in stated), (stated, live["description"])
    text = html.unescape(page.text)
    assert f"at 30 frames per second ({live['accuracy']['accuracy']})" in text, live["accuracy"]
    # The benchmark's choice stays, said to be for its own run; it is not called the live scene's default.
    assert "Automatic choice over these 10 s at 60 frames per second:" in text
    assert "Default for the live scene" not in text


def test_the_heavy_top_script_prints_the_readout_the_page_shows(client, tmp_path):
    session_id = f"script-{secrets.token_hex(6)}"
    with live_viewer(client, SCENE, session_id):
        playback = f"/api/scenes/{SCENE}/sessions/{session_id}/playback"
        wait_until(lambda: client.get(playback).json()["t_s"] > 2.5, timeout_s=40, what="the top to run 2.5 s")
        assert client.put(playback, json={"playing": False}).status_code == 200
        answer = client.get(f"/api/scenes/{SCENE}/sessions/{session_id}/live").json()
    rows = {q["name"]: q for q in answer["readout"]["quantities"]}
    t_s = rows["t_s"]["value"]
    frame_t_s = round(t_s * FRAME_RATE_HZ) / FRAME_RATE_HZ
    assert abs(frame_t_s - t_s) < 1e-9  # the scene stands on a frame
    script = client.get(f"/api/scenes/{SCENE}/script.py").text
    assert "T_END_S = 2.0" in script and "FRAME_RATE_HZ = 30.0" in script
    # As the script says: set T_END_S to the page's t to compare with its readout.
    printed: Printed = run_script(script.replace("T_END_S = 2.0", f"T_END_S = {frame_t_s!r}"), tmp_path)
    assert printed.names("readout") == set(rows), (printed.names("readout"), set(rows))
    for name, row in rows.items():
        line = printed.value("readout", name)
        if row["value"] is None:  # a word: shown as it is, with no unit
            assert line == row["text"], (name, line, row)
            continue
        number, _, unit = line.partition(" ")
        assert unit == row["unit"], (name, line, row)
        tolerance = SWEPT_TOL_DEG if name.endswith("_swept_deg") else SAME_FUNCTIONS_REL * abs(row["value"])
        if name == "t_s":
            tolerance = 1e-9
        assert math.isclose(float(number), row["value"], rel_tol=0.0, abs_tol=tolerance), (name, float(number), row["value"])
    # What the band is: the swept one inside the predicted one, to the same tolerance.
    assert rows["theta_min_deg"]["value"] - SWEPT_TOL_DEG <= rows["theta_min_swept_deg"]["value"]
    assert rows["theta_max_swept_deg"]["value"] <= rows["theta_max_deg"]["value"] + SWEPT_TOL_DEG


@pytest.mark.parametrize("scene_id", ["heavy-top"])
def test_the_live_default_is_the_scenes_restart_choice(scene_id):
    """In one process: the page's source and the scene's restart choose the same integrator once the pilot is in."""
    from app.scenes import SCENES
    from app.scenes.kit.integrated import live_integrator

    cls = SCENES[scene_id]
    integrator, choice, frame_dt_s = cls.live_default()
    params = cls.parameters.defaults()
    physical = {k: params[k] for k in cls.model.parameters.by_name}
    again, choice_again = live_integrator(cls.model(), physical, {"method": "auto", "steps_per_frame": 0, "rtol": params["rtol"]}, frame_dt_s, run_pilots=False)
    assert again.describe(frame_dt_s) == integrator.describe(frame_dt_s) and choice_again == choice
    assert frame_dt_s == pytest.approx(1.0 / 30.0) and choice is not None and choice.meets_target
