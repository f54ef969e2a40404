"""The course: lesson files parsed (:mod:`.lessons`) and checked against the scene, example and derivation registries
(:mod:`.catalogue`)."""

from app.course.catalogue import Catalogue, CatalogueError, load_catalogue
from app.course.lessons import LESSONS_DIR, Chapter, Lesson, Section, render_markdown

__all__ = [
    "LESSONS_DIR",
    "Catalogue",
    "CatalogueError",
    "Chapter",
    "Lesson",
    "Section",
    "load_catalogue",
    "render_markdown",
]
