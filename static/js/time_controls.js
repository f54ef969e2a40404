// Time controls under an animated scene: play/pause, one step, restart, speed, a scrubber over the motion the
// server keeps (the last 60 s, replayed from stored states), and a share link that restores parameters, time,
// play state and camera in another browser. Keys (outside text boxes): space plays or pauses, ← / → step back
// or forward one frame while paused.
import { config } from "./config.js";
import { element as el } from "./dom.js";
import { lesson } from "./lesson.js";

(function () {
  if (!lesson || !lesson.scene || !lesson.scene.animated) return;
  const params = new URLSearchParams(location.search);
  // In a room the play state is the instructor's (room.js), except while a student explores their own copy.
  const inRoom = params.has("room");
  const scene = lesson.scene;
  const session = lesson.session;
  const FRAME_S = 1 / 30;
  const SPEEDS = config.time_scales;

  // ---- the bar -----------------------------------------------------------------------------------------------
  const play = el("button", { type: "button", class: "tc-play", "aria-label": "Pause" }, "❚❚ Pause");
  const step = el("button", { type: "button", class: "tc-step", title: "One frame forward (→)", "aria-label": "Step one frame forward" }, "Step ▸");
  const restart = el("button", { type: "button", class: "tc-reset", "aria-label": "Restart from t = 0" }, "⟲ Restart");
  const speed = el("select", { class: "tc-speed", "aria-label": "Speed (× real time)" });
  for (const s of SPEEDS) speed.add(new Option(`${s}×`, String(s)));
  speed.value = "1";
  const scrub = el("input", { type: "range", class: "tc-scrub", min: "0", max: "0", step: String(FRAME_S), value: "0", "aria-label": "Time: scrub through the last 60 s" });
  const clock = el("output", { class: "tc-time", "aria-live": "off" }, "t = 0.00 s");
  const share = el("button", { type: "button", class: "tc-share" }, "Share link");
  const shareBox = el("input", { type: "text", class: "tc-share-url", readonly: "", "aria-label": "Share link", hidden: "" });
  const error = el("p", { class: "tc-error error", role: "alert", hidden: "" });
  // The server says when this scene runs slower than chosen, to keep within this device's share of a busy server.
  const slowed = el("p", { class: "tc-slowed", role: "status", hidden: "" });
  const bar = el("div", { class: "time-controls", role: "group", "aria-label": "Time controls" },
    play, step, restart, el("label", { class: "tc-speed-label" }, "Speed ", speed), scrub, clock, share, shareBox, slowed, error);
  const wrap = document.getElementById("viewer-wrap");
  wrap.after(bar);
  if (inRoom) {
    bar.hidden = true;
    document.addEventListener("dynlab:own-scene", (event) => {
      bar.hidden = !event.detail.own;
      error.hidden = true;
      shareBox.hidden = true;
    });
  }

  // ---- state, from the server's answers and the live readout ----------------------------------------------------
  let state = { playing: true, time_scale: 1, t_s: 0, history_s: null };
  let shownAt = performance.now();
  let scrubbing = false;
  function show(next) {
    state = { ...state, ...next, slowed: next.slowed || null };
    shownAt = performance.now();
    slowed.hidden = !state.slowed;
    slowed.textContent = state.slowed ? state.slowed.note : "";
    play.textContent = state.playing ? "❚❚ Pause" : "▶ Play";
    play.setAttribute("aria-label", state.playing ? "Pause" : "Play");
    play.dataset.playing = String(state.playing);
    speed.value = String(state.time_scale);
    if (state.history_s) {
      scrub.min = String(state.history_s[0]);
      scrub.max = String(state.history_s[1]);
    }
    if (!scrubbing && state.t_s !== null && state.t_s !== undefined) scrub.value = String(state.t_s);
    clock.dataset.t = String(state.t_s);
    tick();
  }
  function tick() {
    // Between answers the clock runs on at the time scale while playing (the server's frames do the same).
    const rate = state.time_scale * (state.slowed ? state.slowed.rate : 1);
    const t = state.t_s === null || state.t_s === undefined ? 0 : state.t_s + (state.playing ? rate * (performance.now() - shownAt) / 1000 : 0);
    clock.textContent = `t = ${t.toFixed(2)} s`;
  }
  setInterval(tick, 100);
  // A readout poll asked before the last change was answered may carry the state from before it: it is not shown
  // (otherwise a quick Play then Pause, or a poll landing between them, would send "play" twice).
  let changing = 0;
  let changedAt = -Infinity;
  document.addEventListener("dynlab:live", (event) => {
    const live = event.detail;
    if (!live || !live.playback || changing > 0 || !(live.askedAtMs > changedAt)) return;
    show(live.playback);
  });

  // Changes go to the server one at a time, in the order they were made.
  let queue = Promise.resolve();
  function send(body) {
    changing += 1;
    const answered = queue.then(async () => {
      try {
        const data = await lesson.setPlayback(body);
        error.hidden = true;
        show(data);
        return data;
      } catch (err) {
        error.textContent = err.message;
        error.hidden = false;
        return null;
      } finally {
        changing -= 1;
        changedAt = performance.now();
      }
    });
    queue = answered;
    return answered;
  }
  // Play and pause take effect on the button at once, so a second press undoes the first even before the server's
  // answer; the answer then shows what the server did.
  function togglePlaying() {
    const playing = !state.playing;
    state = { ...state, playing };
    play.textContent = playing ? "❚❚ Pause" : "▶ Play";
    play.setAttribute("aria-label", playing ? "Pause" : "Play");
    send({ playing });
  }
  play.addEventListener("click", togglePlaying);
  step.addEventListener("click", () => send({ step: 1 }));
  restart.addEventListener("click", () => send({ reset: true }));
  speed.addEventListener("change", () => send({ time_scale: Number(speed.value) }));
  scrub.addEventListener("input", () => { scrubbing = true; });
  scrub.addEventListener("change", async () => { await send({ seek_s: Number(scrub.value) }); scrubbing = false; });
  document.addEventListener("keydown", (event) => {
    if (bar.hidden) return; // following in a room: the keys are not this page's to use
    const target = event.target;
    if (target && (target.closest("input, select, textarea, [contenteditable]") || target.isContentEditable)) return;
    const onButton = target && target.closest("button, a, summary");
    if (event.key === " " && !onButton) { event.preventDefault(); togglePlaying(); } // a focused button takes its own space
    else if (event.key === "ArrowRight" && !state.playing) { event.preventDefault(); send({ step: 1 }); }
    else if (event.key === "ArrowLeft" && !state.playing && state.history_s) {
      event.preventDefault();
      send({ seek_s: Math.max(state.history_s[0], (state.t_s || 0) - FRAME_S) });
    }
  });

  // ---- share links -----------------------------------------------------------------------------------------------
  share.addEventListener("click", async () => {
    const now = await fetch(`/api/scenes/${scene.id}/sessions/${session.id}/playback`).then((r) => (r.ok ? r.json() : null)).catch(() => null);
    if (now) show(now);
    const url = new URL(location.pathname, location.origin);
    if (params.has("scene")) url.searchParams.set("scene", params.get("scene"));
    const changed = Object.fromEntries(Object.entries(session.values).filter(([k, v]) => JSON.stringify(v) !== JSON.stringify(lesson.defaults[k])));
    if (Object.keys(changed).length) url.searchParams.set("params", JSON.stringify(changed));
    url.searchParams.set("t", (state.t_s || 0).toFixed(4));
    url.searchParams.set("playing", state.playing ? "1" : "0");
    if (state.time_scale !== 1) url.searchParams.set("speed", String(state.time_scale));
    if (now && now.camera) url.searchParams.set("camera", [...now.camera.position, ...now.camera.look_at].map((v) => +v.toFixed(4)).join(","));
    shareBox.value = url.toString();
    shareBox.hidden = false;
    shareBox.select();
    try { await navigator.clipboard.writeText(shareBox.value); share.textContent = "Link copied"; } catch (e) { share.textContent = "Share link"; }
  });

  // Opened from a share link: once the page's session exists, go to the shared time, play state, speed and camera,
  // and only then let the viewer open (lesson.holdViewer), so its scene starts at the shared instant.
  const shared = lesson.shared;
  if (shared) {
    lesson.holdViewer(new Promise((resolve) => document.addEventListener("dynlab:viewer-started", () => {
      const body = { go_to_s: shared.t_s, playing: shared.playing };
      if (shared.time_scale) body.time_scale = shared.time_scale;
      if (shared.camera) body.camera = shared.camera;
      send(body).then(resolve);
    }, { once: true })));
  }
})();

// "Save recording": the last few seconds the viewer showed (a still for a scene without motion), as one HTML file
// that plays offline in any browser, for walkthroughs and for preparing a class. Beside the time controls.
(function () {
  if (!lesson || !lesson.scene) return;
  const scene = lesson.scene;
  const session = lesson.session;
  const group = el("div", { class: "recording-controls", role: "group", "aria-label": "Save a recording" });
  // A room's scene is the instructor's: a student records only their own copy, while exploring (room.js).
  if (new URLSearchParams(location.search).has("room")) {
    group.hidden = true;
    document.addEventListener("dynlab:own-scene", (event) => { group.hidden = !event.detail.own; });
  }
  const save = el("button", { type: "button", class: "rec-save", text: scene.animated ? "Save recording" : "Save recording (a still)" });
  const seconds = el("select", { class: "rec-seconds", "aria-label": "Recording length: the last seconds shown" });
  for (const s of [5, 10, 30, 60]) seconds.add(new Option(`last ${s} s`, String(s)));
  seconds.value = "10";
  seconds.hidden = !scene.animated;
  const status = el("span", { class: "rec-status", role: "status", text: "One HTML file that plays offline in any browser, with no server." });
  group.append(save, seconds, status);
  (document.querySelector(".time-controls") || document.getElementById("viewer-wrap")).after(group);

  save.addEventListener("click", async () => {
    const name = `${scene.id}-recording.html`;
    save.disabled = true;
    status.textContent = "preparing…";
    status.dataset.state = "preparing";
    try {
      const response = await fetch(`/api/scenes/${scene.id}/sessions/${session.id}/recording.html?seconds=${seconds.value}`);
      if (!response.ok) {
        const data = await response.json().catch(() => ({}));
        throw new Error(Array.isArray(data.detail) ? data.detail[0].msg : data.detail || response.statusText);
      }
      const blob = await response.blob();
      const link = document.createElement("a");
      link.href = URL.createObjectURL(blob);
      link.download = name;
      document.body.append(link);
      link.click();
      link.remove();
      setTimeout(() => URL.revokeObjectURL(link.href), 60000);
      status.textContent = `Saved ${name} (${(blob.size / 2 ** 20).toFixed(1)} MB): open it in any browser, offline.`;
      status.dataset.state = "saved";
    } catch (e) {
      status.textContent = `The recording could not be made: ${e.message}`;
      status.dataset.state = "error";
    } finally {
      save.disabled = false;
    }
  });
})();
