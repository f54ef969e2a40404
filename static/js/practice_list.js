// Practice beside the lessons: a lesson page lists its section's exercises (with this browser's progress on each),
// and the course page shows, per section, how many exercises this learner has solved and takes a resume code from
// another device. The learner is the token exercise.js keeps (localStorage "dynlab.learner").
import { api } from "./api.js";
import { element } from "./dom.js";

// This browser's learner (the token exercise.js keeps), read by every practice script from here.
export const LEARNER_KEY = "dynlab.learner";

export function learner() {
  try { return JSON.parse(localStorage.getItem(LEARNER_KEY)); } catch { return null; }
}

async function progress() {
  const me = learner();
  if (!me) return null;
  try {
    return await api("GET", "/api/progress", undefined, { "X-Learner-Token": me.token });
  } catch (error) {
    if (error.status === 401) localStorage.removeItem(LEARNER_KEY);
    return null;
  }
}

function solvedParts(kept, exerciseId) {
  return kept ? kept.parts.filter((p) => p.exercise_id === exerciseId && p.solved).length : 0;
}

// A lesson page: its section's exercises, after the lesson text.
export async function listSectionExercises(section, before) {
  const exercises = await api("GET", `/api/exercises?section=${encodeURIComponent(section)}`).catch(() => []);
  if (!exercises.length) return;
  const kept = await progress();
  const items = exercises.map((e) => {
    const solved = solvedParts(kept, e.id);
    const status = solved ? ` — ${solved} of ${e.parts} parts solved` : ` — ${e.parts} parts`;
    return element("li", {}, element("a", { href: `/exercises/${e.id}` }, e.title), status);
  });
  const block = element("section", { id: "practice", class: "practice", "aria-labelledby": "practice-title" },
    element("h2", { id: "practice-title" }, "Practice"),
    element("p", {}, "Exercises on this section, checked step by step: your own numbers, feedback that names a common mistake, hints on request, and (where a scene shows the system) that scene at your numbers."),
    element("ul", {}, ...items));
  before.before(block);
}

// The course page: per section, this learner's solved exercises; and a box for a resume code.
export async function showCourseProgress() {
  const all = await api("GET", "/api/exercises").catch(() => []);
  const kept = await progress();
  const bySection = {};
  for (const e of all) (bySection[e.section] ||= []).push(e);
  for (const item of document.querySelectorAll("li[data-section]")) {
    const mine = bySection[item.dataset.section];
    if (!mine) continue;
    const solved = mine.filter((e) => kept && kept.sections[e.section] && solvedParts(kept, e.id) === e.parts).length;
    item.append(" · ", element("a", { href: `/exercises/${mine[0].id}`, class: "practice-link" },
      kept ? `practice: ${solved} of ${mine.length} exercises solved` : `practice: ${mine.length} exercise${mine.length === 1 ? "" : "s"}`));
  }
  const box = document.getElementById("resume-box");
  if (!box) return;
  const input = box.querySelector("input");
  const said = box.querySelector(".resume-said");
  box.hidden = false;
  if (kept) said.textContent = `This browser's practice: ${kept.parts.filter((p) => p.solved).length} parts solved.`;
  box.addEventListener("submit", async (event) => {
    event.preventDefault();
    try {
      const made = await api("POST", "/api/learners/resume", { code: input.value.trim() });
      localStorage.setItem(LEARNER_KEY, JSON.stringify(made));
      said.textContent = "Done: this browser now carries that progress.";
      location.reload();
    } catch (error) {
      said.textContent = error.message;
    }
  });
}
