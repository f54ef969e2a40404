// Lesson page: controls generated from the scene's parameter schema, the live
// viewer (one scene per page session) and the worked-solution panel. `lesson` is what the page's other scripts drive
// (null on a lesson with neither a scene nor worked examples); the browser tests read it too, by importing this module.
import { api, apiPatient, randomId } from "./api.js";
import { config } from "./config.js";
import { formatNumber } from "./format.js";
import { katexInto, renderMath } from "./katex.js";
import { renderPlot } from "./plot.js";

export const lesson = (function () {
  const scene = config.scene;
  const examples = config.examples;
  if (!scene && !examples.length) return null;
  // In a classroom room (?room=…) static/js/room.js decides what the viewer shows and where changes go.
  const inRoom = new URLSearchParams(location.search).has("room");

  // ---- session: one per tab and lesson, kept across reloads --------------------
  const storageKey = `dynlab.session.${config.lesson_id}`;
  let saved = null;
  try { saved = JSON.parse(sessionStorage.getItem(storageKey)); } catch (e) { saved = null; }
  // The key claims the session on the first change: nobody who only learns the id can drive this page's scene.
  const session = { id: (saved && saved.id) || randomId(), key: (saved && saved.key) || randomId(), values: {} };

  // ---- parameters: the scene's, else the union of the examples' inputs ------------
  const specs = [];
  const seen = new Set();
  for (const spec of scene ? scene.parameters : examples.flatMap((e) => e.inputs)) {
    if (!seen.has(spec.name)) { seen.add(spec.name); specs.push(spec); }
  }
  const defaults = Object.fromEntries(specs.map((s) => [s.name, s.default]));
  session.values = { ...defaults };
  if (saved && saved.values) for (const s of specs) if (s.name in saved.values) session.values[s.name] = saved.values[s.name];
  // A share link (?params=…&t=…&playing=…&speed=…&camera=…) sets the values it carries; time_controls.js restores the rest.
  const shared = sharedState(new URLSearchParams(location.search), specs);
  if (shared) Object.assign(session.values, shared.params);

  // ---- number formatting (significant figures, units shown beside) -------------
  const fmt = (v) => (typeof v === "number" ? formatNumber(v) : String(v));
  const fmtValue = (v) => (Array.isArray(v) ? `[${v.map(fmtValue).join(", ")}]` : fmt(v)); // a vector, or a matrix row by row

  // ---- controls -------------------------------------------------------------------
  const form = document.getElementById("controls");
  const list = document.getElementById("control-list");
  const errorBox = document.getElementById("control-error");
  const errorHome = errorBox.nextElementSibling; // where a message about no one control is shown (before "Reset")
  const widgets = {};

  function toSlider(spec, v) {
    if (spec.scale === "log") return Math.log10(v);
    if (spec.scale === "symlog") return Math.sign(v) * Math.log10(1 + Math.abs(v));
    return v;
  }
  function fromSlider(spec, x) {
    if (spec.scale === "log") return +Math.pow(10, x).toPrecision(6);
    if (spec.scale === "symlog") return +(Math.sign(x) * (Math.pow(10, Math.abs(x)) - 1)).toPrecision(4);
    return +x;
  }

  for (const spec of specs) {
    const row = document.createElement("div");
    row.className = "control";
    row.dataset.name = spec.name;
    const id = `ctl-${spec.name}`;
    const label = document.createElement("label");
    label.htmlFor = id;
    label.innerHTML = `${spec.label} <span class="unit">${spec.unit ? "(" + spec.unit + ")" : ""}</span>`;
    row.appendChild(label);
    if (spec.kind === "choice") {
      const select = document.createElement("select");
      select.id = id;
      for (const c of spec.choices) select.add(new Option(c, c));
      select.value = session.values[spec.name];
      select.addEventListener("change", () => { session.values[spec.name] = select.value; schedule(); });
      row.appendChild(select);
      row.appendChild(document.createElement("span"));
      widgets[spec.name] = { set: (v) => { select.value = v; } };
    } else if (spec.kind === "text") {
      // Typed text (e.g. a curve x(t)): sent on Enter or when the box loses focus; the server parses it.
      row.classList.add("wide");
      const input = document.createElement("input");
      input.type = "text";
      input.id = id;
      input.maxLength = spec.max_length;
      input.spellcheck = false;
      input.autocomplete = "off";
      input.value = session.values[spec.name];
      input.addEventListener("change", () => { session.values[spec.name] = input.value; schedule(); });
      row.appendChild(input);
      widgets[spec.name] = { set: (v) => { input.value = v; } };
    } else if (spec.kind === "list") {
      // A list of records (the bodies of a composite): an editable table, the whole list sent on each change.
      row.classList.add("list");
      const editor = bodyEditor(spec, (records) => { session.values[spec.name] = records; schedule(); });
      editor.set(session.values[spec.name]);
      row.appendChild(editor.element);
      widgets[spec.name] = { set: (v) => { session.values[spec.name] = editor.set(v); }, markError: editor.markError };
    } else if (spec.kind === "vector") {
      // A vector: one number box per component, e.g. [x, y, z] in the body frame.
      row.classList.add("wide");
      const boxes = document.createElement("span");
      boxes.className = "vector";
      const inputs = [];
      for (let i = 0; i < spec.length; i++) {
        const number = document.createElement("input");
        number.type = "number";
        number.id = i === 0 ? id : `${id}-${i}`;
        number.min = spec.min; number.max = spec.max; number.step = "any";
        number.setAttribute("aria-label", `${spec.label} component ${"xyz"[i] || i}`);
        number.addEventListener("change", () => {
          const v = inputs.map((box) => Number(box.value));
          if (inputs.some((box) => box.value === "") || !v.every(Number.isFinite)) { showError(spec.name, `${spec.label} needs ${spec.length} numbers`); return; }
          session.values[spec.name] = v;
          schedule();
        });
        inputs.push(number);
        boxes.appendChild(number);
      }
      const set = (v) => { inputs.forEach((box, i) => { box.value = v[i]; }); };
      set(session.values[spec.name]);
      row.appendChild(boxes);
      widgets[spec.name] = { set };
    } else {
      const slot = document.createElement("span");
      slot.className = "slider";
      const range = document.createElement("input");
      range.type = "range";
      range.min = toSlider(spec, spec.min);
      range.max = toSlider(spec, spec.max);
      range.step = spec.scale === "log" ? 0.05 : spec.scale === "symlog" ? 0.01 : (spec.step || (spec.max - spec.min) / 200);
      range.setAttribute("aria-label", `${spec.label} slider`);
      range.setAttribute("aria-describedby", `${id}-desc`);
      const number = document.createElement("input");
      number.type = "number";
      number.id = id;
      number.min = spec.min; number.max = spec.max; number.step = "any";
      const set = (v) => { range.value = toSlider(spec, v); number.value = v; };
      set(session.values[spec.name]);
      range.addEventListener("input", () => {
        const v = fromSlider(spec, range.value);
        number.value = v;
        session.values[spec.name] = v;
        schedule();
      });
      number.addEventListener("change", () => {
        const v = Number(number.value);
        if (number.value === "" || !Number.isFinite(v)) { showError(spec.name, `${spec.label} needs a number`); return; }
        range.value = toSlider(spec, v);
        session.values[spec.name] = v;
        schedule();
      });
      slot.appendChild(range);
      row.appendChild(slot);
      row.appendChild(number);
      widgets[spec.name] = { set, slot };
    }
    const desc = document.createElement("div");
    desc.className = "desc";
    desc.id = `${id}-desc`;
    desc.textContent = ["choice", "text", "list"].includes(spec.kind) ? spec.description : `${spec.description} (${spec.min} to ${spec.max} ${spec.unit})`;
    row.appendChild(desc);
    list.appendChild(row);
  }
  // Presets: one button sets several controls (e.g. a helix, the tennis-racket body).
  if (scene && scene.presets && scene.presets.length) {
    const bar = document.createElement("div");
    bar.className = "presets";
    bar.setAttribute("role", "group");
    bar.setAttribute("aria-label", "Presets");
    const title = document.createElement("span");
    title.textContent = "Presets:";
    bar.appendChild(title);
    for (const preset of scene.presets) {
      const button = document.createElement("button");
      button.type = "button";
      button.dataset.preset = preset.name;
      button.textContent = preset.label;
      button.title = preset.description || preset.label;
      button.addEventListener("click", () => {
        Object.assign(session.values, preset.values);
        for (const name of Object.keys(preset.values)) if (widgets[name]) widgets[name].set(preset.values[name]);
        schedule({ preset: preset.name });
      });
      bar.appendChild(button);
    }
    list.before(bar);
  }
  form.hidden = specs.length === 0;
  document.getElementById("reset").addEventListener("click", () => {
    session.values = { ...defaults };
    for (const s of specs) widgets[s.name].set(defaults[s.name]);
    schedule({ reset: true });
  });

  function showError(field, message, loc) {
    // loc (from a 422): [..., name, index, field, ...] points into a list control's row and field.
    const path = loc || [];
    let listName = null;
    for (const [name, widget] of Object.entries(widgets)) {
      if (!widget.markError) continue;
      const at = path.indexOf(name);
      const hit = at >= 0 && path.length > at + 1;
      widget.markError(hit ? path[at + 1] : null, hit ? path[at + 2] : null);
      if (at >= 0) listName = name;
    }
    const invalid = listName || field;
    let invalidRow = null;
    list.querySelectorAll(".control").forEach((row) => {
      row.classList.toggle("invalid", row.dataset.name === invalid);
      if (row.dataset.name === invalid) invalidRow = row;
    });
    // The message goes right under the control it is about (on a phone the list below it is a screen or more
    // long); one about no control in particular goes under the whole list.
    if (message && invalidRow) invalidRow.append(errorBox);
    else if (errorBox.parentNode !== errorHome.parentNode) errorHome.parentNode.insertBefore(errorBox, errorHome);
    errorBox.textContent = message;
    errorBox.hidden = !message;
    if (message) {
      const box = errorBox.getBoundingClientRect();
      if (box.top < 0 || box.bottom > window.innerHeight) errorBox.scrollIntoView({ block: "nearest" });
    }
  }

  // ---- body editor: one row per record of a "list" parameter (item_schema: fields, shapes, sequences) -----
  function bodyEditor(spec, onChange) {
    const schema = spec.item_schema;
    const shapes = Object.fromEntries(schema.shapes.map((s) => [s.shape, s]));
    const element = document.createElement("div");
    element.className = "body-editor";
    const rows = document.createElement("div");
    const add = document.createElement("button");
    add.type = "button";
    add.className = "add-body";
    add.textContent = "add body";
    element.append(rows, add);
    let records = [];
    const clone = (v) => JSON.parse(JSON.stringify(v));
    const field = (text, input) => {
      const label = document.createElement("label");
      label.className = "field";
      const span = document.createElement("span");
      span.textContent = text;
      label.append(span, input);
      return label;
    };
    const number = (value, name, component) => {
      const input = document.createElement("input");
      input.type = "number";
      input.step = "any";
      input.value = value;
      input.dataset.field = name;
      if (component !== undefined) input.dataset.component = component;
      return input;
    };
    const select = (options, value, name) => {
      const el = document.createElement("select");
      for (const o of options) el.add(new Option(o, o));
      el.value = value;
      el.dataset.field = name;
      return el;
    };
    function render() {
      rows.replaceChildren(...records.map((record, index) => {
        const shape = shapes[record.shape];
        const box = document.createElement("fieldset");
        box.className = "body-row";
        box.dataset.index = index;
        const legend = document.createElement("legend");
        legend.textContent = `body ${index + 1}`;
        box.appendChild(legend);
        box.appendChild(field("shape", select(schema.shapes.map((s) => s.shape), record.shape, "shape")));
        box.appendChild(field("mass (kg)", number(record.mass_kg, "mass_kg")));
        for (const d of shape.dimensions) box.appendChild(field(`${d.replace(/_m$/, "").replaceAll("_", " ")} (m)`, number(record[d], d)));
        "xyz".split("").forEach((c, i) => box.appendChild(field(`${c} (m)`, number(record.position_m[i], "position_m", i))));
        box.appendChild(field("sequence", select(schema.sequences, record.sequence, "sequence")));
        [0, 1, 2].forEach((i) => box.appendChild(field(`angle ${i + 1} (deg)`, number(record.angles_deg[i], "angles_deg", i))));
        const hole = document.createElement("input");
        hole.type = "checkbox";
        hole.checked = record.hole;
        hole.dataset.field = "hole";
        box.appendChild(field("hole", hole));
        const remove = document.createElement("button");
        remove.type = "button";
        remove.className = "remove-body";
        remove.textContent = "remove";
        remove.setAttribute("aria-label", `remove body ${index + 1}`);
        remove.addEventListener("click", () => { records.splice(index, 1); render(); onChange(clone(records)); });
        box.appendChild(remove);
        box.addEventListener("change", (event) => edit(index, event.target));
        return box;
      }));
      add.disabled = records.length >= schema.max_items;
    }
    function edit(index, input) {
      const record = records[index];
      const name = input.dataset.field;
      if (name === "shape") {
        // Keep the dimensions the new shape shares with the old one; the rest start at 0.1 m.
        const kept = { shape: input.value, mass_kg: record.mass_kg };
        for (const d of shapes[input.value].dimensions) kept[d] = d in record ? record[d] : 0.1;
        records[index] = { ...kept, position_m: record.position_m, sequence: record.sequence, angles_deg: record.angles_deg, hole: record.hole };
        render();
      } else if (name === "sequence") {
        record.sequence = input.value;
      } else if (name === "hole") {
        record.hole = input.checked;
      } else {
        const v = Number(input.value);
        if (input.value === "" || !Number.isFinite(v)) {
          const fieldLabel = input.closest("label").querySelector("span").textContent;  // e.g. "radius (m)", as the server words it
          showError(spec.name, `${spec.label}, body ${index + 1}, ${fieldLabel}: needs a number`, [spec.name, index, name]);
          return;
        }
        if (input.dataset.component !== undefined) record[name][Number(input.dataset.component)] = v;
        else record[name] = v;
      }
      onChange(clone(records));
    }
    add.addEventListener("click", () => {
      records.push({ shape: "sphere", mass_kg: 1, radius_m: 0.05, position_m: [0, 0, 0], sequence: "3-2-1", angles_deg: [0, 0, 0], hole: false });
      render();
      onChange(clone(records));
    });
    return {
      element,
      set(v) { records = clone(v); render(); return clone(records); },
      markError(index, name) {
        rows.querySelectorAll(".body-row").forEach((box) => {
          const here = index !== null && index !== undefined && Number(box.dataset.index) === Number(index);
          box.classList.toggle("invalid", here);
          box.querySelectorAll("[data-field]").forEach((el) => el.classList.toggle("invalid", here && el.dataset.field === name));
        });
      },
    };
  }

  // A change to this page's scene or a solve, with the session's key: nobody who only learns its id may change it.
  const call = (method, url, body) => api(method, url, body, { "X-Session-Key": session.key });
  // Setting the scene's parameters and solving the examples may be sent again unchanged: a busy server is waited out
  // (its Retry-After), with a word in the error line meanwhile, instead of losing the student's change.
  const callPatiently = (method, url, body) =>
    apiPatient(method, url, body, { "X-Session-Key": session.key }, {
      onWait: (seconds) => showError(null, `The server is busy; sending your change again in ${seconds} s…`),
    });

  // ---- solution panel ---------------------------------------------------------------
  const panel = document.getElementById("solution");
  // An example's story (the words around its steps), typeset once and moved into each new rendering of its solution.
  const STORY_PARTS = { situation: "The situation", wanted: "What is wanted", approach: "Why this approach", check: "The check", what_if: "What if" };
  const stories = {};
  function story(example) {
    if (!example.story_html) return null;
    if (!stories[example.id]) {
      const part = (name) => {
        const section = document.createElement("section");
        section.className = `story story-${name.replace("_", "-")}`;
        const title = document.createElement("h3");
        title.textContent = STORY_PARTS[name];
        const body = document.createElement("div");
        body.innerHTML = example.story_html[name]; // server-rendered Markdown of our own example modules
        renderMath(body);
        section.append(title, body);
        return section;
      };
      stories[example.id] = { before: ["situation", "wanted", "approach"].map(part), after: ["check", "what_if"].map(part) };
    }
    return stories[example.id];
  }
  function renderSolution(example, result) {
    const box = document.createElement("div");
    box.className = "example";
    box.dataset.example = example.id;
    box.dataset.inputs = JSON.stringify(result.inputs);
    const h = document.createElement("h2");
    h.textContent = `Worked ${example.story_html ? "example" : "solution"} — ${example.title}`;
    box.appendChild(h);
    const words = story(example);
    if (words) box.append(...words.before);
    const outputs = document.createElement("table");
    outputs.className = "outputs";
    outputs.innerHTML = "<thead><tr><th>output</th><th>value</th><th>unit</th></tr></thead>";
    const tbody = document.createElement("tbody");
    for (const [name, value] of Object.entries(result.outputs)) {
      if (Array.isArray(value) && value.length > 3) continue; // sweeps are plotted, not listed
      const tr = document.createElement("tr");
      tr.innerHTML = `<td class="sym"></td><td class="val"></td><td class="unit"></td>`;
      tr.children[0].textContent = name;
      tr.children[1].textContent = fmtValue(value);
      tr.children[1].dataset.output = name;
      tr.children[1].dataset.value = JSON.stringify(value);
      tr.children[2].textContent = example.output_units[name] || "";
      tbody.appendChild(tr);
    }
    outputs.appendChild(tbody);
    box.appendChild(outputs);
    for (const step of result.steps) {
      const div = document.createElement("div");
      div.className = "step";
      const title = document.createElement("h3");
      title.textContent = step.title;
      const eq = document.createElement("div");
      katexInto(eq, step.latex, true);
      const table = document.createElement("table");
      table.className = "values";
      for (const [sym, value] of Object.entries(step.values)) {
        const tr = document.createElement("tr");
        tr.innerHTML = `<td class="sym"></td><td></td>`;
        tr.children[0].textContent = sym;
        tr.children[1].textContent = `${fmtValue(value)} ${step.units[sym] || ""}`;
        table.appendChild(tr);
      }
      div.append(title, eq, table);
      box.appendChild(div);
    }
    for (const plot of result.plots || []) {
      const div = document.createElement("div");
      renderPlot(div, plot);
      box.appendChild(div);
    }
    if (words) box.append(...words.after);
    return box;
  }

  // ---- one update at a time, always ending on the latest values ------------------
  let running = false, pending = false, viewerStarted = false;
  // The room's hook (room.js): when set, changed values go to it instead of this page's own session.
  let changeHook = null;
  let sentValues = { ...session.values };
  const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
  function changedValues() {
    const changed = {};
    for (const s of specs) if (!same(session.values[s.name], sentValues[s.name])) changed[s.name] = session.values[s.name];
    sentValues = { ...session.values };
    return changed;
  }
  // ---- "Open as Python": scripts that print this page's numbers with the project's own package ----
  const pythonLinks = document.getElementById("open-as-python");
  function showPythonLinks(values) {
    if (!pythonLinks) return;
    const link = (url, params, text) => {
      const a = document.createElement("a");
      a.href = `${url}?params=${encodeURIComponent(JSON.stringify(params))}`;
      a.textContent = text;
      return a;
    };
    const links = scene ? [link(`/api/scenes/${scene.id}/script.py`, values, scene.title)] : [];
    for (const example of examples) {
      const inputs = Object.fromEntries(example.inputs.map((s) => [s.name, values[s.name]]));
      links.push(link(`/api/examples/${encodeURIComponent(example.id)}/script.py`, inputs, `worked example ${example.id}`));
    }
    pythonLinks.replaceChildren("Open as Python, for the values above: ", ...links.flatMap((a, i) => (i ? [" · ", a] : [a])));
    pythonLinks.hidden = false;
  }
  async function update() {
    const values = { ...session.values };
    try {
      if (scene && !changeHook) {
        const reply = await callPatiently("PUT", `/api/scenes/${scene.id}/sessions/${session.id}`, { params: values });
        Object.assign(values, reply.params);
        pollSoon();
        sessionExists();
        if (!viewerStarted && !inRoom) startViewer(); // the worked examples below need not hold the scene back
      }
      const rendered = [];
      for (const example of examples) {
        const inputs = Object.fromEntries(example.inputs.map((s) => [s.name, values[s.name]]));
        const result = await callPatiently("POST", `/api/examples/${encodeURIComponent(example.id)}/solve`, { inputs });
        rendered.push(renderSolution(example, result));
      }
      if (rendered.length) {
        const stamp = document.createElement("p");
        stamp.className = "updated";
        stamp.textContent = `Computed by the server at ${new Date().toLocaleTimeString()} for the controls above.`;
        panel.replaceChildren(...rendered, stamp);
        panel.hidden = false;
      }
      showError(null, "");
      showPythonLinks(values);
      sessionStorage.setItem(storageKey, JSON.stringify(session));
    } catch (err) {
      showError(err.field, err.message, err.loc);
    }
  }
  async function schedule(how) {
    if (changeHook) {
      const changed = changedValues();
      if (Object.keys(changed).length || how) changeHook(changed, how || {});
    } else {
      sentValues = { ...session.values };
    }
    if (running) { pending = true; return; }
    running = true;
    do { pending = false; await update(); } while (pending);
    running = false;
  }

  // ---- live readout: the scene's own quantities, marks on controls, integration ------
  const live = document.getElementById("live");
  const readoutBox = document.getElementById("readout");
  let pollTimer = null;
  // Live numbers exist once the page's viewer has connected (about 1 s after it starts): until then the poll asks
  // the session's playback (a small answer), every quarter second, which counts its viewers, instead of asking
  // /live into a 404.
  let viewerConnected = false;
  let pollInFlight = false, pollAgain = false;
  async function pollLive() {
    pollTimer = null;
    pollInFlight = true;
    try {
      if (!viewerConnected) {
        const playback = await fetch(`/api/scenes/${scene.id}/sessions/${session.id}/playback`);
        viewerConnected = playback.ok && (await playback.json()).viewers > 0;
      }
      if (viewerConnected) {
        const askedAtMs = performance.now(); // listeners tell an answer that predates their own last change
        const response = await fetch(`/api/scenes/${scene.id}/sessions/${session.id}/live`);
        if (response.ok) {
          const data = await response.json();
          document.dispatchEvent(new CustomEvent("dynlab:live", { detail: { ...data, askedAtMs } }));
          if (data.readout) renderReadout(data.readout);
          if (scene.integrated && data.invariants) renderLive(data);
        } else if (response.status === 404) viewerConnected = false; // the viewer went (a reconnect): wait for it again
      }
    } catch (e) { /* the next poll retries */ }
    pollInFlight = false;
    if (polling) pollTimer = setTimeout(pollLive, pollAgain ? 0 : document.hidden ? 3000 : viewerConnected ? 1000 : 250);
    pollAgain = false;
  }
  // A control the student changed has reached the scene: ask for its numbers now, so the readout answers the change
  // at once rather than at the next second's poll (a poll already on its way is followed straight away by another).
  function pollSoon() {
    if (!polling) return;
    if (pollInFlight) { pollAgain = true; return; }
    clearTimeout(pollTimer);
    pollTimer = setTimeout(pollLive, 0);
  }
  let polling = false;
  function startPolling() {
    if (polling || !scene || !(scene.integrated || scene.readout)) return;
    polling = true;
    viewerConnected = false;
    pollTimer = setTimeout(pollLive, 250);  // the first numbers follow the viewer's connection within a quarter second
  }
  function stopPolling() {
    polling = false;
    clearTimeout(pollTimer);
    pollTimer = null;
  }
  // ---- described motion: one short line a screen reader announces politely (the readout table is not live) ----
  // The scene's time, its status, the readout's first two quantities and its message (only when the message is
  // new), rewritten at most every MOTION_EVERY_MS: a screen reader must not read the table's numbers every second.
  const motionLine = document.querySelector(".motion-description");
  const MOTION_EVERY_MS = 5000;
  const motion = { t_s: null, status: "", readout: null, shownAt: -Infinity, timer: null, toldMessage: "" };
  const spoken = (v) => formatNumber(v, { digits: 3, expDigits: 2, large: 1e4 });
  const withoutEquations = (text) => text.split("$$").filter((_, i) => i % 2 === 0).join(" ").replace(/\s+/g, " ").trim();
  function motionSentence() {
    const items = (motion.readout && motion.readout.quantities) || [];
    const clock = items.find((item) => item.name === "t_s" && typeof item.value === "number");
    const t = motion.t_s !== null ? motion.t_s : clock ? clock.value : null;
    const parts = [];
    if (t !== null) parts.push(`t = ${t.toFixed(1)} s`);
    if (motion.status) parts.push(motion.status);
    const quantities = items.filter((item) => item.name !== "t_s").slice(0, 2).map((item) => (item.value === null || item.value === undefined
      ? `${item.label}: ${item.text || "not defined"}` : `${item.label} = ${spoken(item.value)}${item.unit ? " " + item.unit : ""}`));
    if (quantities.length) parts.push(quantities.join(", "));
    const message = withoutEquations((motion.readout && motion.readout.message) || "");
    if (message && message !== motion.toldMessage) parts.push(message.length > 160 ? `${message.slice(0, 159)}…` : message);
    return { sentence: parts.join("; "), message };
  }
  function describeMotion(update) {
    Object.assign(motion, update);
    if (!motionLine || motion.timer) return;
    motion.timer = setTimeout(() => {
      motion.timer = null;
      const { sentence, message } = motionSentence();
      if (sentence === motionLine.textContent) return;
      motionLine.textContent = sentence;
      motion.shownAt = performance.now();
      motion.toldMessage = message;
    }, Math.max(motion.shownAt + MOTION_EVERY_MS - performance.now(), 0));
  }
  function renderReadout(readout) {
    readoutBox.hidden = false;
    const tbody = readoutBox.querySelector("tbody");
    const items = readout.quantities || [];
    // Same quantities as last time: update the cells in place (no flicker, stable for screen readers).
    const names = items.map((item) => item.name).join("|");
    if (tbody.dataset.names !== names) {
      tbody.replaceChildren(...items.map(() => {
        const tr = document.createElement("tr");
        tr.innerHTML = "<td class='sym'></td><td class='val'></td><td class='unit'></td>";
        return tr;
      }));
      tbody.dataset.names = names;
    }
    items.forEach((item, i) => {
      const tr = tbody.children[i];
      tr.children[0].textContent = item.label;
      // A null value shows its text (why it is undefined, or a word); a number with a text shows both.
      const shown = item.value === null || item.value === undefined ? (item.text || "") : item.value;
      tr.children[1].textContent = item.value === null || item.value === undefined
        ? shown : (item.text ? `${fmt(item.value)} (${item.text})` : fmt(item.value));
      tr.children[1].dataset.quantity = item.name;
      tr.children[1].dataset.value = JSON.stringify(shown);
      // A value that is text (a word, or why there is no number) has no unit: "no flips in this motion", not "… s";
      // a vector's components given as text (text_in_unit) keep theirs.
      tr.children[2].textContent = (item.value === null || item.value === undefined) && !item.text_in_unit ? "" : (item.unit || "");
    });
    const message = readoutBox.querySelector(".readout-message");
    if (message.dataset.source !== (readout.message || "")) {
      // Text between $$ … $$ is an equation (e.g. equations a scene derived); the rest is plain text.
      message.dataset.source = readout.message || "";
      message.replaceChildren();
      (readout.message || "").split("$$").forEach((part, i) => {
        if (i % 2 === 0) { if (part) message.append(part); return; }
        const eq = document.createElement("div");
        eq.className = "readout-equation";
        katexInto(eq, part, true);
        message.append(eq);
      });
    }
    message.hidden = !readout.message;
    describeMotion({ readout });
    // Marks: a labelled tick on a slider at a value that depends on the other controls.
    for (const [name, spec] of Object.entries(widgets)) {
      if (!spec.slot) continue;
      spec.slot.querySelectorAll(".mark").forEach((el) => el.remove());
      const control = specs.find((s) => s.name === name);
      const marks = (readout.marks || {})[name] || [];
      spec.slot.closest(".control").classList.toggle("has-mark", marks.length > 0);
      for (const mark of marks) {
        const lo = toSlider(control, control.min), hi = toSlider(control, control.max);
        const x = (toSlider(control, mark.value) - lo) / (hi - lo);
        const tick = document.createElement("span");
        tick.className = "mark";
        tick.dataset.mark = mark.label;
        tick.dataset.value = String(mark.value);
        tick.title = `${mark.label}: ${fmt(mark.value)} ${control.unit}`;
        tick.hidden = !(x >= 0 && x <= 1);
        tick.style.left = `${(100 * Math.min(Math.max(x, 0), 1)).toFixed(2)}%`;
        tick.innerHTML = "<span></span>";
        tick.firstChild.textContent = mark.label;
        spec.slot.appendChild(tick);
      }
      placeMarkLabels(spec.slot);
    }
  }
  // Mark labels, measured: each is centred over its tick but kept inside the slider; one that would overlap the
  // label before it goes up a row, and one that would overlap on both rows keeps only its tick (whose title names it).
  // Redone on every readout (about once a second), so a narrower window or projector mode's larger text is taken in.
  const MARK_LABEL_GAP_PX = 6;
  function placeMarkLabels(slot) {
    const slotBox = slot.getBoundingClientRect();
    const rowEnds = [-Infinity, -Infinity];
    let rowsUsed = 0;
    const ticks = [...slot.querySelectorAll(".mark:not([hidden])")].map((tick) => [tick, tick.getBoundingClientRect().left - slotBox.left]);
    for (const [tick, tickLeft] of ticks.sort((a, b) => a[1] - b[1])) {
      const label = tick.firstChild;
      const width = label.getBoundingClientRect().width;
      const left = Math.min(Math.max(tickLeft + 1 - width / 2, 0), Math.max(slotBox.width - width, 0));
      label.style.left = `${(left - tickLeft).toFixed(1)}px`;
      label.style.transform = "none";
      const row = rowEnds.findIndex((end) => left >= end + MARK_LABEL_GAP_PX);
      label.hidden = row < 0;
      label.classList.toggle("upper", row === 1);
      if (row >= 0) { rowEnds[row] = left + width; rowsUsed = Math.max(rowsUsed, row + 1); }
    }
    slot.closest(".control").classList.toggle("two-mark-rows", rowsUsed > 1);
  }
  function renderLive(data) {
    live.hidden = false;
    const q = (name) => live.querySelector(`[data-live="${name}"]`);
    q("description").textContent = data.description;
    q("t_s").textContent = data.t_s.toFixed(2);
    describeMotion({ t_s: data.t_s, status: data.status || "" });
    q("cost").textContent = data.physics_us_per_frame.toFixed(1);
    const status = q("status");
    status.hidden = !data.status;
    status.textContent = data.status;
    const rows = Object.entries(data.invariants).map(([name, inv]) => {
      const tr = document.createElement("tr");
      tr.innerHTML = "<td class='sym'></td><td class='val'></td><td class='unit'></td><td class='val'></td>";
      tr.children[0].textContent = name.replaceAll("_", " ");
      tr.children[1].textContent = fmt(inv.value);
      tr.children[2].textContent = inv.unit;
      tr.children[3].textContent = inv.relative_drift.toExponential(1);
      tr.children[3].dataset.drift = name;
      return tr;
    });
    q("invariants").replaceChildren(...rows);
    renderAccuracy(data);
    const h = data.drift_history;
    const points = h.t_s.map((t, i) => [t, Math.max(h.max_relative_drift[i], 1e-17)]);
    if (points.length > 1) {
      renderPlot(q("plot"), {
        title: "Largest invariant drift (relative)", x_label: "t (s)", y_label: "|ΔI| / scale", log_x: false, log_y: true,
        series: [{ name: "max drift", x: points.map((p) => p[0]), y: points.map((p) => p[1]) }],
      });
    }
  }

  // Accuracy: the target the automatic step meets, the error estimated for the step in use, and the error
  // against the model's reference solution (phase error, beside the invariants' drift). Absent keys hide the lines.
  function liveLine(name, after) {
    let el = live.querySelector(`[data-live="${name}"]`);
    if (!el) {
      el = document.createElement("p");
      el.className = "live-accuracy";
      el.dataset.live = name;
      after.after(el);
    }
    return el;
  }
  function renderAccuracy(data) {
    const method = live.querySelector(".live-method");
    const accuracy = liveLine("accuracy", method);
    const acc = data.accuracy;
    accuracy.hidden = !acc;
    if (acc) {
      accuracy.textContent = acc.accuracy + (acc.note ? ` — ${acc.note}` : "");
      // "estimating": the pilot is still measuring (the fixed step rule runs meanwhile), not a fault.
      accuracy.classList.toggle("error", acc.status !== "ok" && acc.status !== "estimating");
      accuracy.dataset.status = acc.status;
      accuracy.dataset.estimated = acc.estimated_error === null ? "" : String(acc.estimated_error);
    }
    const reference = liveLine("reference_error", accuracy);
    const ref = data.reference_error;
    reference.hidden = !ref;
    if (ref) {
      const unit = ref.unit || "relative";
      reference.textContent = `error against the ${ref.reference}: ${ref.value.toExponential(1)} ${unit} now, ` +
        `${ref.max_so_far.toExponential(1)} ${unit} at most so far`;
      reference.dataset.value = String(ref.value);
    }
  }

  function startViewer() {
    document.dispatchEvent(new CustomEvent("dynlab:viewer-started"));
    startPolling();
    showViewer(ownViewer);
  }
  const ownViewer = scene ? `/viewer/${scene.id}/${session.id}/?hideViserLogo` : null;
  // The page's own viewer, preloaded: it loads and starts viser's client while the page renders and makes its
  // session, and opens its websocket when told the session exists (app/web/pages.py VIEWER_SCRIPT, `wait`): a
  // viewer may not open a session its page has not made. It is the own viewer, so showing that keeps it.
  const preloadedViewer = scene ? `${ownViewer}&wait` : null;
  // What must reach the session before its viewer opens (holdViewer: a share link's instant, which time_controls.js
  // sends once the session exists), so the viewer's scene starts there rather than playing from t = 0 until it comes.
  let sessionReady = false;
  const viewerHolds = [];
  const holdViewer = (promise) => { viewerHolds.push(promise.catch(() => {})); };
  const viewerFrame = document.getElementById("viewer");
  const tellViewer = () => viewerFrame.contentWindow.postMessage({ type: "dynlab:session-ready" }, location.origin);
  function sessionExists() {
    Promise.all(viewerHolds).then(() => {
      sessionReady = true;
      if (viewerFrame.getAttribute("src") === preloadedViewer) tellViewer();
    });
  }
  window.addEventListener("message", (event) => {
    if (event.origin !== location.origin || event.source !== viewerFrame.contentWindow) return;
    if (event.data && event.data.type === "dynlab:viewer-waiting" && sessionReady) tellViewer();
  });
  const showsOwnViewer = () => ownViewer !== null && [ownViewer, preloadedViewer].includes(viewerFrame.getAttribute("src"));
  function showViewer(src) {
    viewerStarted = true;
    document.getElementById("viewer-wrap").hidden = false;
    if (viewerFrame.getAttribute("src") !== src && !(src === ownViewer && showsOwnViewer())) viewerFrame.src = src;
  }
  function preloadViewer() { // as viewer_preload.js did while the page was parsed, unless it could not
    document.getElementById("viewer-wrap").hidden = false;
    if (viewerFrame.getAttribute("src") !== preloadedViewer) viewerFrame.src = preloadedViewer;
  }

  // ---- what room.js drives: values shown without sending, locked controls, the viewer, the readout ------
  let locked = false, lockReason = "";
  const lockNote = document.createElement("p");
  lockNote.className = "controls-locked";
  lockNote.setAttribute("role", "status");
  lockNote.hidden = true;
  form.querySelector("h2").after(lockNote);
  function applyLock() {
    for (const el of form.querySelectorAll("input, select, textarea, button")) {
      if (locked && !el.disabled) { el.disabled = true; el.dataset.roomLocked = "1"; }
      else if (!locked && el.dataset.roomLocked) { el.disabled = false; delete el.dataset.roomLocked; }
    }
    form.classList.toggle("locked", locked);
    lockNote.textContent = lockReason;
    lockNote.hidden = !locked || !lockReason;
  }
  function lock(on, why) {
    locked = Boolean(on);
    lockReason = why || "";
    applyLock();
  }
  function setValues(values) {
    for (const s of specs) {
      if (!(s.name in values)) continue;
      session.values[s.name] = values[s.name];
      sentValues[s.name] = values[s.name];
      widgets[s.name].set(values[s.name]);
    }
    if (locked) applyLock(); // a list control redraws its rows: lock the new ones too
  }
  function onChange(fn) { changeHook = typeof fn === "function" ? fn : null; }

  // A share link's state: parameters (only known names; the server validates the values), time, play state, speed, camera.
  function sharedState(query, knownSpecs) {
    if (!query.has("t") && !query.has("params")) return null;
    let values = {};
    try { values = JSON.parse(query.get("params") || "{}"); } catch (e) { values = {}; }
    const known = new Set(knownSpecs.map((s) => s.name));
    const paramsOut = Object.fromEntries(Object.entries(values && typeof values === "object" ? values : {}).filter(([k]) => known.has(k)));
    const t = Number(query.get("t"));
    const camera = (query.get("camera") || "").split(",").map(Number);
    return {
      params: paramsOut,
      t_s: Number.isFinite(t) && t >= 0 ? t : 0,
      playing: query.get("playing") !== "0",
      time_scale: query.has("speed") ? Number(query.get("speed")) : null,
      camera: camera.length === 6 && camera.every(Number.isFinite) ? { position: camera.slice(0, 3), look_at: camera.slice(3) } : null,
    };
  }

  const lesson = {
    session, schedule, scene, specs, defaults, ownViewer, shared,
    setValues, lock, onChange, showViewer, showsOwnViewer, startPolling, stopPolling, holdViewer,
    // The session's time controls and camera (PUT …/playback with the session key); rejects with the server's message.
    setPlayback: (body) => call("PUT", `/api/scenes/${scene.id}/sessions/${session.id}/playback`, body),
    renderReadout, renderLive: (data) => { if (scene && scene.integrated && data.invariants) renderLive(data); },
  };
  if (!inRoom) {
    if (scene) preloadViewer();
    schedule();
  }
  return lesson;
})();
