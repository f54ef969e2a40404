"""Scenes: one per file, grouped by chapter (``chNN``), each drawing one model for one browser.

:data:`SCENES` maps scene id to class. It is found, not kept by hand: every
:class:`~app.scenes.kit.Scene` subclass with an ``id`` defined in a module under
``app/scenes/chNN/`` is registered, chapter by chapter.
"""

from __future__ import annotations

import importlib
import pkgutil

from app.scenes.kit import Scene


def _discover() -> dict[str, type[Scene]]:
    found: dict[str, type[Scene]] = {}
    chapters = sorted(m.name for m in pkgutil.iter_modules(__path__) if m.ispkg and m.name.startswith("ch"))
    for chapter in chapters:
        package = importlib.import_module(f"{__name__}.{chapter}")
        for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name):
            module = importlib.import_module(f"{package.__name__}.{info.name}")
            for value in vars(module).values():
                if (
                    isinstance(value, type)
                    and issubclass(value, Scene)
                    and value.__module__ == module.__name__
                    and "id" in vars(value)
                ):
                    if value.id in found:
                        raise ValueError(
                            f"two scenes share the id {value.id!r}: {found[value.id].__module__} and {module.__name__}"
                        )
                    found[value.id] = value
    return found


SCENES: dict[str, type[Scene]] = _discover()

__all__ = ["SCENES", "Scene"]
