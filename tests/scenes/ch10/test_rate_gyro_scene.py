"""The rate gyro's scale: the numbers a student reads are where the pointer stops for that input rate.

In the steady state β = G Ω (G = I_a ω_s / k); a numbered tick for Ω must sit where the pointer's tip is at
that β, to round-off (1e-12 m: a few float64 operations on numbers of order 1). Only the ends and zero are
numbered, in full-size type, so the numbers cannot run into each other on the short arc.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from app.physics.systems.ch10 import rate_gyro as physics
from app.scenes.ch10.rate_gyro import POINTER_LENGTH, SCALE_LABEL_GAP, SCALE_LABEL_SIZE, SCALE_X, RateGyroScene


def scale_labels(client) -> dict[str, object]:
    return {name: handle for name, handle in client.scene.handles.items() if re.fullmatch(r"/table/scale/t\d+", name) and not handle._impl.removed}


@pytest.mark.parametrize("rate", [0.5, -0.3, 2.0])
def test_numbered_ticks_sit_where_the_pointer_reads_their_rate(client, rate):
    scene = RateGyroScene(client, RateGyroScene.parameters.validate({"input_rate_rad_s": rate}))
    gain = physics.steady_gain_s(scene.params)
    labels = scale_labels(client)
    texts = sorted(handle.text for handle in labels.values())
    assert len(labels) == 3 and "0" in texts and all(t == "0" or t.endswith(" rad/s") for t in texts)
    for handle in labels.values():
        omega = 0.0 if handle.text == "0" else float(re.match(r"([+−][\d.]+)", handle.text).group(1).replace("−", "-"))
        beta = gain * omega
        expected = np.array([SCALE_X, -math.sin(beta), math.cos(beta)]) * np.array([1.0, POINTER_LENGTH + SCALE_LABEL_GAP, POINTER_LENGTH + SCALE_LABEL_GAP])
        np.testing.assert_allclose(handle.position, expected, rtol=0, atol=1e-12)
        assert handle.font_screen_scale == SCALE_LABEL_SIZE >= 1.0
    ends = [float(re.match(r"([+−][\d.]+)", t).group(1).replace("−", "-")) for t in texts if t != "0"]
    assert sorted(ends) == pytest.approx([-max(ends), max(ends)]) and max(ends) >= abs(rate) - 1e-12  # the scale reaches Ω₀
    scene.close()
