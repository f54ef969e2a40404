"""Every preset a scene offers validates against that scene's own parameters."""

from __future__ import annotations

import pytest

from app.scenes import SCENES

PRESETS = [(cls, preset) for cls in SCENES.values() for preset in cls.presets]


@pytest.mark.parametrize("cls, preset", PRESETS, ids=[f"{cls.id}:{preset.name}" for cls, preset in PRESETS])
def test_preset_values_are_valid_parameters(cls, preset):
    validated = cls.parameters.validate(preset.values)
    for name, value in preset.values.items():
        assert validated[name] == (list(value) if isinstance(value, tuple) else value)
