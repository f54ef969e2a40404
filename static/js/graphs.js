// Graphs under an integrated scene: energy bars (kinetic, potential, total, dissipated) and a graph of any
// series, invariant or energy part against time or against another quantity (a phase plot), with a CSV download.
// Polls GET /api/scenes/{scene}/sessions/{sid}/graph about 4 times a second, only while the section is open and
// the tab visible, asking for the frames after the last time received (since_s) and keeping the last 60 s.
// Time going back (restart, new parameters, play on from a scrubbed instant) starts the graph again.
import { element as el } from "./dom.js";
import { formatNumber } from "./format.js";
import { lesson } from "./lesson.js";
import { renderPlot } from "./plot.js";

(function () {
  const section = document.getElementById("graphs");
  if (!lesson || !section || !lesson.scene || !lesson.scene.animated) return;
  // A room's scene is the instructor's (room.js): a student graphs only their own copy, while exploring.
  const inRoom = new URLSearchParams(location.search).has("room");
  let own = !inRoom;
  const scene = lesson.scene;
  const session = lesson.session;
  const base = `/api/scenes/${scene.id}/sessions/${session.id}`;
  const POLL_MS = 250, IDLE_MS = 1000, RETRY_MS = 2000;
  const KEEP_S = 60;
  const WINDOWS_S = [5, 10, 30, KEEP_S]; // a fast motion (a nutation at a few hertz) needs a few seconds to be seen
  const MAX_Y = 3;
  const TIME = "__time__";
  const NONE = "";
  const TOTAL = "energy_total_J", DISSIPATED = "energy_dissipated_J";
  const SAME_FRAME_S = 1e-9;
  const TURN = { rad: 2 * Math.PI, deg: 360, "°": 360 }; // one whole turn, by the unit an angle is given in

  // Four significant figures, trailing zeros kept (18.00 J says how precisely it is shown).
  const fmt = (v) => formatNumber(v, { digits: 4, expDigits: 3, large: 1e4, keepZeros: true });

  // ---- the panel ---------------------------------------------------------------------------------------------
  const note = el("p", { class: "graphs-note" }, "Waiting for the scene to start…");
  const energyHeading = el("h3", { id: "energy-bars-title", text: "Energy now" });
  const energyRows = el("tbody");
  const energyTable = el("table", { class: "energy-bars", "aria-labelledby": "energy-bars-title" },
    el("thead", {}, el("tr", {}, el("th", { scope: "col", text: "part" }), el("th", { scope: "col", text: "bar (from zero)" }), el("th", { scope: "col", text: "value" }))),
    energyRows);
  const energyNote = el("p", { class: "energy-note", hidden: "" });
  const energyBox = el("div", { class: "energy", hidden: "" }, energyHeading, energyTable, energyNote);

  const xPick = el("select", { id: "graph-x" });
  const windowPick = el("select", { id: "graph-window" });
  for (const s of WINDOWS_S) windowPick.add(new Option(`the last ${s} s`, String(s)));
  windowPick.value = String(KEEP_S);
  const yPicks = Array.from({ length: MAX_Y }, (_, i) => el("select", { id: `graph-y${i + 1}` }));
  const pickers = el("div", { class: "graph-pickers", role: "group", "aria-label": "What the graph plots" },
    ...yPicks.map((select, i) => el("label", { for: select.id }, i === 0 ? "y " : `and y${i + 1} `, select)),
    el("label", { for: xPick.id }, "against x ", xPick),
    el("label", { for: windowPick.id }, "over ", windowPick));
  const plotBox = el("div", { class: "graph-plot" });
  const summary = el("p", { class: "graph-summary" });
  const csv = el("a", { class: "graph-csv", href: `${base}/graph.csv`, download: `${scene.id}-graph.csv`, hidden: "" }, "Download CSV (the kept motion, every quantity)");
  const graphBox = el("div", { class: "time-graph", hidden: "" }, el("h3", { text: "Graph" }), pickers, plotBox, summary, csv);
  section.append(note, energyBox, graphBox);

  // ---- what has been received: times, every quantity's values, the latest energy -------------------------------
  let quantities = [];
  const byName = {};
  let store = { t: [], values: {} };
  let lastT = null;
  function clearStore() {
    store = { t: [], values: Object.fromEntries(quantities.map((q) => [q.name, []])) };
    lastT = null;
  }
  const labelOf = (name) => (name === TIME ? "time t" : byName[name].label);
  const unitOf = (name) => (name === TIME ? "s" : byName[name].unit);
  const withUnit = (name) => (unitOf(name) ? `${labelOf(name)} (${unitOf(name)})` : labelOf(name));

  // What the student picked (null: not yet), kept apart from the pickers: a rebuilt picker list (another run's
  // quantities) puts it back wherever those quantities exist again.
  const chosen = { x: null, y: yPicks.map(() => null) };
  function setQuantities(next) {
    // A scene replaying from its start has kept no frames for a moment, and its answer then lists no quantities:
    // that is not a new set of quantities, so the pickers (and the student's choice) stay as they are.
    if (!next.length) return false;
    const names = next.map((q) => q.name).join("|");
    if (names === quantities.map((q) => q.name).join("|")) return false;
    quantities = next;
    for (const key of Object.keys(byName)) delete byName[key];
    for (const q of quantities) byName[q.name] = q;
    const keep = [chosen.x ?? xPick.value, ...yPicks.map((s, i) => chosen.y[i] ?? s.value)];
    const groups = [["series", "series"], ["invariant", "invariants"], ["energy", "energy"]];
    const fill = (select, first) => {
      select.replaceChildren(first);
      for (const [kind, title] of groups) {
        const members = quantities.filter((q) => q.kind === kind);
        if (!members.length) continue;
        const group = el("optgroup", { label: title });
        for (const q of members) group.append(new Option(withUnit(q.name), q.name));
        select.append(group);
      }
    };
    fill(xPick, new Option("time t (s)", TIME));
    yPicks.forEach((select, i) => fill(select, new Option(i === 0 ? "(choose)" : "(none)", NONE)));
    const known = (v) => v === TIME || v === NONE || v in byName;
    xPick.value = keep[0] && known(keep[0]) ? keep[0] : TIME;
    const firstSeries = (quantities.find((q) => q.kind === "series") || quantities[0] || {}).name || NONE;
    yPicks.forEach((select, i) => { select.value = keep[i + 1] && known(keep[i + 1]) ? keep[i + 1] : i === 0 ? firstSeries : NONE; });
    return true;
  }

  // One answer: new quantities rebuild the pickers, new frames are appended; returns when to ask again (ms).
  function receive(data) {
    if (setQuantities(data.quantities || [])) clearStore();
    note.textContent = data.note || "";
    note.hidden = !data.note;
    graphBox.hidden = quantities.length === 0;
    csv.hidden = quantities.length === 0;
    // Each request asks from the last time received, that frame included: if the server no longer keeps it, time
    // went back (restart, new parameters, playing on from an earlier instant) and the kept motion is another run.
    const times = data.t_s || [];
    if (lastT !== null && !(times.length && Math.abs(times[0] - lastT) <= SAME_FRAME_S)) {
      clearStore();
      replaying = true; // the last run's graph stays up for now (see below)
      renderGraph();
      return 0; // ask again at once, for the new run's frames from its start
    }
    // The server unwraps an angle within one answer only, from that answer's first frame, so an angle can come back
    // whole turns away from the values already kept; the repeated frame says how many turns to add.
    const turnShift = {};
    if (lastT !== null) {
      for (const q of quantities) {
        const period = TURN[q.unit];
        const kept = store.values[q.name];
        const again = ((data.values || {})[q.name] || [])[0];
        if (period && kept.length && kept[kept.length - 1] !== null && again !== null && again !== undefined) {
          turnShift[q.name] = period * Math.round((kept[kept.length - 1] - again) / period);
        }
      }
    }
    let added = 0;
    times.forEach((t, i) => {
      if (lastT !== null && t <= lastT) return;
      store.t.push(t);
      for (const q of quantities) {
        const value = ((data.values || {})[q.name] || [])[i] ?? null;
        store.values[q.name].push(value === null ? null : value + (turnShift[q.name] || 0));
      }
      lastT = t;
      added += 1;
    });
    if (lastT !== null) {
      const drop = store.t.findIndex((t) => t >= lastT - KEEP_S);
      if (drop > 0) {
        store.t.splice(0, drop);
        for (const name of Object.keys(store.values)) store.values[name].splice(0, drop);
      }
    }
    renderEnergy(data.energy);
    // After a replay the last run's graph stays up until the new run has a line (two instants), or until an answer
    // brings no new frame (the new run is paused): then the new run's graph, whatever it holds.
    const replayed = replaying && (store.t.length >= 2 || (!added && lastT !== null));
    if (replayed) replaying = false;
    if (added || replayed) renderGraph();
    // Paused (nothing new): ask less often; but a run that has just started again is asked at the usual rate.
    return added || lastT === null ? POLL_MS : IDLE_MS;
  }

  // ---- energy bars, from a zero line (a negative potential is drawn to the left of it) ------------------------
  function renderEnergy(energy) {
    energyBox.hidden = !energy;
    if (!energy) return;
    const rows = [
      ...energy.parts.filter((p) => p.name !== DISSIPATED).map((p) => ({ ...p, kind: "part" })),
      { name: TOTAL, label: "total (kinetic + potential)", value_J: energy.total_J, kind: "total" },
      ...energy.parts.filter((p) => p.name === DISSIPATED).map((p) => ({ ...p, label: `${p.label} (since t = 0)`, kind: "dissipated" })),
    ];
    const finite = rows.map((r) => r.value_J).filter(Number.isFinite);
    const lo = Math.min(0, ...finite), hi = Math.max(0, ...finite);
    const range = hi - lo || 1;
    const at = (v) => (100 * (v - lo)) / range;
    const zero = at(0);
    if (energyRows.dataset.names !== rows.map((r) => r.name).join("|")) {
      energyRows.replaceChildren(...rows.map((r) => el("tr", { class: `energy-${r.kind}` },
        el("th", { scope: "row" }),
        el("td", { class: "track-cell", "aria-hidden": "true" }, el("span", { class: "track" }, el("span", { class: "zero" }), el("span", { class: "bar" }))),
        el("td", { class: "val" }))));
      energyRows.dataset.names = rows.map((r) => r.name).join("|");
    }
    rows.forEach((r, i) => {
      const tr = energyRows.children[i];
      tr.children[0].textContent = r.label;
      const value = tr.children[2];
      value.dataset.energy = r.name;
      value.dataset.value = JSON.stringify(Number.isFinite(r.value_J) ? r.value_J : null);
      value.textContent = Number.isFinite(r.value_J) ? `${fmt(r.value_J)} J` : "not defined";
      const track = tr.children[1].firstChild;
      track.firstChild.style.left = `${zero.toFixed(2)}%`;
      const v = Number.isFinite(r.value_J) ? at(r.value_J) : zero;
      const bar = track.lastChild;
      bar.style.left = `${Math.min(v, zero).toFixed(2)}%`;
      bar.style.width = `${Math.abs(v - zero).toFixed(2)}%`;
    });
    energyHeading.textContent = lastT !== null ? `Energy at t = ${lastT.toFixed(2)} s` : "Energy now";
    energyNote.textContent = energy.note || "";
    energyNote.hidden = !energy.note;
  }

  // ---- the graph: y (up to three) against time or against a quantity ------------------------------------------
  function range(values) {
    const finite = values.filter(Number.isFinite);
    return finite.length ? [Math.min(...finite), Math.max(...finite)] : null;
  }
  let replaying = false;
  function renderGraph() {
    if (replaying) return;
    const xName = xPick.value;
    const yNames = [...new Set(yPicks.map((s) => s.value).filter((v) => v !== NONE && v in byName))];
    const from = store.t.findIndex((t) => t >= lastT - Number(windowPick.value) - SAME_FRAME_S);
    const shown = (values) => values.slice(Math.max(from, 0));
    const ts = shown(store.t);
    const xs = shown(xName === TIME ? store.t : store.values[xName] || []);
    const series = yNames.map((name) => ({ name: withUnit(name), x: xs, y: shown(store.values[name]) }));
    const plotted = series.filter((s) => s.y.some((v, i) => Number.isFinite(v) && Number.isFinite(s.x[i])));
    graphBox.dataset.points = String(plotted.length ? Math.max(...plotted.map((s) => s.y.filter((v, i) => Number.isFinite(v) && Number.isFinite(s.x[i])).length)) : 0);
    graphBox.dataset.kind = xName === TIME ? "time" : "phase";
    const what = yNames.map(withUnit).join(", ");
    const against = withUnit(xName);
    if (!yNames.length || !plotted.length || ts.length < 2) {
      plotBox.replaceChildren();
      summary.textContent = yNames.length ? "Waiting for the scene's motion…" : "Choose a quantity for y.";
      return;
    }
    const ranges = series.map((s, i) => {
      const name = yNames[i];
      const r = range(s.y);
      return r ? `${labelOf(name)} from ${fmt(r[0])} to ${fmt(r[1])} ${unitOf(name)}` : `${labelOf(name)} not defined`;
    });
    const description = `${xName === TIME ? "Time graph" : "Phase plot"} of ${what} against ${against}: ` +
      `${ts.length} instants from t = ${ts[0].toFixed(2)} s to ${ts[ts.length - 1].toFixed(2)} s; ${ranges.join("; ")}.`;
    renderPlot(plotBox, {
      title: `${yNames.map(labelOf).join(", ")} against ${labelOf(xName)}`,
      x_label: against,
      y_label: yNames.length === 1 ? withUnit(yNames[0]) : yNames.map((n) => unitOf(n) || "–").filter((u, i, all) => all.indexOf(u) === i).join(", "),
      log_x: false, log_y: false, series, description,
    });
    summary.textContent = description;
  }
  xPick.addEventListener("change", () => { chosen.x = xPick.value; renderGraph(); });
  windowPick.addEventListener("change", renderGraph);
  yPicks.forEach((select, i) => select.addEventListener("change", () => { chosen.y[i] = select.value; renderGraph(); }));

  // ---- polling: only while open, visible and the session has a scene ------------------------------------------
  let ready = false, timer = null, inFlight = false;
  const wanted = () => own && ready && section.open && !document.hidden;
  function pollIn(ms) {
    clearTimeout(timer);
    timer = null;
    if (wanted() && !inFlight) timer = setTimeout(poll, ms);
  }
  async function poll() {
    timer = null;
    if (!wanted() || inFlight) return;
    inFlight = true;
    let delay = RETRY_MS;
    try {
      const query = new URLSearchParams({ max_points: "600" });
      if (lastT !== null) query.set("since_s", String(lastT - SAME_FRAME_S / 2)); // the last frame again: see receive()
      const response = await fetch(`${base}/graph?${query}`);
      if (response.ok) delay = receive(await response.json());
      // 404: the viewer is (re)connecting and the session has no scene for a moment; try again later.
    } catch (e) { /* the next poll retries */ }
    inFlight = false;
    pollIn(delay);
  }
  section.addEventListener("toggle", () => pollIn(0));
  document.addEventListener("visibilitychange", () => pollIn(0));
  // The first live readout proves the session has its scene: before it a graph request would only 404.
  document.addEventListener("dynlab:live", () => {
    if (ready) return;
    ready = true;
    if (scene.integrated) pollIn(0);
    else probe();
  });
  // An integrated scene always has graphs; another animated scene shows the section only if the server graphs it.
  async function probe() {
    try {
      const response = await fetch(`${base}/graph?max_points=10`);
      const data = response.ok ? await response.json() : null;
      if (data && data.quantities && data.quantities.length) { probed = true; section.hidden = !own; pollIn(0); }
    } catch (e) { /* no graphs for this scene */ }
  }
  let probed = false; // an animated scene that is not integrated: whether the server graphs it
  section.hidden = !own || !scene.integrated;
  document.addEventListener("dynlab:own-scene", (event) => {
    own = event.detail.own;
    ready = false; // the own copy is a new run: wait for its first live readout
    clearStore();
    section.hidden = !own || !(scene.integrated || probed);
    pollIn(0);
  });
})();
