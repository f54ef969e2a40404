"""Physical systems, one module each, grouped by the chapter whose lessons use them (``chNN``).

A system module holds its parameters, its model (closed form or integrated) and
its reference solution beside it. Systems used by more than one chapter
(the rotating Earth) sit here at the top.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil
from functools import cache

from app.physics.core.solution import WorkedExample


def system_modules() -> list[str]:
    """Every system module's dotted name, chapter by chapter (``ch01`` … ``ch10``), then by name."""
    names = []
    for chapter in sorted(m.name for m in pkgutil.iter_modules(__path__) if m.ispkg and m.name.startswith("ch")):
        package = importlib.import_module(f"{__name__}.{chapter}")
        names += sorted(f"{package.__name__}.{m.name}" for m in pkgutil.iter_modules(package.__path__) if not m.ispkg)
    return names


@cache
def worked_examples() -> dict[str, WorkedExample]:
    """Every worked example by id, ordered by chapter then id: the ``EXAMPLE`` a system module declares (found, not
    listed)."""
    examples: dict[str, WorkedExample] = {}
    for name in system_modules():
        example = getattr(importlib.import_module(name), "EXAMPLE", None)
        if isinstance(example, WorkedExample):
            if example.id in examples:
                raise ValueError(f"two worked examples share the id {example.id!r} ({name})")
            examples[example.id] = example
    return dict(sorted(examples.items(), key=lambda item: (item[1].chapter, item[0])))


@cache
def analytical_systems() -> dict:
    """Every catalogue system of the derivation engine by id (chapters 7–9): the ``SYSTEM`` a module declares."""
    from app.physics.mechanics.description import SystemDescription

    systems: dict[str, SystemDescription] = {}
    for name in system_modules():
        system = getattr(importlib.import_module(name), "SYSTEM", None)
        if isinstance(system, SystemDescription):  # a model module may import its system's SYSTEM: the same object
            if systems.get(system.id, system) is not system:
                raise ValueError(f"two catalogue systems share the id {system.id!r} ({name})")
            systems[system.id] = system
    return systems


def multibody_systems() -> dict:
    """Every system described by its parts (bodies, joints, rolling contacts) by id: the ``SYSTEM`` a module
    declares as a :class:`~app.physics.mechanics.multibody.parts.MultibodySystem`, or a family of them (one id whose
    parameters choose the member)."""
    from app.physics.mechanics.multibody.parts import MultibodyFamily, MultibodySystem

    systems: dict[str, MultibodySystem | MultibodyFamily] = {}
    for name in system_modules():
        system = getattr(importlib.import_module(name), "SYSTEM", None)
        if isinstance(system, MultibodySystem | MultibodyFamily):
            if systems.get(system.id, system) is not system:
                raise ValueError(f"two multibody systems share the id {system.id!r} ({name})")
            systems[system.id] = system
    return systems


def multibody_member(system_id: str, params):
    """The catalogue system ``system_id``'s member for ``params`` (validated here): what a bounded child derives."""
    entry = multibody_catalogue()[system_id]
    return entry.member(entry.parameters.validate(params))


@functools.cache
def multibody_catalogue() -> dict:
    """:func:`multibody_systems`, found once."""
    return multibody_systems()
