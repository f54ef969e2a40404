"""The derivations shipped with the app (``app/physics/mechanics/shipped``) are the catalogue's and current: every
catalogue system in every formulation that applies, under the engine's and the system's present keys, and nothing
else; and what is shipped is what sympy derives now.

``DYNLAB_REGENERATE_REFERENCES=1`` (as for tests/references) derives them all again and writes them: about a minute
of sympy on the 2-core machine. Run it after changing the derivation engine or a catalogue system; this test says so
when it is needed."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from app.physics.mechanics import engine
from app.physics.mechanics.agreement import random_states
from app.physics.mechanics.engine import SHIPPED_DIRECTORY, available_formulations, derived, entry_paths
from app.physics.systems import analytical_systems

SYSTEMS = analytical_systems()
REGENERATE = "DYNLAB_REGENERATE_REFERENCES=1 uv run pytest tests/physics/mechanics/test_shipped_derivations.py"


def _catalogue() -> list[tuple[str, str]]:
    """(system id, formulation) of every catalogue derivation."""
    return [
        (system_id, formulation)
        for system_id, system in sorted(SYSTEMS.items())
        for formulation, reason in available_formulations(system).items()
        if not reason
    ]


def _ship(directory: Path, work: Path) -> None:
    """Derive every catalogue derivation afresh in ``work`` and put its two files in ``directory`` (emptied first)."""
    for system_id, formulation in _catalogue():
        engine._memory.clear()
        result = derived(SYSTEMS[system_id], formulation, directory=work)
        result.finish_shown()  # its shown forms simplified (a busy machine may have put that off), so it is stored
        for path in entry_paths(SYSTEMS[system_id], formulation, work):
            assert path.exists(), f"{system_id} by {formulation}: {path.name} was not written"
    engine._memory.clear()
    shutil.rmtree(directory, ignore_errors=True)
    directory.mkdir(parents=True)
    for system_id, formulation in _catalogue():
        for path in entry_paths(SYSTEMS[system_id], formulation, work):
            shutil.copy2(path, directory / path.name)


def test_the_shipped_derivations_are_the_catalogues_under_the_present_keys(tmp_path):
    if os.environ.get("DYNLAB_REGENERATE_REFERENCES") == "1":
        _ship(SHIPPED_DIRECTORY, tmp_path)
    expected = {path.name for key in _catalogue() for path in entry_paths(SYSTEMS[key[0]], key[1], SHIPPED_DIRECTORY)}
    present = {path.name for path in SHIPPED_DIRECTORY.glob("*") if path.suffix in (".json", ".py")}
    assert not expected - present, f"missing or stale (the engine or a system changed): run {REGENERATE}"
    assert not present - expected, f"derivations nothing asks for any more: run {REGENERATE}"


@pytest.mark.parametrize("system_id", ["simple-pendulum", "spherical-pendulum"])
def test_a_shipped_derivation_is_what_sympy_derives_now_and_is_read_without_sympy(system_id, tmp_path, monkeypatch):
    """The same generated code, character for character, and the same state derivative at random states."""
    system = SYSTEMS[system_id]
    p = np.array(system.parameter_array(system.parameters.defaults()))
    states = random_states(system, np.random.default_rng(11), 20)
    monkeypatch.setenv("DYNLAB_DERIVATION_CACHE", str(tmp_path / "empty-cache"))
    for formulation, reason in available_formulations(system).items():
        if reason:
            continue
        monkeypatch.setattr(engine, "_memory", engine.OrderedDict())
        fresh = derived(system, formulation, directory=tmp_path / "fresh")
        assert not fresh.from_cache
        monkeypatch.setattr(engine, "_memory", engine.OrderedDict())
        with monkeypatch.context() as no_sympy:
            no_sympy.setitem(engine.DERIVERS, formulation, _not_again)
            shipped = derived(system, formulation)
        assert shipped.from_cache and shipped.source_path.parent == SHIPPED_DIRECTORY, formulation
        assert shipped.source_path.read_text() == fresh.source_path.read_text(), formulation
        assert shipped.equations_latex == fresh.equations_latex, formulation
        for y in states:
            assert np.array_equal(shipped.state_derivative(0.3, y, p), fresh.state_derivative(0.3, y, p)), formulation


def _not_again(system):
    raise AssertionError("derived with sympy although the app ships this derivation")
