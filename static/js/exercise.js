// An exercise page: its numbers (the learner's own variant), its parts checked one by one, hints one at a time, the
// named mistake's feedback, the worked solution once solved or given up, and "See it" (the scene at these numbers).
// The learner is this browser's token (localStorage), made when it first opens an exercise; nothing else is kept here.
// Opened from a class room (?room=, an exercise the instructor assigned): the room's numbers, and every answer goes
// with the room's student token too, so the instructor's results count it.
import "./common.js";
import { api, ApiError, randomId } from "./api.js";
import { element } from "./dom.js";
import { katexInto, renderMath } from "./katex.js";
import { LEARNER_KEY, learner } from "./practice_list.js";
import { studentToken } from "./room_practice.js";

const root = document.getElementById("exercise");
const exerciseId = root.dataset.exercise;
const partsList = document.getElementById("parts");
const errorBox = document.getElementById("exercise-error");
const giveUp = document.getElementById("give-up");
const seeIt = document.getElementById("see-it");
let exercise = null;
const answered = new Set();
// The class room this exercise was opened from, while the room assigns it and this browser is one of its students.
const askedRoom = new URLSearchParams(location.search).get("room");
let roomId = askedRoom && /^[0-9a-f]{16}$/.test(askedRoom) && studentToken(askedRoom) ? askedRoom : null;
const inRoom = (body) => (roomId ? { ...body, room_id: roomId } : body);
const roomQuery = () => (roomId ? `room=${roomId}` : "");

function learnerHeaders() {
  const me = learner();
  return { ...(me ? { "X-Learner-Token": me.token } : {}), ...(roomId ? { "X-Student-Token": studentToken(roomId) } : {}) };
}
async function ensureLearner() {
  if (learner()) return learner();
  try {
    const made = await api("POST", "/api/learners");
    localStorage.setItem(LEARNER_KEY, JSON.stringify(made));
    showResume();
    return made;
  } catch (error) {
    return null; // a server that keeps nothing: answers are still checked
  }
}
// A request as this learner; a token the server no longer knows is dropped and the request made without it.
async function asLearner(method, url, body) {
  try {
    return await api(method, url, body, learnerHeaders());
  } catch (error) {
    if (error instanceof ApiError && error.status === 401 && learner()) {
      localStorage.removeItem(LEARNER_KEY);
      return api(method, url, body);
    }
    throw error;
  }
}

// A unit as typed (kg*m^2/s) as it is read (kg·m²/s).
const shownUnit = (unit) => unit.replaceAll("*", "·").replaceAll("^2", "²").replaceAll("^3", "³");

function html(target, markup) {
  target.innerHTML = markup; // server-rendered Markdown of our own exercise files
  renderMath(target);
}

function showResume() {
  const me = learner();
  const text = document.getElementById("resume-text");
  if (!me) return;
  text.textContent = "";
  text.append(
    "Your answers are kept on this server for this browser. ",
    ...(me.resume_code ? ["To carry them to another device, type this code on the course page there: ", element("code", { text: me.resume_code })] : []),
  );
}

function answerInputs(part) {
  const id = (name) => `p-${part.id}-${name}`;
  const label = (name, text, input) => element("label", { for: id(name) }, text, " ", input);
  if (part.answer_kind === "number") {
    const value = element("input", { id: id("value"), type: "text", inputmode: "decimal", autocomplete: "off", required: true, size: "12" });
    const unit = element("input", { id: id("unit"), type: "text", value: part.unit, size: "10", autocomplete: "off" });
    return { nodes: [label("value", "Answer", value), label("unit", "unit", unit)], read: () => ({ value: Number(value.value.trim().replace(/\s/g, "")), unit: unit.value.trim() }), first: value };
  }
  if (part.answer_kind === "vector") {
    const boxes = ["x", "y", "z"].map((c) => element("input", { id: id(c), type: "text", inputmode: "decimal", size: "8", autocomplete: "off" }));
    const unit = element("input", { id: id("unit"), type: "text", value: part.unit, size: "10" });
    return {
      nodes: [...boxes.map((b, i) => label("xyz"[i], `${"xyz"[i]}:`, b)), label("unit", "unit", unit), element("span", { class: "muted" }, ` components in ${part.frame}`)],
      read: () => ({ vector: boxes.map((b) => Number(b.value.trim())), unit: unit.value.trim(), frame: part.frame }), first: boxes[0],
    };
  }
  if (part.answer_kind === "expression") {
    const box = element("input", { id: id("expr"), type: "text", size: "40", autocomplete: "off", spellcheck: "false", "aria-describedby": id("symbols") });
    const symbols = element("p", { id: id("symbols"), class: "symbols muted" },
      "Symbols you may use: ", ...part.symbols.flatMap((s, i) => [i ? ", " : "", element("code", { text: s.name }), ` (${s.meaning})`]),
      ". Write powers with ^, e.g. sin(theta)^2.");
    return { nodes: [label("expr", "Expression", box), symbols], read: () => ({ expression: box.value }), first: box };
  }
  const name = id("choice");
  const radios = part.choices.map((c) => element("label", { class: "choice" }, element("input", { type: "radio", name, value: c.id }), " ", c.text));
  return { nodes: [element("fieldset", {}, element("legend", { class: "sr-only" }, "Choices"), ...radios)], read: () => ({ choice: (document.querySelector(`input[name="${name}"]:checked`) || {}).value || "" }), first: radios[0]?.querySelector("input") };
}

function renderPart(part, index) {
  const prompt = element("div", { class: "prompt" });
  html(prompt, part.prompt_html);
  const inputs = answerInputs(part);
  const feedback = element("div", { class: "feedback", "aria-live": "polite", id: `p-${part.id}-feedback` });
  const check = element("button", { type: "submit" }, "Check");
  const hintButton = element("button", { type: "button", class: "hint-button" }, `Hint (${part.hints.length})`);
  const hints = element("ol", { class: "hints" });
  hintButton.hidden = part.hints.length === 0;
  let shown = 0;
  hintButton.addEventListener("click", () => {
    const item = element("li");
    html(item, part.hints_html[shown]);
    hints.append(item);
    shown += 1;
    hintButton.textContent = shown < part.hints.length ? `Another hint (${part.hints.length - shown} left)` : "No more hints";
    hintButton.disabled = shown >= part.hints.length;
  });
  const form = element("form", { class: "answer", "aria-label": `Answer to part ${index + 1}` }, ...inputs.nodes, check, hintButton);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    check.disabled = true;
    feedback.className = "feedback";
    try {
      await ensureLearner();
      const verdict = await asLearner("POST", `/api/exercises/${exerciseId}/attempts`, inRoom({ variant: exercise.variant, part: part.id, answer: inputs.read() }));
      feedback.classList.add(verdict.correct ? "correct" : "wrong");
      html(feedback, (verdict.correct ? "<p><strong>Correct.</strong></p>" : verdict.mistake ? "<p><strong>Not quite — a common mistake:</strong></p>" : "") + (verdict.correct ? "" : verdict.feedback_html));
      if (verdict.correct) partDone(part.id);
    } catch (error) {
      if (roomId && error instanceof ApiError && [403, 404].includes(error.status)) {
        leaveRoom(error.message); // removed from the room, or it closed: the exercise stays theirs to practise
        return;
      }
      if (error instanceof ApiError && error.status === 409) { // another tab or device changed whose numbers these are
        location.reload();
        return;
      }
      feedback.classList.add("unreadable");
      feedback.textContent = error.message;
    } finally {
      check.disabled = false;
      feedback.dataset.checked = String(Number(feedback.dataset.checked || 0) + 1); // answers checked so far
    }
  });
  return element("li", { class: "part", id: `part-${part.id}` }, prompt, form, hints, feedback);
}

// On a laptop, once a part is answered, the scene at this exercise's numbers beside it (a page session of its own, kept
// for this tab); on a phone the "See it" link opens it in its lesson instead.
const roomForScene = window.matchMedia("(min-width: 1100px)");
let sceneShown = false;
async function showSceneBeside() {
  if (sceneShown || !exercise.scene || !exercise.scene.url || !roomForScene.matches) return;
  sceneShown = true;
  const { scene_id: sceneId, params } = exercise.scene;
  const kept = `dynlab.exercise-scene.${exerciseId}.${exercise.variant}`;
  let session = null;
  try { session = JSON.parse(sessionStorage.getItem(kept)); } catch { session = null; }
  session ||= { id: randomId(), key: randomId() };
  try {
    await api("PUT", `/api/scenes/${encodeURIComponent(sceneId)}/sessions/${session.id}`, { params }, { "X-Session-Key": session.key });
  } catch (error) {
    sceneShown = false; // busy, or this device holds its share of scenes: "See it" still opens it
    return;
  }
  sessionStorage.setItem(kept, JSON.stringify(session));
  document.getElementById("exercise-viewer").src = `/viewer/${encodeURIComponent(sceneId)}/${session.id}/?hideViserLogo`;
  document.getElementById("exercise-scene-lesson").href = exercise.scene.url;
  document.getElementById("exercise-scene").hidden = false;
}

function partDone(partId) {
  answered.add(partId);
  if (exercise.scene && exercise.scene.url) seeIt.hidden = false;
  showSceneBeside();
  if (answered.size === exercise.parts.length) showSolution("GET");
}

async function showSolution(method) {
  try {
    const solution = method === "GET"
      ? await asLearner("GET", `/api/exercises/${exerciseId}/solution?variant=${exercise.variant}${roomId ? `&${roomQuery()}` : ""}`)
      : await asLearner("POST", `/api/exercises/${exerciseId}/give-up`, inRoom({ variant: exercise.variant }));
    const steps = document.getElementById("worked-steps");
    steps.textContent = "";
    for (const part of solution.parts) {
      const spec = exercise.parts.find((p) => p.id === part.id);
      const answer = part.answer;
      const text = "value" in answer ? `${Number(answer.value.toPrecision(4))} ${shownUnit(answer.unit)}`
        : "vector" in answer ? `(${answer.vector.map((c) => Number(c.toPrecision(4))).join(", ")}) ${shownUnit(answer.unit)} in ${answer.frame}`
        : "expression" in answer ? answer.expression : spec.choices.find((c) => c.id === answer.choice).text;
      const working = element("div", { class: "working" });
      katexInto(working, part.working, true);
      steps.append(element("li", {}, working, element("p", {}, "Answer: ", element("strong", { text }))));
    }
    document.getElementById("worked").hidden = false;
    giveUp.hidden = true;
    if (exercise.scene && exercise.scene.url) seeIt.hidden = false;
    showSceneBeside();
  } catch (error) {
    if (method === "POST") { errorBox.textContent = error.message; errorBox.hidden = false; }
  }
}

// What this learner already did on this variant (after a reload, on another day, after a server restart).
async function showKept() {
  if (!learner()) return;
  let progress;
  try { progress = await asLearner("GET", "/api/progress"); } catch { return; }
  const mine = progress.parts.filter((p) => p.exercise_id === exerciseId && p.variant === exercise.variant);
  for (const kept of mine) {
    const feedback = document.getElementById(`p-${kept.part}-feedback`);
    if (!feedback) continue;
    if (kept.solved) {
      feedback.className = "feedback correct";
      feedback.textContent = `Solved earlier (${kept.attempts} attempt${kept.attempts === 1 ? "" : "s"}).`;
      answered.add(kept.part);
    } else if (kept.gave_up) {
      feedback.className = "feedback";
      feedback.textContent = "Given up earlier: the worked solution is below.";
      answered.add(kept.part);
    }
  }
  if (answered.size && exercise.scene && exercise.scene.url) seeIt.hidden = false;
  if (answered.size) showSceneBeside();
  if (answered.size === exercise.parts.length) showSolution("GET");
}

// This page no longer works for the room (the student was removed, or the room closed): reopen it without the room,
// the student's own practice from now on.
function leaveRoom(why) {
  sessionStorage.setItem("dynlab.exercise.left-room", why);
  const own = new URL(location.href);
  own.searchParams.delete("room");
  location.replace(own.pathname + own.search);
}

function showRoomNote(...content) {
  const note = document.getElementById("room-note");
  note.replaceChildren(...content);
  note.hidden = false;
}

async function load() {
  await ensureLearner(); // first, so that the numbers shown are this learner's own from the start
  try {
    try {
      exercise = await asLearner("GET", `/api/exercises/${exerciseId}${roomId ? `?${roomQuery()}` : ""}`);
    } catch (error) {
      if (!(roomId && error instanceof ApiError && [403, 404, 409].includes(error.status))) throw error;
      roomId = null; // taken back, the room closed, or this browser left it: the exercise is still theirs to practise
      showRoomNote(`Not counted for your class: ${error.message}.`);
      exercise = await asLearner("GET", `/api/exercises/${exerciseId}`);
    }
  } catch (error) {
    html(document.getElementById("statement"), "");
    errorBox.textContent = `This exercise could not be loaded: ${error.message}`;
    errorBox.hidden = false;
    return;
  }
  const left = sessionStorage.getItem("dynlab.exercise.left-room");
  if (left) {
    sessionStorage.removeItem("dynlab.exercise.left-room");
    showRoomNote(`No longer counted for your class (${left}); your answers are your own practice now.`);
  }
  if (exercise.room) {
    const back = exercise.room.lesson_id ? element("a", { href: `/lessons/${encodeURIComponent(exercise.room.lesson_id)}?room=${roomId}` }, "Back to the class") : "";
    showRoomNote(`Assigned in class room ${exercise.room.code}${exercise.room.class_variant ? ", with the same numbers for the whole class" : ""}: your instructor sees how the class does. `, back);
  }
  html(document.getElementById("statement"), exercise.statement_html);
  exercise.parts.forEach((part, i) => partsList.append(renderPart(part, i)));
  if (exercise.scene && exercise.scene.url) seeIt.href = exercise.scene.url;
  giveUp.hidden = false;
  giveUp.addEventListener("click", () => showSolution("POST"));
  showResume();
  await showKept();
  document.body.dataset.exerciseReady = "true";
}

load();
