// Exercises in a class room (issue 27, point 7). The instructor's panel assigns a section's exercises or chosen ones,
// optionally with one set of numbers for the whole class, and shows live, per exercise and per part, how many tried,
// solved and gave up, and the named mistakes most made (anonymous unless names are on), with the CSV to download.
// A student's room bar lists what is assigned, each opening the exercise page in the room (?room=).
import { api } from "./api.js";
import { element as el } from "./dom.js";

// The room's token this browser was given on joining (join.js keeps it), or null.
export function studentToken(roomId) {
  const raw = localStorage.getItem(`dynlab.room.${roomId}`);
  if (!raw) return null;
  try {
    const saved = JSON.parse(raw);
    return typeof saved === "string" ? saved : saved && saved.student_token;
  } catch (e) {
    return raw;
  }
}

let catalogue = null;
// Every exercise (id, title, section, parts), once per page.
function exercises() {
  catalogue ||= api("GET", "/api/exercises").catch(() => []);
  return catalogue;
}

// ---- a student: what the instructor assigned -----------------------------------------------------
export function studentAssignment(roomId) {
  const list = el("ul", { class: "room-assigned-list" });
  const note = el("p", { class: "muted" });
  const element = el("section", { class: "room-assigned", "aria-label": "Exercises from your instructor", hidden: true },
    el("h2", { text: "Exercises from your instructor" }), note, list);
  let shown = null;
  return {
    element,
    async render(assignment) {
      const key = assignment ? JSON.stringify(assignment) : null;
      if (key === shown) return;
      shown = key;
      element.hidden = !assignment;
      if (!assignment) return;
      note.textContent = assignment.class_variant
        ? "The whole class works on the same numbers. Your instructor sees how the class does."
        : "Each of you works on your own numbers. Your instructor sees how the class does.";
      const byId = Object.fromEntries((await exercises()).map((e) => [e.id, e]));
      list.replaceChildren(...assignment.exercise_ids.map((id) => el("li", {},
        el("a", { href: `/exercises/${encodeURIComponent(id)}?room=${roomId}`, "data-exercise": id },
          byId[id] ? `${byId[id].section} ${byId[id].title}` : id))));
    },
  };
}

// ---- the instructor: assign, then watch the results -----------------------------------------------
export function instructorAssignment(roomId, showError) {
  const REFRESH_MS = 3000;
  const section = el("select", { id: "room-assign-section" }, new Option("Loading exercises…", ""));
  const choices = el("fieldset", { class: "room-assign-choices" }, el("legend", { text: "Assign" }));
  const classVariant = el("input", { type: "checkbox", id: "room-assign-class-variant" });
  const names = el("input", { type: "checkbox", id: "room-assign-names" });
  const assign = el("button", { type: "button", "data-room": "assign", text: "Assign" });
  const takeBack = el("button", { type: "button", "data-room": "unassign", text: "Take back", hidden: true });
  const current = el("p", { class: "room-assigned-now muted", "aria-live": "polite", text: "Nothing assigned yet." });
  const csv = el("a", { class: "room-csv", href: `/api/rooms/${roomId}/assignment/results.csv`, download: "", text: "Download CSV", hidden: true });
  const results = el("div", { class: "room-exercise-results", "aria-live": "polite" });
  const element = el("details", { class: "room-practice" },
    el("summary", { text: "Exercises" }),
    el("p", {}, el("label", { for: section.id, text: "Section " }), section),
    choices,
    el("p", {}, el("label", { for: classVariant.id }, classVariant, " One set of numbers for the whole class")),
    el("p", { class: "muted room-assign-caveat", text: "With one set, a student who gives up sees worked answers the others could copy; the table counts them as given up, and keeps the class's numbers while you change what is assigned." }),
    el("p", {}, el("label", { for: names.id }, names, " Show names in the results")),
    el("div", { class: "room-buttons" }, assign, takeBack, csv),
    current, results);
  let assignment = null, timer = null, bySection = {}, titles = {};

  exercises().then((all) => {
    bySection = {};
    for (const e of all) { (bySection[e.section] ||= []).push(e); titles[e.id] = e; }
    if (assignment) describe(assignment);
    const sections = Object.keys(bySection);
    section.replaceChildren(...sections.map((s) => new Option(`${s} — ${bySection[s].length} exercise${bySection[s].length === 1 ? "" : "s"}`, s)));
    listChoices();
  });
  function describe(a) {
    current.textContent = `Assigned: ${a.exercise_ids.map((id) => (titles[id] ? titles[id].title : id)).join(", ")}` +
      (a.class_variant ? " — one set of numbers for the class." : " — each student's own numbers.");
  }
  function listChoices() {
    const mine = bySection[section.value] || [];
    choices.replaceChildren(el("legend", { text: "Assign" }), ...mine.map((e) => el("label", { class: "choice" },
      el("input", { type: "checkbox", value: e.id, checked: true }), ` ${e.title}`)));
  }
  section.addEventListener("change", listChoices);

  async function send(body) {
    assign.disabled = takeBack.disabled = true;
    try {
      if (body) await api("PUT", `/api/rooms/${roomId}/assignment`, body);
      else await api("DELETE", `/api/rooms/${roomId}/assignment`);
      refresh();
    } catch (err) {
      showError(`Not assigned: ${err.message}`);
    } finally {
      assign.disabled = takeBack.disabled = false;
    }
  }
  assign.addEventListener("click", () => {
    const ids = [...choices.querySelectorAll("input:checked")].map((box) => box.value);
    if (!ids.length) { showError("Tick at least one exercise to assign."); return; }
    send({ exercise_ids: ids, class_variant: classVariant.checked, show_names: names.checked });
  });
  takeBack.addEventListener("click", () => send(null));
  names.addEventListener("change", () => {
    if (assignment) send({ exercise_ids: assignment.exercise_ids, class_variant: assignment.class_variant, show_names: names.checked });
  });

  // One table per exercise: a row per part (tried, solved, gave up, its named mistakes with how many made each);
  // with names on, a row under it with each student's work.
  // A name beside the id it belongs to (two students may give the same name); "student 3" is its own id.
  const who = (n) => (n.student === `student ${n.student_id.slice(1)}` ? n.student : `${n.student} (${n.student_id})`);
  const work = (n) => `${who(n)}: ${n.solved ? "solved" : n.gave_up ? "gave up" : `${n.attempts} tried`}`;
  function table(exercise, showNames) {
    const rows = exercise.parts.flatMap((p) => [el("tr", { "data-part": p.part },
      el("th", { scope: "row", text: p.part }),
      el("td", { class: "num", text: String(p.tried) }),
      el("td", { class: "num", text: String(p.solved) }),
      el("td", { class: "num", text: String(p.gave_up) }),
      el("td", {}, ...(p.mistakes.length
        ? p.mistakes.map((m) => el("span", { class: "room-mistake", title: m.text, "data-mistake": m.mistake }, `${m.mistake} × ${m.students}`))
        : [el("span", { class: "muted", text: "—" })]))),
      ...(showNames ? [el("tr", { class: "room-part-names", "data-names-of": p.part },
        el("td", { colspan: 5, text: (p.names || []).map(work).join(" · ") || "nobody yet" }))] : [])]);
    return el("div", { class: "room-table-scroll" }, el("table", { class: "room-exercise-table", "data-exercise": exercise.exercise_id },
      el("caption", {}, el("a", { href: `/exercises/${encodeURIComponent(exercise.exercise_id)}`, target: "_blank", rel: "noopener" }, `${exercise.section} ${exercise.title}`)),
      el("thead", {}, el("tr", {}, ...["Part", "Tried", "Solved", "Gave up", "Common mistakes"].map((h) => el("th", { scope: "col", text: h })))),
      el("tbody", {}, ...rows)));
  }

  async function refresh() {
    clearTimeout(timer);
    if (!assignment) { results.replaceChildren(); return; }
    try {
      const r = await api("GET", `/api/rooms/${roomId}/assignment/results`);
      names.checked = r.show_names;
      results.replaceChildren(el("p", { class: "muted", text: `${r.students} student${r.students === 1 ? "" : "s"} in the room${r.show_names ? "" : " · anonymous"}` }),
        ...r.exercises.map((e) => table(e, r.show_names)));
    } catch (err) {
      results.replaceChildren(el("p", { class: "error", text: `Results unavailable: ${err.message}` }));
    }
    if (assignment && !document.hidden) timer = setTimeout(refresh, REFRESH_MS);
  }
  document.addEventListener("visibilitychange", () => { if (!document.hidden && assignment) refresh(); });

  return {
    element,
    state(state) {
      const next = state.assignment;
      const changed = JSON.stringify(next) !== JSON.stringify(assignment);
      assignment = next;
      takeBack.hidden = csv.hidden = !assignment;
      if (!changed) return;
      if (assignment) {
        describe(assignment);
        classVariant.checked = assignment.class_variant;
      } else {
        current.textContent = "Nothing assigned yet.";
      }
      refresh();
    },
  };
}
