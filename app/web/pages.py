"""HTML pages: the course outline, lesson pages, the Solver lab and the viser viewer page."""

from __future__ import annotations

import html
import math
import re
from datetime import datetime
from functools import cache, lru_cache
from pathlib import Path
from string import Template

import viser
from fastapi import APIRouter, HTTPException
from fastapi.responses import HTMLResponse, RedirectResponse, Response

from app.api.deps import CatalogueDep, SceneHostDep, SettingsDep
from app.course import Catalogue, Chapter, Lesson, bench_reports, render_markdown
from app.course.lessons import split_front_matter
from app.physics.core.solution import WorkedExample
from app.physics.mechanics.derivation import FORMULATION_TITLES, FORMULATIONS
from app.physics.mechanics.engine import available_formulations
from app.scenes import SCENES
from app.scenes.host.host import SESSION_ID_PATTERN
from app.scenes.kit import IntegratedScene
from app.web.page_config import config_script, page_config
from app.web.static_files import inline_module, modulepreload_links
from app.web.viewer_client import unpacked_client

router = APIRouter(tags=["pages"], include_in_schema=False)
TEMPLATES = Path(__file__).resolve().parent / "templates"
esc = html.escape


@cache
def _template(name: str) -> Template:
    return Template((TEMPLATES / name).read_text(encoding="utf-8"))


#: CSS added to viser's client page on every viewer route (a lesson's viewer, a room's, the projector's).
#: The lesson page carries the controls, so viser's own control panel is hidden: on a wide viewer its floating
#: dock window (the one holding the "viser-control-panel" tab: the "Connected" pill, and when expanded the
#: websocket URL, dev settings, scene tree and share button), on a viewer under 576 px wide its bottom sheet (the
#: panel outside the dock root, a Paper around a ScrollArea). Every floating window is hidden, not only the one
#: holding the tab: viser draws the panel's window a second or more before the tab exists (a flash of the websocket
#: pill on every load), and our scenes add no GUI of their own, so no other window is lost. Selectors from viser 1.1.1's
#: client
#: (ControlPanelDock.tsx, ControlPanel.tsx, BottomPanel.tsx), pinned by
#: tests/browser/test_viewer_controls_in_browser.py.
#: Add viewer styling (label sizes, projector mode) here.
VIEWER_CSS = """
[data-floating-window],
[data-dock-leaf]:has([data-dock-tab="viser-control-panel"]),
#root .mantine-Paper-root:not([data-floating-window]):has(> div > .mantine-ScrollArea-root) \
{ display: none !important; }
"""

#: Script added to viser's client page, for the keyboard (outside text boxes; viser's own keys orbit, move and pan):
#: "+" and "−" zoom (the camera moves towards or away from the point it looks at, 15 % a press) and "R" puts the camera
#: back at the scene's start pose (viser's "Reset View": the initial camera each scene sets). Should viser's hook
#: be missing, "R" asks the page around the viewer to reset it (a lesson page does so through the session's playback).
#: A viewer opened with ``wait`` (a lesson page preloads its own while it makes the session) starts viser's client at
#: once but opens the websocket only when the page says the session exists ("dynlab:session-ready"; it asks with
#: "dynlab:viewer-waiting" in case it was told before it listened): viser 1.1.1's client keeps its websocket in a
#: web worker and connects when told the server's address, so every message to its workers waits until then.
#: A viewer that lost its connection (its scene worker restarted) retries while it is shown, not only while it has
#: the focus as viser's client would have it.
VIEWER_SCRIPT = """
// viser 1.1.1's client retries a lost connection only while its own document has the focus (document.hasFocus()).
// In a lesson page the focus is the page's (a student reading, or moving a slider), so after a scene worker restarted
// the viewer stayed disconnected, the scene frozen, until someone clicked into it. Here it retries while it is shown.
document.hasFocus = () => document.visibilityState === "visible";
document.addEventListener("keydown", (event) => {
  const target = event.target instanceof Element ? event.target : null;
  if (event.ctrlKey || event.metaKey || event.altKey || \
(target && target.closest("input, select, textarea, [contenteditable]"))) return;
  const viewer = window.__viserMutable;
  const controls = viewer && viewer.cameraControl;
  const zoom = { "+": 1, "=": 1, "-": -1, "_": -1 }[event.key];
  if (zoom && controls && controls.enabled) {
    event.preventDefault();
    controls.dolly(zoom * 0.15 * controls.distance, true);
  } else if (event.key === "r" || event.key === "R") {
    if (viewer && typeof viewer.resetCameraPose === "function") viewer.resetCameraPose(true);
    else if (window.parent !== window) window.parent.postMessage({ type: "dynlab:reset-view" }, location.origin);
  }
});
if (new URLSearchParams(location.search).has("wait") && window.parent !== window) {
  const ready = new Promise((resolve) => window.addEventListener("message", (event) => {
    const data = event.origin === location.origin && event.source === window.parent ? event.data : null;
    if (data && data.type === "dynlab:session-ready") resolve();
  }));
  const NativeWorker = window.Worker;
  window.Worker = class extends NativeWorker {
    postMessage(...args) { ready.then(() => super.postMessage(...args)); }
  };
  window.parent.postMessage({ type: "dynlab:viewer-waiting" }, location.origin);
}
"""

_VIEWER_HEAD_END = b"</title>"


@lru_cache(maxsize=1)
def viewer_client_html() -> bytes:
    """viser's client page (unpacked: :func:`unpacked_client`) with :data:`VIEWER_CSS` and :data:`VIEWER_SCRIPT` in its
    head and a title saying what it shows: the page every viewer route serves."""
    client = unpacked_client().page
    if client.count(_VIEWER_HEAD_END) != 1:
        raise RuntimeError(
            f"viser {viser.__version__}'s client page has no single "
            f"{_VIEWER_HEAD_END!r}: the viewer page cannot be patched"
        )
    title_start = client.index(b"<title>")
    added = f"<style>{VIEWER_CSS}</style><script>{VIEWER_SCRIPT}</script>".encode()
    return (
        client[:title_start]
        + "<title>3D scene — Dynamics Lab</title>".encode()
        + added
        + client[client.index(_VIEWER_HEAD_END) + len(_VIEWER_HEAD_END) :]
    )


def _page(title: str, body: str, *, scripts: tuple[str, ...] = (), config: dict | None = None) -> HTMLResponse:
    """A page: ``body`` in the site's frame, its configuration (:func:`page_config` with ``config``) and its
    ``scripts``, each an ES module that imports what it needs (so their order is no one's concern), with every module
    they import preloaded (:func:`modulepreload_links`)."""
    modules = modulepreload_links(scripts) + "".join(f'<script type="module" src="{src}"></script>' for src in scripts)
    return HTMLResponse(
        _template("page.html").substitute(
            title=esc(title), body=body, config=config_script(page_config(**(config or {}))), scripts=modules
        )
    )


def _section_item(number: str, title: str, lessons: list[Lesson]) -> str:
    """One section of a chapter's list, saying in words whether it has a lesson (links to each) or not yet."""
    if lessons:
        links = ", ".join(f'<a href="{esc(l.url)}">{esc(l.title)}</a>' for l in lessons)
        status = f'<span class="sec-status has-lesson">lesson{"s" if len(lessons) > 1 else ""}:</span> {links}'
    else:
        status = '<span class="sec-status no-lesson">no lesson yet</span>'
    return f'<li data-section="{esc(number)}"><span class=sec-num>{esc(number)}</span> {esc(title)} — {status}</li>'


def _chapter_card(chapter: Chapter) -> str:
    by_section: dict[str, list[Lesson]] = {}
    for lesson in chapter.lessons:
        by_section.setdefault(lesson.section, []).append(lesson)
    sections = "".join(_section_item(s.number, s.title, by_section.get(s.number, [])) for s in chapter.sections)
    covered = sum(1 for s in chapter.sections if s.number in by_section)
    if chapter.lessons:
        lessons = "".join(
            f'<li><a href="{esc(l.url)}"><span class=sec-num>{esc(l.section)}</span> {esc(l.title)}</a>'
            + (' <span class="tag" title="has a live 3D scene">3D</span>' if l.scene else "")
            + "</li>"
            for l in chapter.lessons
        )
        lessons_html = f'<h4>Lessons</h4><ul class="lessons">{lessons}</ul>'
    else:
        lessons_html = '<p class="muted">No interactive lessons for this chapter yet.</p>'
    return (
        f'<section class="chapter" id="chapter-{chapter.number}" aria-labelledby="ch{chapter.number}-title">'
        f'<h3 id="ch{chapter.number}-title"><span class="ch-num">{chapter.number}</span> {esc(chapter.title)}</h3>'
        f'<p class="summary">{esc(chapter.summary)}</p>'
        f"<details><summary>Sections: {covered} of {len(chapter.sections)} with a lesson</summary><ul "
        f'class="sections">{sections}</ul></details>'
        f"{lessons_html}</section>"
    )


@router.get("/", response_class=HTMLResponse)
def course_page(catalogue: CatalogueDep) -> HTMLResponse:
    body = _template("course.html").substitute(chapters="".join(_chapter_card(ch) for ch in catalogue.chapters))
    return _page("Dynamics Lab — course", body, scripts=("/static/js/course_page.js",))


def _lesson_config(lesson: Lesson, catalogue: Catalogue, scene_id: str | None) -> dict:
    """What lesson.js needs: the shown scene's schema (the page shows one viewer) and every example's schema.

    The catalogue checked every reference at start-up, so each id is found here.
    """
    return {
        "lesson_id": lesson.id,
        "section": lesson.section,
        "scene": catalogue.scenes[scene_id].schema() if scene_id else None,
        "examples": [_example_config(catalogue.examples[example_id]) for example_id in lesson.examples],
        "derivations": [_derivation_config(catalogue.derivations[system_id]) for system_id in lesson.derivations],
        "linearised": [_linearised_config(catalogue.multibody[system_id]) for system_id in lesson.linearised],
    }


def _example_config(example: WorkedExample) -> dict:
    """An example's schema, with its story rendered (Markdown to HTML; the page typesets the math)."""
    config = example.schema()
    if example.story is not None:
        config["story_html"] = {part: render_markdown(text) for part, text in example.story.as_dict().items()}
    return config


def _derivation_config(system) -> dict:
    """What derivations.js needs to ask /api/systems/{id}/derive for each formulation and show why others do not
    apply."""
    reasons = available_formulations(system)
    return {
        "id": system.id,
        "title": system.title,
        "formulations": [{"id": f, "title": FORMULATION_TITLES[f], "unavailable": reasons[f]} for f in FORMULATIONS],
        "assumptions": system.assumptions,
    }


def _linearised_config(system) -> dict:
    """What stability.js needs to ask /api/systems/{id}/eigenvalues along the reference motion's sweep and name
    where stability changes."""
    reference = system.reference
    parameter, low, high = reference.sweep
    return {
        "id": system.id,
        "title": system.title,
        "about": reference.about,
        "parameters": [p.name for p in system.parameters.parameters],
        "parameter": parameter,
        "label": system.parameters.by_name[parameter].display_name(),
        "low": low,
        "high": high,
        "crossing_names": [
            {"becomes": becomes, "oscillating": oscillating, "name": name}
            for becomes, oscillating, name in reference.crossing_names
        ],
    }


def _scene_picker(lesson: Lesson, catalogue: Catalogue, shown: str | None) -> str:
    """Links between the scenes of a lesson that names several (empty for one or none)."""
    if len(lesson.scenes) < 2:
        return ""
    current = ' aria-current="page"'
    links = "".join(
        f'<a href="{esc(lesson.url)}?scene={esc(scene_id)}"{current if scene_id == shown else ""}>'
        f"{esc(catalogue.scenes[scene_id].title)}</a>"
        for scene_id in lesson.scenes
    )
    return f'<nav class="scene-picker" aria-label="Scenes of this lesson">{links}</nav>'


@router.get("/lessons/{lesson_id}", response_class=HTMLResponse)
def lesson_page(lesson_id: str, catalogue: CatalogueDep, scene: str | None = None) -> HTMLResponse:
    """A lesson page; ``?scene=<id>`` picks which of the lesson's scenes the viewer shows (default: the first)."""
    lesson = catalogue.lessons.get(lesson_id)
    if lesson is None:
        raise HTTPException(status_code=404, detail=f"no lesson {lesson_id!r}")
    if scene is not None and scene not in lesson.scenes:
        named = ", ".join(lesson.scenes) or "none"
        raise HTTPException(
            status_code=404, detail=f"lesson {lesson_id!r} has no scene {scene!r} (its scenes: {named})"
        )
    shown = scene or lesson.scene
    chapter = catalogue.chapter_of(lesson)
    previous, following = catalogue.neighbours(lesson)
    nav = "".join(
        f'<a class="{cls}" href="{esc(l.url)}">{arrow} {esc(l.section)} {esc(l.title)}</a>' if l else "<span></span>"
        for l, cls, arrow in ((previous, "prev", "←"), (following, "next", "→"))
    )
    body = _template("lesson.html").substitute(
        chapter_number=chapter.number,
        chapter_title=esc(chapter.title),
        section=esc(lesson.section),
        title=esc(lesson.title),
        summary=esc(lesson.summary),
        lesson_html=lesson.body_html,
        nav=nav,
        scene_picker=_scene_picker(lesson, catalogue, shown),
        has_scene="has-scene" if lesson.scene or lesson.examples else "no-scene",
        viewer_preload=inline_module("js/viewer_preload.js") if shown else "",
    )
    return _page(
        f"{lesson.section} {lesson.title} — Dynamics Lab",
        body,
        scripts=("/static/js/lesson_page.js",),
        config=_lesson_config(lesson, catalogue, shown),
    )


# ---- Solver lab ---------------------------------------------------------------------------


def fmt_sig(value: object, digits: int = 3, min_exp: int = -3) -> str:
    """A number to ``digits`` significant figures, as HTML: decimals from 10^min_exp to 9999, else a × 10ⁿ."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return "—"
    if value == 0:
        return "0"
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    exp = int(exponent)
    if min_exp <= exp <= 3:
        return f"{round(value, digits - 1 - exp):.{max(0, digits - 1 - exp)}f}"
    return f"{mantissa} × 10<sup>{str(exp).replace('-', '−')}</sup>"


def fmt_setting(value: object) -> str:
    """A solver setting: integers as they are, powers of ten as 10ⁿ, other numbers to 3 significant figures."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return esc(str(value))
    if isinstance(value, int) or (math.isfinite(value) and value.is_integer() and abs(value) < 1e6):
        return str(int(value))
    if value > 0 and math.isfinite(value):
        exp = round(math.log10(value))
        if math.isclose(value, 10.0**exp, rel_tol=1e-9):
            return f"10<sup>{str(exp).replace('-', '−')}</sup>"
    return fmt_sig(value)


def _setting_name(name: object) -> str:
    return esc(str(name or "setting").replace("_", " "))


def _esc_code(text: str) -> str:
    """Escape, then show `backticked` parts as code."""
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", esc(text))


def _with_unit(value_html: str, unit: str) -> str:
    return f"{value_html} {esc(unit)}" if unit and value_html != "—" else value_html


@lru_cache(maxsize=4)
def _solver_lab_text(lessons_dir: Path) -> tuple[dict, str]:
    """Front matter and rendered body of ``solver-lab.md`` in the lessons folder (TOML between '+++' lines, like the
    lessons)."""
    path = lessons_dir / "solver-lab.md"
    meta, body = split_front_matter(path.read_text(encoding="utf-8"), str(path))
    return meta, render_markdown(body)


def _method_labels(scene: dict) -> dict[str, str]:
    return {str(m.get("method")): str(m.get("label") or m.get("method")) for m in scene.get("methods") or ()}


def _ratio_sentence(ratio: dict, scene: dict) -> str:
    if ratio.get("text"):
        return esc(str(ratio["text"]))
    labels = _method_labels(scene)
    default = scene.get("default") or {}
    ours = esc(labels.get(str(default.get("method")), str(default.get("method", "the default method"))))
    baseline = esc(labels.get(str(ratio.get("baseline")), str(ratio.get("baseline", "the baseline"))))
    value = ratio.get("ratio")
    at = _with_unit(fmt_setting(ratio.get("at_error")), str(scene.get("error_unit") or ""))
    if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        return f"At an error of {at}, {baseline} could not be compared with {ours}."
    if value >= 1:
        return f"At an error of {at}, {baseline} takes <strong>{fmt_sig(value)} times</strong> the CPU time of {ours}."
    return f"At an error of {at}, {baseline} is <strong>{fmt_sig(1 / value)} times faster</strong> than {ours}."


def _point_note(point: dict) -> str:
    status = point.get("status", "ok")
    error = point.get("error")
    if status != "ok":
        return f"{esc(str(status))}; not plotted"
    if isinstance(error, (int, float)) and not isinstance(error, bool) and error == 0:
        return "error 0 (below what the reference resolves); not plotted"
    if not isinstance(error, (int, float)) or isinstance(error, bool) or not math.isfinite(error):
        return "no finite error; not plotted"
    return ""


def _points_table(scene: dict) -> str:
    unit = str(scene.get("error_unit") or "")
    default = scene.get("default") or {}
    rows = []
    count = 0
    for method in scene.get("methods") or ():
        points = list(method.get("points") or ())
        count += len(points)
        setting_name = _setting_name(method.get("setting_name"))
        for i, point in enumerate(points):
            is_default = (method.get("method"), point.get("setting")) == (default.get("method"), default.get("setting"))
            cpu = point.get("cpu_s")
            cpu_ms = 1e3 * cpu if isinstance(cpu, (int, float)) and not isinstance(cpu, bool) else None
            evals = point.get("rhs_evals")
            evals_text = f"{evals:,}" if isinstance(evals, int) and not isinstance(evals, bool) else "—"
            first = (
                f'<th scope="rowgroup" rowspan="{len(points)}">{esc(str(method.get("label") or method.get("method")))}'
                f'<span class="family">{esc(str(method.get("family", "")))}; setting: {setting_name}</span></th>'
                if i == 0
                else ""
            )
            note = _point_note(point)
            rows.append(
                f"<tr{' class=is-default' if is_default else ''}>{first}"
                f'<td class="num">{fmt_setting(point.get("setting"))}</td>'
                f'<td class="num">{fmt_sig(cpu_ms)}</td>'
                f'<td class="num">{fmt_sig(point.get("error"), min_exp=-1)}</td>'
                f'<td class="num">{evals_text}</td>'
                f"<td>{'<span class=tag>default</span> ' if is_default else ''}{note}</td></tr>"
            )
    unit_text = f" ({esc(unit)})" if unit else ""
    return (
        f'<details class="bench-points"><summary>All {count} measured points</summary>'
        '<div class="table-wrap"><table><thead><tr><th scope="col">Method</th><th scope="col">Setting</th>'
        f'<th scope="col">CPU time (ms)</th><th scope="col">Error{unit_text}</th>'
        '<th scope="col">RHS evaluations</th><th scope="col">Note</th></tr></thead>'
        f"<tbody>{''.join(rows)}</tbody></table></div></details>"
    )


def _default_paragraph(scene: dict) -> str:
    default = scene.get("default")
    if not default:
        return ""
    unit = str(scene.get("error_unit") or "")
    labels = _method_labels(scene)
    setting_name = next(
        (m.get("setting_name") for m in scene.get("methods") or () if m.get("method") == default.get("method")), None
    )
    name = esc(labels.get(str(default.get("method")), str(default.get("method"))))
    setting = f" with {_setting_name(setting_name)} = {fmt_setting(default['setting'])}" if "setting" in default else ""
    cpu = default.get("cpu_s")
    # The benchmark's own automatic choice, for its span and frame rate: a live scene chooses for its own (below).
    t_end, rate = scene.get("t_end_s"), scene.get("frame_rate_hz")
    over = (
        f" over these {fmt_setting(t_end)} s at {fmt_setting(rate)} frames per second"
        if isinstance(t_end, (int, float)) and isinstance(rate, (int, float))
        else ""
    )
    parts = [f"<strong>Automatic choice{over}:</strong> {name}{setting}."]
    if isinstance(cpu, (int, float)) and not isinstance(cpu, bool) and math.isfinite(cpu):
        span = f"the whole {fmt_setting(t_end)} s run" if isinstance(t_end, (int, float)) else "the whole run"
        sentence = f"CPU time <strong>{fmt_sig(1e3 * cpu)} ms</strong> for {span}"
        if isinstance(t_end, (int, float)) and isinstance(rate, (int, float)) and t_end > 0 and rate > 0:
            per_frame_us = 1e6 * cpu / (t_end * rate)
            sentence += (
                f" ({fmt_sig(per_frame_us)} µs per frame, out of a frame budget of {fmt_sig(1e3 / rate)} ms"
                f" at {fmt_setting(rate)} frames per second)"
            )
        parts.append(sentence + ";")
    error = default.get("error")
    parts.append(f"error <strong>{_with_unit(fmt_sig(error, min_exp=-1), unit)}</strong>")
    target = scene.get("target_error")
    if isinstance(target, (int, float)) and isinstance(error, (int, float)) and math.isfinite(error):
        verdict = "within" if error <= target else "above"
        parts[-1] += f", {verdict} the target of {_with_unit(fmt_setting(target), unit)}"
    parts[-1] += "."
    return f'<p class="bench-default">{" ".join(parts)}</p>'


#: Where solver-lab.md states what a live scene runs: ``{{live-default:<scene id>}}``, filled in on every request by
#: :func:`live_default_text` (never typed by hand: the benchmark's run is not the live scene's).
LIVE_DEFAULT_MARK = re.compile(r"\{\{live-default:([a-z0-9-]{1,64})\}\}")


def live_default_text(scene_id: str) -> str:
    """What the live scene ``scene_id`` runs at its defaults, as its live panel says it, in HTML: the integrator and
    step ("Splitting, order 8 (exact free flow), 1 step/frame (h = 33.3 ms)"), its frame rate and its accuracy
    ("target 1e-06 rad over 60 s · estimated 4e-07 rad · 1 step/frame"). Asked of the scene's own choice
    (:meth:`IntegratedScene.live_default`, the step choice's pilots run or reused); a scene that is not integrated, or a
    choice that fails, says so in words, never an error page."""
    cls = SCENES.get(scene_id)
    if cls is None or not issubclass(cls, IntegratedScene):
        return "(no live integrated scene of that name)"
    try:
        integrator, choice, frame_dt_s = cls.live_default()
    except Exception as exc:  # noqa: BLE001 - a page states what it cannot compute and goes on
        return f"(its choice could not be computed here: {esc(str(exc))})"
    text = (
        f'<span class="live-default" data-scene="{esc(scene_id)}">{esc(integrator.describe(frame_dt_s))}</span> '
        f"at {fmt_setting(round(1.0 / frame_dt_s, 6))} frames per second"
    )
    return text + (f" ({esc(choice.text())})" if choice is not None else "")


def with_live_defaults(html_text: str) -> str:
    """``html_text`` with each ``{{live-default:<scene id>}}`` replaced by :func:`live_default_text`."""
    return LIVE_DEFAULT_MARK.sub(lambda match: live_default_text(match.group(1)), html_text)


def _live_scene_paragraph(scene: dict) -> str:
    """What the live scene the benchmark case stands for (its ``live_scene``) runs, beside the benchmark's choice."""
    live = scene.get("live_scene")
    if not isinstance(live, str) or not bench_reports.SCENE_ID_PATTERN.fullmatch(live):
        return ""
    return (
        f'<p class="bench-live"><strong>The live scene</strong> ({esc(live)}, at its defaults, choosing for a minute '
        f"of motion) runs {live_default_text(live)}.</p>"
    )


def _scene_section(scene: dict, settings) -> str:
    scene_id = str(scene.get("scene_id", ""))
    safe_id = scene_id if bench_reports.SCENE_ID_PATTERN.fullmatch(scene_id) else ""
    title = esc(str(scene.get("title") or scene_id))
    unit = str(scene.get("error_unit") or "")
    meta = []
    if scene.get("error_measure"):
        measure = f"<strong>Error:</strong> {esc(str(scene['error_measure']))}{f' ({esc(unit)})' if unit else ''}"
        if scene.get("reference"):
            reference = re.sub(r"^the\s+", "", str(scene["reference"]), flags=re.IGNORECASE)
            measure += f", against the {esc(reference)}"
        meta.append(measure + ".")
    t_end, rate = scene.get("t_end_s"), scene.get("frame_rate_hz")
    if isinstance(t_end, (int, float)) and isinstance(rate, (int, float)):
        meta.append(f"{fmt_setting(t_end)} s of motion at {fmt_setting(rate)} frames per second.")
    if isinstance(scene.get("target_error"), (int, float)):
        meta.append(f"Target error {_with_unit(fmt_setting(scene['target_error']), unit)}.")
    if safe_id and bench_reports.diagram_path(settings, safe_id):
        methods = ", ".join(str(m.get("label") or m.get("method")) for m in scene.get("methods") or ())
        alt = (
            f"Work-precision diagram for {scene.get('title') or scene_id}: CPU time against error, both on log scales, "
            f"for {methods}. The measured values are in the table below."
        )
        figure = (
            f'<figure class="bench-figure"><a href="/bench/{safe_id}.svg" title="Open the diagram on its own">'
            f'<img src="/bench/{safe_id}.svg" alt="{esc(alt)}" width="760" height="480"></a></figure>'
        )
    else:
        how = _esc_code(bench_reports.HOW_TO_MEASURE)
        figure = f'<p class="notice">The diagram for this scene is missing; {how}.</p>'
    ratios = "".join(f"<li>{_ratio_sentence(r, scene)}</li>" for r in scene.get("ratios") or ())
    anchor = f' id="bench-{safe_id}"' if safe_id else ""
    return (
        f'<section class="bench-scene"{anchor}>'
        f"<h2>{title}</h2>"
        f'<p class="bench-meta">{" ".join(meta)}</p>'
        f"{figure}{_default_paragraph(scene)}{_live_scene_paragraph(scene)}"
        + (f'<ul class="bench-ratios">{ratios}</ul>' if ratios else "")
        + _points_table(scene)
        + "</section>"
    )


def _run_summary(results: dict) -> str:
    machine = results.get("machine") or {}
    bits = []
    if machine.get("cpu"):
        cores = machine.get("cores")
        bits.append(esc(str(machine["cpu"])) + (f" ({esc(str(cores))} cores)" if cores else ""))
    names = {"python": "Python", "numpy": "NumPy", "scipy": "SciPy", "numba": "numba", "mujoco": "MuJoCo"}
    versions = [f"{name} {esc(str(machine[key]))}" for key, name in names.items() if machine.get(key)]
    if versions:
        bits.append(", ".join(versions))
    created = str(results.get("created") or "")
    try:
        when = datetime.fromisoformat(created.replace("Z", "+00:00")).strftime("%d %b %Y, %H:%M UTC")
    except ValueError:
        when = esc(created)
    scenes = results.get("scenes") or []
    toc = " · ".join(
        f'<a href="#bench-{esc(str(s.get("scene_id")))}">{esc(str(s.get("title") or s.get("scene_id")))}</a>'
        for s in scenes
        if bench_reports.SCENE_ID_PATTERN.fullmatch(str(s.get("scene_id", "")))
    )
    return (
        '<section class="bench-run"><h2>Measured results</h2>'
        f"<p>One run{f' on {when}' if when else ''}{': ' + '; '.join(bits) if bits else ''}. "
        "Every number below comes from that run on that machine. "
        '<a href="/api/bench/work-precision">Raw data (JSON)</a></p>'
        + (f'<nav class="bench-toc" aria-label="Scenes">Scenes: {toc}</nav>' if toc else "")
        + "</section>"
    )


def _guarded(render, item, *args) -> str:
    """Render one part of the results; a malformed entry becomes a notice instead of a failed page."""
    try:
        return render(item, *args)
    except (AttributeError, TypeError, KeyError, ValueError, IndexError):
        name = item.get("title") or item.get("scene_id") if isinstance(item, dict) else None
        what = f"The entry for {esc(str(name))}" if name else "An entry"
        return (
            f'<section class="bench-scene notice"><p>{what} in the benchmark results is malformed; '
            f"{_esc_code(bench_reports.HOW_TO_MEASURE)} again.</p></section>"
        )


def _capacity_row(step: dict) -> str:
    fps = step.get("frames_per_s") or {}
    health = step.get("health_ms") or {}
    cells = [
        fmt_sig(fps.get("p10")),
        fmt_sig(fps.get("median")),
        fmt_sig(fps.get("min")),
        fmt_sig(step.get("server_cpu_cores")),
        fmt_sig(step.get("server_rss_mb")),
        fmt_sig(step.get("load_tool_cpu_cores")),
        fmt_sig(health.get("p95")),
        fmt_sig(step.get("bytes_per_frame")),
    ]
    errors = step.get("errors")
    return (
        f'<tr><th scope="row">{esc(str(step.get("scene_id")))}</th><td '
        f'class="num">{esc(str(step.get("students")))}</td>'
        + "".join(f'<td class="num">{cell}</td>' for cell in cells)
        + f'<td class="num">{esc(str(errors))}</td></tr>'
    )


def _capacity_table(report: dict, settings) -> str:
    machine = report.get("machine") or {}
    server = report.get("server") or {}
    targets = report.get("targets") or {}
    created = esc(str(report.get("created") or "")[:16].replace("T", " "))
    lines = (
        f"Measured {created} UTC on {esc(str(machine.get('cores', '?')))} cores "
        f"({esc(str(machine.get('cpu') or 'unknown CPU'))}); scene workers: "
        f"{esc(bench_reports.describe_workers(server.get('workers')))}; each student a real viewer "
        f"websocket on its own scene. Targets: 100 students at ≥ {fmt_sig(targets.get('p10_frames_per_s'))} frames/s "
        f"for 9 students in 10 (10th percentile); 150 students with every one at ≥ "
        f"{fmt_sig(targets.get('min_frames_per_s_degraded'))} frames/s."
    )
    figure = ""
    if bench_reports.diagram_path(settings, "capacity"):
        figure = (
            '<figure class="bench-figure"><a href="/bench/capacity.svg" title="Open the plot on its own">'
            '<img src="/bench/capacity.svg" alt="Classroom capacity: frames per second each student receives '
            'against the number of students, per scene. The measured values are in the table below." '
            'width="760" height="460"></a></figure>'
        )
    rows = "".join(_capacity_row(step) for step in report["steps"] if isinstance(step, dict))
    return (
        f'<p class="bench-meta">{lines}</p>{figure}'
        '<div class="table-wrap"><table><thead><tr><th scope="col">Scene</th><th scope="col">Students</th>'
        '<th scope="col">Frames/s, 10th percentile</th><th scope="col">Median</th><th scope="col">Slowest</th>'
        '<th scope="col">Server CPU (cores)</th><th scope="col">Server memory (MB)</th>'
        '<th scope="col">Load tool CPU (cores)</th><th scope="col">Health p95 (ms)</th>'
        '<th scope="col">Bytes per frame</th><th scope="col">Errors</th></tr></thead>'
        f"<tbody>{rows}</tbody></table></div>"
    )


def _classroom_note(settings) -> str:
    """What a class following one room's scene measured (``classroom.json``, from ``dynlab load --room``): the frame
    rate of 100 followers and the server's CPU with 1 and 100 of them, and the plot; empty if there is no report."""
    try:
        report = bench_reports.read_capacity_report(Path(settings.bench_dir) / bench_reports.CLASSROOM_REPORT)
    except ValueError as exc:
        return f'<p class="notice">{esc(str(exc))}; <code>dynlab load --room</code> measures it again.</p>'
    if report is None:
        return ""
    try:
        cost = report["follow_cost"]
        size = bench_reports.FOLLOW_COST_CLASS
        step = next(s for s in report["steps"] if s["students"] == size)
        fps = step["frames_per_s"]
        text = (
            f"<p>Following the instructor, the class shares one simulation: {size} students following one "
            f"{esc(str(cost['scene_id']))} demo each received {fmt_sig(fps['p10'])} frames/s (10th percentile; slowest "
            f"{fmt_sig(fps['min'])}), and the server used {fmt_sig(cost[f'cpu_cores_{size}'])} cores, against "
            f"{fmt_sig(cost['cpu_cores_1'])} for one follower and {fmt_sig(cost.get('one_viewer_cpu_cores'))} for one "
            f"student on a scene of their own (<code>dynlab load --room</code>).</p>"
        )
    except (AttributeError, TypeError, KeyError, ValueError, StopIteration):
        return (
            '<p class="notice">The measurement of a class following one room is malformed; <code>dynlab load '
            "--room</code> measures it again.</p>"
        )
    figure = ""
    if bench_reports.diagram_path(settings, "classroom"):
        figure = (
            '<figure class="bench-figure"><a href="/bench/classroom.svg" title="Open the plot on its own">'
            '<img src="/bench/classroom.svg" alt="A class following one room: frames per second each student receives '
            'and the server CPU against the number of students, beside students each on a scene of their own." '
            'width="980" height="540"></a></figure>'
        )
    return text + figure


def _attack_row(attack: dict) -> str:
    answers = ", ".join(
        f"{esc(str(answer))} ×{esc(str(count))}" for answer, count in (attack.get("answers") or {}).items()
    )
    latency = (attack.get("latency_ms") or {}).get("max")
    slowest = f"{latency:,.0f}" if isinstance(latency, (int, float)) and not isinstance(latency, bool) else "—"
    return (
        f'<tr><td class="num">{esc(str(attack.get("item")))}</td><th scope="row">{esc(str(attack.get("name")))}</th>'
        f'<td class="num">{esc(str(attack.get("count")))}</td>'
        f'<td>{answers or "—"}</td><td class="num">{slowest}</td></tr>'
    )


def _attack_note(settings) -> str:
    """What a class on its own scenes received while one client attacked it (``attack.json``, from ``dynlab load
    --attack``): frames/s before and under attack against the target, the plot, and every attack with the answers it
    got; a notice saying how to measure it when there is no report."""
    how = "<code>dynlab load --attack</code> measures it"
    heading = "<h3>Under attack</h3>"
    try:
        report = bench_reports.read_attack_report(Path(settings.bench_dir) / bench_reports.ATTACK_REPORT)
    except ValueError as exc:
        return f'{heading}<p class="notice">{esc(str(exc))}; {how} again.</p>'
    if report is None:
        return (
            f'{heading}<p class="notice">No measurement under attack yet: {how} (students on their own scenes, first '
            "alone, then while one client attacks the class).</p>"
        )
    try:
        windows = report["windows"]
        before, during = windows["baseline"]["frames_per_s"], windows["attack"]["frames_per_s"]
        target = report["targets"]["p10_frames_per_s"]
        text = (
            f"<p>With {esc(str(report['students']))} students each on a "
            f"{esc(str(report['scene_id']))} session of their own, each from its own address, "
            "and one client attacking the class from one address (changing the room's "
            "shared scene without the instructor, turning students' sessions into another scene through the viewer "
            "socket, flooding session claims and look-ups, bursts of 40 requests at once, long seeks and steps on "
            "expensive sessions, 200 viewers, two slow derivations at once), the students received "
            f"{fmt_sig(during['p10'])} frames/s (10th percentile; median {fmt_sig(during['median'])}, slowest "
            f"{fmt_sig(during['min'])}), against {fmt_sig(before['p10'])} (median {fmt_sig(before['median'])}) just "
            f"before the attack. The target is {fmt_sig(target)} under attack: "
            f"{'met' if during['p10'] >= target else 'not met'}. Measured "
            f"{esc(str(report.get('created') or '')[:16].replace('T', ' '))} UTC (<code>dynlab load "
            "--attack</code>).</p>"
        )
        rows = "".join(_attack_row(attack) for attack in bench_reports.listed_attacks(report))
    except (AttributeError, TypeError, KeyError, ValueError):
        return f'{heading}<p class="notice">The measurement under attack is malformed; {how} again.</p>'
    figure = ""
    plot = bench_reports.diagram_path(settings, "attack")
    if plot:
        size = bench_reports.diagram_size(plot)
        size_attributes = f' width="{esc(size[0])}" height="{esc(size[1])}"' if size else ""
        figure = (
            '<figure class="bench-figure"><a href="/bench/attack.svg" title="Open the plot on its own">'
            '<img src="/bench/attack.svg" alt="A class under attack: frames per second each student receives before '
            'and while one client attacks, and what each attack got. The attacks are in the table below."'
            f"{size_attributes}></a></figure>"
        )
    # The exact requests are in attack.json and the plot; the table keeps to what fits beside the text.
    table = (
        '<div class="table-wrap"><table class="bench-attacks"><thead><tr><th scope="col">Item</th>'
        '<th scope="col">Attack</th><th scope="col">Tries</th>'
        '<th scope="col">Answers (count)</th><th scope="col">Slowest answer (ms)</th></tr></thead>'
        f"<tbody>{rows}</tbody></table></div>"
    )
    return heading + text + figure + table


def _capacity_section(settings) -> str:
    """The "Classroom capacity" section: the plot and table of ``capacity.json`` (written by ``dynlab load``), what a
    class following one room measured (``classroom.json``, from ``dynlab load --room``), and what a class received
    while one client attacked it (``attack.json``, from ``dynlab load --attack``)."""
    how = "<code>dynlab load</code> measures it (real viewer websockets, 10 to 150 students) and writes it"
    try:
        report = bench_reports.read_capacity_report(Path(settings.bench_dir) / bench_reports.CAPACITY_REPORT)
    except ValueError as exc:
        content = f'<p class="notice">{esc(str(exc))}; {how} again.</p>'
    else:
        if report is None:
            content = f'<p class="notice">No classroom measurement yet: {how}.</p>'
        else:
            try:
                content = _capacity_table(report, settings)
            except (AttributeError, TypeError, KeyError, ValueError):
                content = f'<p class="notice">The classroom measurement is malformed; {how} again.</p>'
    return (
        '<section class="bench-scene bench-capacity" id="bench-capacity"><h2>Classroom capacity</h2>'
        "<p>How many students the server streams their own live scene to, at how many frames per second.</p>"
        f"{content}{_classroom_note(settings)}{_attack_note(settings)}</section>"
    )


def _scaling_row(ours: dict, sympy_row: dict | None) -> str:
    def cell(value: object, unit: str = "") -> str:
        return f"<td>{_with_unit(fmt_sig(value), unit)}</td>"

    def count(value: object) -> str:
        return f"<td>{_operations(value)}</td>"

    compile_s = (ours.get("derive_generate_load_s") or 0) + (ours.get("numba_s") or 0)
    baseline = sympy_row or {}
    return (
        f"<tr><td>{esc(str(ours.get('links')))}</td><td>{'planar' if ours.get('planar') else 'spatial'}</td>"
        f"{cell(ours.get('derive_generate_load_s'), 's')}{cell(ours.get('numba_s'), 's')}{cell(compile_s, 's')}"
        f"{cell(ours.get('rhs_us'), 'µs')}{cell(ours.get('frame_us'), 'µs')}{count(ours.get('operations_written_out'))}"
        f"{count(ours.get('operations_in_code'))}{cell(baseline.get('derive_lambdify_s'), 's')}"
        f"{cell(baseline.get('rhs_us'), 'µs')}</tr>"
    )


def _operations(value: object) -> str:
    """A count of operations, exactly, with thousands separated ("—" if it is not a count)."""
    return f"{value:,}" if isinstance(value, int) and not isinstance(value, bool) else "—"


def _scaling_section(settings) -> str:
    """The "Derivation engine at scale" section: ``scaling.json`` (``dynlab derivations --scaling``) as a plot and a
    table, the N-link chain against sympy's KanesMethod + lambdify, and the bicycle cold and cached."""
    how = "<code>dynlab derivations --scaling</code> measures it (each size cold, in a fresh process) and writes it"
    try:
        report = bench_reports.read_scaling_report(Path(settings.bench_dir) / bench_reports.SCALING_REPORT)
    except ValueError as exc:
        content = f'<p class="notice">{esc(str(exc))}; {how} again.</p>'
    else:
        if report is None:
            content = f'<p class="notice">No scaling measurement yet: {how}.</p>'
        else:
            try:
                content = _scaling_content(report, settings)
            except (AttributeError, TypeError, KeyError, ValueError):
                content = f'<p class="notice">The scaling measurement is malformed; {how} again.</p>'
    return (
        '<section class="bench-scene bench-scaling" id="bench-scaling"><h2>The derivation engine at scale</h2>'
        "<p>How long a system built of parts takes to derive, generate and compile, how big its equations are before "
        "and after common subexpressions are shared, and one right-hand side, against sympy's "
        "<code>KanesMethod</code> with <code>lambdify</code> (what a user writes) on the same machine.</p>"
        f"{content}</section>"
    )


def _scaling_content(report: dict, settings) -> str:
    rows = [r for r in report["rows"] if isinstance(r, dict)]
    baseline = {(r.get("links"), r.get("planar")): r for r in rows if r.get("engine") == "sympy"}
    ours = [r for r in rows if r.get("engine") == "ours"]
    figure = ""
    if bench_reports.diagram_path(settings, "scaling"):
        figure = (
            '<figure class="bench-figure"><a href="/bench/scaling.svg" title="Open the plot on its own">'
            '<img src="/bench/scaling.svg" alt="Derive, generate and compile time and operation counts of the N-link '
            "pendulum against its number of links, ours and sympy's. The measured values are in the table below.\" "
            'width="760" height="460"></a></figure>'
        )
    body = "".join(_scaling_row(r, baseline.get((r.get("links"), r.get("planar")))) for r in ours)
    targets = report.get("targets") or {}
    chain = targets.get("chain_20_derive_and_compile_cold_s") or {}
    frame = targets.get("chain_20_live_frame_us") or {}
    bicycle = report.get("bicycle") or {}
    cold, cached = bicycle.get("cold") or {}, bicycle.get("cached") or {}
    notes = (
        "<p>The 20-link chain cold: derived, generated and loaded in "
        f"{_with_unit(fmt_sig(chain.get('derive_generate_load_s')), 's')}; with numba's compiled kernels, "
        f"{_with_unit(fmt_sig(chain.get('with_numba_s')), 's')} (target "
        f"{_with_unit(fmt_sig(chain.get('target')), 's')}); one live frame of it at the scenes' 10<sup>−6</sup>, "
        f"{_with_unit(fmt_sig(frame.get('measured')), 'µs')} (target {_with_unit(fmt_sig(frame.get('target')), 'µs')})."
        " The Whipple bicycle: "
        f"{_with_unit(fmt_sig(cold.get('total_s')), 's')} cold with its kernels (target 15 s), "
        f"{_with_unit(fmt_sig(cached.get('total_s')), 's')} from the disk cache (target 0.05 s); "
        f"{_operations(cold.get('operations_written_out'))} operations written out, "
        f"{_operations(cold.get('operations_in_code'))} in its generated code.</p>"
    )
    return (
        f'<p class="bench-meta">Measured by <code>{esc(str(report.get("generated_by", "")))}</code> on '
        f"{esc(str(report.get('machine', 'this machine')))}.</p>{figure}{notes}"
        '<div class="table-wrap"><table><thead><tr><th scope="col">Links</th><th scope="col">Motion</th>'
        '<th scope="col">Derive + generate + load</th><th scope="col">numba kernels</th><th scope="col">Cold total</th>'
        '<th scope="col">One rhs, plain Python</th><th scope="col">One live frame (1e-6, compiled)</th>'
        '<th scope="col">Operations written out</th>'
        '<th scope="col">Operations in code</th><th scope="col">sympy KanesMethod + lambdify</th>'
        '<th scope="col">sympy rhs</th></tr></thead>'
        f"<tbody>{body}</tbody></table></div>"
    )


@router.get("/solver-lab", response_class=HTMLResponse)
def solver_lab_page(settings: SettingsDep) -> HTMLResponse:
    meta, prose = _solver_lab_text(Path(settings.lessons_dir))
    try:
        results = bench_reports.load_results(settings)
    except bench_reports.BenchResultsError as exc:
        results_html = (
            '<section class="bench-run notice" role="status"><h2>Measured results</h2>'
            f"<p>{_esc_code(str(exc))}; {_esc_code(bench_reports.HOW_TO_MEASURE)} again.</p></section>"
        )
    else:
        if results is None:
            results_html = (
                '<section class="bench-run notice" role="status"><h2>No measurements yet</h2>'
                f"<p>{_esc_code(bench_reports.missing_message(settings))}</p>"
                "<p>Then reload this page: <code>uv run --group bench dynlab bench</code> writes "
                "<code>work_precision.json</code> and one diagram per scene into the benchmark folder.</p></section>"
            )
        else:
            results_html = _guarded(_run_summary, results) + "".join(
                _guarded(_scene_section, scene, settings) for scene in results["scenes"]
            )
    body = _template("solver_lab.html").substitute(
        title=esc(str(meta.get("title", "Solver lab"))),
        summary=esc(str(meta.get("summary", ""))),
        prose=with_live_defaults(prose),
        results=results_html,
        capacity=_capacity_section(settings),
        scaling=_scaling_section(settings),
    )
    return _page("Solver lab — Dynamics Lab", body, scripts=("/static/js/solver_lab.js",))


@router.get("/viewer/{scene_id}/{session_id}")
def viewer_redirect(scene_id: str, session_id: str) -> RedirectResponse:
    return RedirectResponse(f"/viewer/{scene_id}/{session_id}/")


@router.get("/viewer/{scene_id}/{session_id}/")
def viewer_page(scene_id: str, session_id: str, host: SceneHostDep) -> Response:
    """viser's single-file client; it connects back to this path's websocket relay."""
    if scene_id not in host.scenes or not SESSION_ID_PATTERN.match(session_id):
        raise HTTPException(status_code=404, detail="unknown scene or malformed session id")
    return Response(viewer_client_html(), media_type="text/html; charset=utf-8")
