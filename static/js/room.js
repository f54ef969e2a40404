// Classroom mode of a lesson page (?room=<room_id>): a student follows the instructor's room (controls locked,
// the room's one shared scene in the viewer, its readout from the room socket) or explores their own copy;
// the instructor's page drives the room and shows the instructor panel, the students and the polls.
// An instructor page on another lesson or scene than the room's follows the room there (a second or stale tab never
// moves the class); the class moves only when the instructor chooses it: the previous/next and scene links, or
// "Show … to the class". Every change the page sends names the lesson and scene it shows (if_lesson_id,
// if_scene_id): once the room has moved on, the server refuses it (409) instead of applying it to another scene.
// Without ?room the page is a plain lesson; the instructor only gets a button to open a room on it.
// `classroom` is this page's place in its room once it has one (null before): the browser tests read it by importing
// this module, and drive the room through its socket with `send`.
import { api } from "./api.js";
import { config } from "./config.js";
import { element as el } from "./dom.js";
import { formatNumber } from "./format.js";
import { lesson } from "./lesson.js"; // null on a lesson page without a scene or examples
import { instructorAssignment, studentAssignment, studentToken as savedStudentToken } from "./room_practice.js";
import { reconnectingSocket } from "./socket.js";

export let classroom = null;

(function () {
  const query = new URLSearchParams(location.search);
  const roomId = query.get("room");
  const pageScene = config.scene ? config.scene.id : null;
  const aside = document.querySelector(".lesson-live");
  if (!aside) return;

  const THROTTLE_MS = 67; // about 15 changes a second while a slider is dragged; the last value is always sent
  const FOLLOW_TEXT = "Following the instructor — the controls show what the class sees";
  const EXPLORE_TEXT = "Exploring on your own — the instructor can bring everyone back";

  const fmt = (v) => (typeof v === "number" ? formatNumber(v, { digits: 4, large: Infinity, small: 0 }) : String(v));
  const scaleText = (s) => `${fmt(s)}×`;
  const announce = (message) => document.dispatchEvent(new CustomEvent("dynlab:room", { detail: message }));
  const roomPage = (lessonId, sceneId, extra) =>
    `/lessons/${encodeURIComponent(lessonId)}?room=${roomId}` + (sceneId ? `&scene=${encodeURIComponent(sceneId)}` : "") + (extra || "");

  // ---- the room socket: reconnects by the page's one rule when it drops (a phone that slept) ------------------
  function roomSocket({ onOpen, onMessage, onGone }) {
    let gone = false;
    return reconnectingSocket(`/api/rooms/${roomId}/socket`, {
      onOpen,
      onMessage(message) {
        if (message.type === "closed") { gone = true; onGone("The instructor closed this room."); }
        if (message.type === "removed") { gone = true; onGone(message.detail || "The instructor removed you from this room.", { removed: true }); }
        onMessage(message);
        announce(message);
      },
      onClose(event) {
        if (gone) return false;
        if (event.code === 1008) { gone = true; onGone("This room is not open any more (closed, or the server restarted)."); return false; }
        return true;
      },
    });
  }

  // ---- what both sides show: the play status, the room's readout, a room that has gone --------------
  function playStatus(state, who) {
    if (!state.playing) return `❚❚ paused by ${who} · ${scaleText(state.time_scale)}`;
    return `▶ playing · ${scaleText(state.time_scale)}`;
  }
  function showReadout(message) {
    if (!lesson || message.scene_id !== pageScene || !message.data) return;
    if (message.data.readout) lesson.renderReadout(message.data.readout);
    lesson.renderLive(message.data);
  }
  function goneNotice(text, { removed = false } = {}) {
    // A removed device cannot join this room again: no link back to joining, and the room's scene is no longer shown.
    const note = el("p", { class: "room-gone error", role: "alert" }, removed ? text : `${text} `, removed ? "" : el("a", { href: "/join", text: "Join a room" }));
    aside.prepend(note);
    if (lesson) lesson.lock(true, text);
    if (removed) {
      const viewer = document.getElementById("viewer-wrap");
      if (viewer) { document.getElementById("viewer").src = "about:blank"; viewer.hidden = true; }
      for (const line of document.querySelectorAll(".room-status, .room-banner")) line.textContent = "";
    }
  }

  fetch("/api/me")
    .then((response) => response.json())
    .then(({ role }) => {
      if (!roomId) { if (role === "instructor") offerRoom(); return; }
      if (!/^[0-9a-f]{16}$/.test(roomId)) { goneNotice("This room link is not valid."); return; }
      if (role === "instructor" && query.get("as") !== "student") instructorPage();
      else studentPage(role === "instructor");
    })
    .catch(() => { /* offline: the page stays a plain lesson */ });

  // ---- an instructor on a plain lesson page: open a room here -----------------------------------------
  function offerRoom() {
    const button = el("button", { type: "button", text: "Start a class room here" });
    const error = el("p", { class: "error", role: "alert", hidden: true });
    const box = el("section", { class: "room-start", "aria-label": "Class room" }, button,
      el("p", { class: "muted", text: "Students join with a code or a QR code and see this lesson's scene as you drive it." }), error);
    aside.prepend(box);
    button.addEventListener("click", async () => {
      button.disabled = true;
      try {
        const room = await api("POST", "/api/rooms", { lesson_id: config.lesson_id, scene_id: pageScene });
        location.assign(`/lessons/${encodeURIComponent(config.lesson_id)}?room=${room.room_id}` + (pageScene ? `&scene=${encodeURIComponent(pageScene)}` : ""));
      } catch (err) {
        error.textContent = `Could not open a room: ${err.message}`;
        error.hidden = false;
        button.disabled = false;
      }
    });
  }

  // While a student explores, the scene in the viewer is their own: the page's time controls, recording and graphs
  // (time_controls.js, graphs.js) then work on it; following, they are hidden (the class's scene is the instructor's).
  const ownScene = (own) => document.dispatchEvent(new CustomEvent("dynlab:own-scene", { detail: { own } }));

  // ---- a student (or the instructor previewing as one) ----------------------------------------------------
  const studentToken = () => savedStudentToken(roomId);

  function studentPage(preview) {
    const token = preview ? null : studentToken();
    if (!preview && !token) { location.replace("/join"); return; }
    const extra = preview ? "&as=student" : "";
    const banner = el("p", { class: "room-banner", text: "Connecting to the room…" });
    const status = el("p", { class: "room-status", "aria-live": "polite" });
    const error = el("p", { class: "room-error error", role: "alert", hidden: true });
    const bar = el("section", { class: "room-bar", "aria-label": "Class room" }, banner, status, error);
    if (preview) bar.append(el("p", { class: "muted", text: "Preview: this is what a student sees (your changes here are not sent)." }));
    const poll = studentPoll(token, preview);
    const practice = studentAssignment(roomId);
    aside.prepend(bar, poll.element, practice.element);
    let mode = null, latest = null, shownParams = "";

    const socket = roomSocket({
      onOpen: () => socket.send({ type: "hello", student_token: token || undefined, following: mode !== "explore" }),
      onMessage,
      onGone: goneNotice,
    });
    classroom = { roomId, role: "student", send: (m) => socket.send(m), state: () => latest };
    if (lesson && !pageScene) lesson.schedule(); // worked examples only: the room has no scene to follow

    function showError(text) {
      error.textContent = text;
      error.hidden = !text;
    }
    function onMessage(message) {
      if (message.type === "state") onState(message.state);
      else if (message.type === "readout" && mode === "follow") showReadout(message);
      else if (message.type === "removed") {
        localStorage.removeItem(`dynlab.room.${roomId}`);
        poll.element.hidden = true;
        practice.element.hidden = true;
        bar.hidden = true;
      } else if (message.type === "error") {
        if (message.status === 403 && !message.action && token) { // the room does not know this token: join again
          localStorage.removeItem(`dynlab.room.${roomId}`);
          location.replace("/join");
          return;
        }
        showError(message.detail);
      }
    }
    let leaving = false;
    function onState(state) {
      latest = state;
      if (leaving) return; // going to the room's new page: a second navigation would abort the first
      if (state.lesson_id && (state.lesson_id !== config.lesson_id || (state.scene_id && state.scene_id !== pageScene))) {
        leaving = true;
        location.replace(roomPage(state.lesson_id, state.scene_id, extra));
        return;
      }
      status.textContent = state.lesson_id ? playStatus(state, "the instructor") : "Waiting for the instructor to choose a lesson";
      status.dataset.playing = String(state.playing);
      poll.render(state.poll);
      practice.render(state.assignment);
      if (!lesson || !pageScene) { banner.textContent = "Following the instructor"; return; }
      if (state.mode === "explore" && state.explore_start) explore(state);
      else follow(state);
    }
    function follow(state) {
      if (mode !== "follow") {
        const back = mode === "explore";
        mode = "follow";
        lesson.onChange(() => {}); // the page never sends its own session while following
        lesson.stopPolling();
        lesson.lock(true, "Locked while you follow the instructor");
        lesson.showViewer(`/room-viewer/${roomId}/?hideViserLogo`);
        banner.textContent = FOLLOW_TEXT;
        bar.dataset.mode = "follow";
        ownScene(false);
        if (back) socket.send({ type: "following", value: true });
      }
      const params = JSON.stringify(state.params);
      if (params !== shownParams) {
        shownParams = params;
        lesson.setValues(state.params);
        if (config.examples.length) lesson.schedule(); // the worked solution for the class's values
      }
    }
    async function explore(state) {
      if (mode === "explore" || mode === "starting") return;
      mode = "starting";
      banner.textContent = "Starting your own copy of the scene…";
      if (preview) {
        mode = "explore";
        banner.textContent = `${EXPLORE_TEXT} (the preview stays on the class's scene)`;
        return;
      }
      socket.send({ type: "following", value: false });
      try {
        const reply = await api("PUT", `/api/scenes/${pageScene}/sessions/${lesson.session.id}`,
          { params: state.explore_start.params, from_room: roomId }, { "X-Session-Key": lesson.session.key });
        if (latest.mode !== "explore") { mode = null; follow(latest); return; } // brought back meanwhile
        mode = "explore";
        shownParams = "";
        lesson.onChange(null);
        lesson.setValues(reply.params);
        lesson.lock(false);
        lesson.showViewer(lesson.ownViewer);
        lesson.startPolling();
        banner.textContent = EXPLORE_TEXT;
        bar.dataset.mode = "explore";
        ownScene(true);
        showError("");
      } catch (err) {
        mode = null;
        showError(`Could not start your own scene: ${err.message}`);
        follow(latest);
      }
    }
  }

  // The current poll on a student's page: the question, choices or a number box, and their answer.
  function studentPoll(token, preview) {
    const element = el("section", { class: "room-poll", "aria-label": "Question from the instructor", hidden: true });
    const answersKey = `dynlab.room.${roomId}.answers`;
    let shown = null, parts = null;
    const saved = () => { try { return JSON.parse(localStorage.getItem(answersKey)) || {}; } catch (e) { return {}; } };

    function build(poll) {
      const name = `poll-${poll.poll_id}`;
      const send = el("button", { type: "button", class: "room-poll-send", text: "Send" });
      const mine = el("p", { class: "room-poll-mine", "aria-live": "polite" });
      const note = el("p", { class: "room-poll-state muted" });
      const revealed = el("p", { class: "room-poll-revealed", hidden: true });
      const inputs = [];
      let field;
      if (poll.kind === "choice") {
        field = el("fieldset", { class: "room-poll-choices" }, el("legend", { text: poll.question }));
        poll.choices.forEach((choice, index) => {
          const radio = el("input", { type: "radio", name, value: String(index), id: `${name}-${index}` });
          inputs.push(radio);
          field.append(el("label", { for: radio.id }, radio, ` ${choice}`));
        });
      } else {
        const box = el("input", { type: "number", step: "any", id: `${name}-value`, inputmode: "decimal" });
        inputs.push(box);
        field = el("div", { class: "room-poll-number" },
          el("label", { for: box.id, class: "room-poll-question", text: poll.question }),
          el("span", {}, box, el("span", { class: "unit", text: ` ${poll.unit}` })));
      }
      element.replaceChildren(el("h2", { text: "Predict" }), field, send, mine, note, revealed);
      const parts = { inputs, send, note, revealed, answer: saved()[poll.poll_id] || "" };
      parts.showAnswer = () => {
        if (parts.answer) mine.textContent = `Your answer: ${parts.answer}` + (shown && !shown.open ? "" : " (you can change it until the poll closes)");
      };
      parts.showAnswer();
      if (preview) { send.disabled = true; note.textContent = "Preview: students answer here; answers from this page are not counted."; }
      send.addEventListener("click", async () => {
        let body, text;
        if (poll.kind === "choice") {
          const picked = inputs.find((radio) => radio.checked);
          if (!picked) { mine.textContent = "Pick one of the choices first."; return; }
          body = { choice: Number(picked.value) };
          text = poll.choices[body.choice];
        } else {
          const value = Number(inputs[0].value);
          if (inputs[0].value === "" || !Number.isFinite(value)) { mine.textContent = `Type a number in ${poll.unit || "the poll's unit"} first.`; return; }
          body = { value };
          text = `${fmt(value)} ${poll.unit}`.trim();
        }
        send.disabled = true;
        try {
          await api("POST", `/api/rooms/${roomId}/polls/${poll.poll_id}/answers`, body, { "X-Student-Token": token });
          parts.answer = text;
          parts.showAnswer();
          localStorage.setItem(answersKey, JSON.stringify({ ...saved(), [poll.poll_id]: text }));
        } catch (err) {
          mine.textContent = `Not sent: ${err.message}`;
        } finally {
          send.disabled = !(shown && shown.open) || preview;
        }
      });
      return parts;
    }

    return {
      element,
      render(poll) {
        element.hidden = !poll;
        if (!poll) { shown = null; return; }
        if (!shown || shown.poll_id !== poll.poll_id) parts = build(poll);
        shown = poll;
        for (const input of parts.inputs) input.disabled = !poll.open;
        parts.send.disabled = !poll.open || preview;
        if (!preview) parts.note.textContent = poll.open ? "" : "The poll is closed.";
        parts.showAnswer();
        parts.revealed.hidden = !poll.revealed;
        if (poll.revealed) parts.revealed.textContent = `Answer: ${poll.revealed.text} — ${poll.revealed.source}`;
      },
    };
  }

  // ---- the instructor's page: it drives the room -------------------------------------------------------------
  function instructorPage() {
    // What this page shows: every change it sends carries it, so a change from a page the room has left is refused.
    const shows = { if_lesson_id: config.lesson_id, if_scene_id: pageScene };
    // Opened on another lesson than the room's, this tab went to the room's and offers to show that lesson instead.
    const came = { lesson: query.get("from"), scene: query.get("from_scene") };
    if (came.lesson) {
      const clean = new URL(location.href);
      clean.searchParams.delete("from");
      clean.searchParams.delete("from_scene");
      history.replaceState(history.state, "", clean.pathname + clean.search); // a reload does not offer it again
    }
    const panel = instructorPanel();
    // A column of its own beside the scene's (static/css/classroom.css): at 1366×768 the scene and the panel are in
    // view together; on a phone it comes first, as it did inside the scene's column.
    aside.after(panel.element);
    let latest = null, inStep = false, leaving = false, lastLocal = 0, pendingApply = null, shownParams = "";
    let pendingParams = {}, lastSent = 0, flushTimer = null;

    const socket = roomSocket({ onOpen: () => panel.connected(true), onMessage, onGone: goneNotice });
    classroom = { roomId, role: "instructor", send: (m) => socket.send(m), state: () => latest };
    if (lesson && !pageScene) lesson.schedule(); // worked examples only: the room has no scene to drive
    const send = (message) => {
      if (message.type === "set_state" && !("if_lesson_id" in message)) Object.assign(message, shows);
      if (!socket.send(message)) panel.error("Not connected to the room: reconnecting, try again in a moment.");
      else panel.sent();
    };
    panel.onAction(send);
    // Moving the class: its state comes back on the socket, and every page in the room (this one too) goes there.
    const moveClass = (lessonId, sceneId, conditions) =>
      send({ type: "set_state", lesson_id: lessonId, scene_id: sceneId || undefined, ...(conditions || shows) });
    panel.onMove(moveClass);

    // The previous/next and scene links move the class (the instructor chose to); one opened in a new tab only opens.
    for (const link of document.querySelectorAll(".prevnext a, .scene-picker a")) {
      const url = new URL(link.href, location.href);
      url.searchParams.set("room", roomId);
      link.href = url.pathname + url.search;
      const target = decodeURIComponent(url.pathname.replace(/^\/lessons\//, ""));
      link.addEventListener("click", (event) => {
        if (event.button !== 0 || event.metaKey || event.ctrlKey || event.shiftKey || event.altKey) return;
        event.preventDefault();
        moveClass(target, url.searchParams.get("scene"));
      });
    }

    if (lesson && pageScene) {
      lesson.stopPolling();
      lesson.showViewer(`/room-viewer/${roomId}/?hideViserLogo`);
      lesson.onChange((changed, how) => {
        lastLocal = Date.now();
        if (how.preset) { send({ type: "set_state", preset: how.preset }); return; }
        if (how.reset) { pendingParams = {}; send({ type: "set_state", params: { ...lesson.defaults } }); return; }
        Object.assign(pendingParams, changed);
        const wait = lastSent + THROTTLE_MS - Date.now();
        if (wait <= 0) flush();
        else if (!flushTimer) flushTimer = setTimeout(flush, wait);
      });
    }
    function flush() {
      clearTimeout(flushTimer);
      flushTimer = null;
      if (!Object.keys(pendingParams).length) return;
      lastSent = Date.now();
      send({ type: "set_state", params: pendingParams });
      pendingParams = {};
    }

    function onMessage(message) {
      if (message.type === "state") onState(message.state);
      else if (message.type === "readout") showReadout(message);
      else if (message.type === "results") panel.results(message.results);
      else if (message.type === "students") panel.students(message.students);
      else if (message.type === "error" && message.status === 409 && message.action === "set_state") { // sent from a scene the room had left
        panel.error("Nothing was changed: the class had already moved on to another lesson or scene, and this tab follows it.");
      } else if (message.type === "error") panel.error(message.detail);
    }
    function onState(state) {
      latest = state;
      if (leaving) return; // going to the room's lesson: a second navigation would abort the first
      panel.state(state);
      if (!state.lesson_id) { // the class sees no lesson yet: this page may show it
        panel.offer(config.lesson_id, pageScene, "The class sees no lesson yet.", { if_lesson_id: null, if_scene_id: null });
        return;
      }
      const here = state.lesson_id === config.lesson_id && state.scene_id === pageScene;
      if (!here) {
        // Follow the room: a second tab, or one left behind, never drives an old lesson. A tab opened on another
        // lesson says which, so the room's page can offer to show it to the class.
        leaving = true;
        const from = inStep ? "" : `&from=${encodeURIComponent(config.lesson_id)}` + (pageScene ? `&from_scene=${encodeURIComponent(pageScene)}` : "");
        location.replace(roomPage(state.lesson_id, state.scene_id, from));
        return;
      }
      inStep = true;
      if (came.lesson && (came.lesson !== config.lesson_id || (came.scene || null) !== pageScene)) {
        panel.offer(came.lesson, came.scene, "This tab was opened on another lesson. The class is on this one, so the tab came here.");
      } else panel.offer(null);
      if (lesson && pageScene) applyParams();
    }
    function applyParams() {
      // An echo of an older value must not pull a slider back while it is being dragged: wait for a pause.
      const quiet = Date.now() - lastLocal;
      if (quiet < 400 || Object.keys(pendingParams).length) {
        if (!pendingApply) pendingApply = setTimeout(() => { pendingApply = null; applyParams(); }, Math.max(50, 400 - quiet));
        return;
      }
      const params = JSON.stringify(latest.params);
      if (params === shownParams) return;
      shownParams = params;
      lesson.setValues(latest.params);
      if (config.examples.length) lesson.schedule();
    }
  }

  // A lesson's title (from the course outline), to name it in words; its id if the outline cannot be read.
  let outline = null;
  async function lessonTitle(lessonId, sceneId) {
    if (lessonId === config.lesson_id) {
      const link = [...document.querySelectorAll(".scene-picker a")].find((a) => new URL(a.href, location.href).searchParams.get("scene") === sceneId);
      if (link) return link.textContent.trim();
    }
    try {
      outline = outline || await api("GET", "/api/chapters");
      for (const chapter of outline) {
        const found = (chapter.lessons || []).find((l) => l.id === lessonId);
        if (found) return `${found.section} ${found.title}`;
      }
    } catch (e) { /* offline: the id says enough */ }
    return lessonId;
  }

  // The instructor panel: how to join, who is here, playback for everyone, follow or explore, the students, the polls.
  function instructorPanel() {
    let act = () => {}, move = () => {}, current = null;
    const button = (text, name) => el("button", { type: "button", "data-room": name, text });
    const code = el("p", { class: "room-code", "aria-label": "Room code" });
    const joinUrl = el("a", { class: "room-join-url" });
    const qr = el("img", { class: "room-qr", src: `/api/rooms/${roomId}/qr.svg`, alt: "QR code of the join address", width: 112, height: 112 });
    const presence = el("p", { class: "room-presence", "aria-live": "polite" });
    const status = el("p", { class: "room-status", "aria-live": "polite" });
    const play = button("❚❚ Pause", "play");
    const restart = button("⟲ Restart", "restart");
    const scale = el("select", { id: "room-time-scale" }, ...config.time_scales.map((s) => new Option(scaleText(s), String(s))));
    const mode = button("Let everyone explore", "mode");
    const error = el("p", { class: "room-error error", role: "alert", hidden: true });
    const offerBox = el("div", { class: "room-offer", role: "status", hidden: true });
    const preview = new URL(location.href);
    preview.searchParams.set("as", "student");
    const polls = instructorPolls((message) => act(message), () => clearErrors());
    const students = instructorStudents((text) => showError(text));
    const practice = instructorAssignment(roomId, (text) => showError(text));
    const element = el("aside", { class: "room-panel", "aria-label": "Class room: instructor" },
      el("div", { class: "room-join" }, qr,
        el("div", {}, el("p", { class: "room-code-label", text: "Join with the code" }), code,
          el("p", { class: "room-join-line" }, "or open ", joinUrl))),
      offerBox, presence, status,
      el("div", { class: "room-buttons", role: "group", "aria-label": "Playback for everyone" }, play, restart,
        el("label", { for: "room-time-scale", text: "Time scale " }), scale, mode),
      el("p", { class: "room-links" },
        el("a", { href: `/rooms/${roomId}/projector`, target: "_blank", rel: "noopener", text: "Projector view" }), " · ",
        el("a", { href: preview.pathname + preview.search, target: "_blank", rel: "noopener", text: "Preview as a student" })),
      error, students.element, polls.element, practice.element);
    play.addEventListener("click", () => current && act({ type: "set_state", playing: !current.playing }));
    restart.addEventListener("click", () => act({ type: "set_state", reset: true }));
    scale.addEventListener("change", () => act({ type: "set_state", time_scale: Number(scale.value) }));
    mode.addEventListener("click", () => current && act({ type: "set_state", mode: current.mode === "follow" ? "explore" : "follow" }));
    // An error stays until it is stale: 10 s, or a later action that the room took (its state comes back with a
    // higher revision than when the action was sent); the own-question form's error goes too.
    let errorTimer = null, sentAt = null;
    function showError(text) {
      sentAt = null; // the action this answers was refused: only a later one can clear it
      error.textContent = text;
      error.hidden = false;
      clearTimeout(errorTimer);
      errorTimer = setTimeout(() => { error.hidden = true; }, 10000);
    }
    function clearErrors() {
      error.hidden = true;
      polls.clearError();
    }
    return {
      element,
      onAction(fn) { act = fn; },
      onMove(fn) { move = fn; },
      connected() { error.hidden = true; },
      error: showError,
      sent() { sentAt = current ? current.revision : -1; },
      results: polls.results,
      students: students.render,
      // "Show … to the class": the instructor's explicit choice to move the class to a lesson (or scene).
      async offer(lessonId, sceneId, why, conditions) {
        if (!lessonId) { offerBox.hidden = true; delete offerBox.dataset.lesson; return; } // nothing to offer (any more)
        if (offerBox.dataset.lesson === `${lessonId}/${sceneId || ""}`) return;
        offerBox.dataset.lesson = `${lessonId}/${sceneId || ""}`;
        const title = await lessonTitle(lessonId, sceneId);
        const show = el("button", { type: "button", "data-room": "show-lesson", text: `Show “${title}” to the class` });
        const dismiss = el("button", { type: "button", class: "room-offer-dismiss", text: "Not now" });
        show.addEventListener("click", () => { show.disabled = true; move(lessonId, sceneId, conditions); });
        dismiss.addEventListener("click", () => { offerBox.hidden = true; });
        offerBox.replaceChildren(el("p", { text: why }), el("div", { class: "room-buttons" }, show, dismiss));
        offerBox.hidden = false;
      },
      state(state) {
        current = state;
        if (sentAt !== null && state.revision > sentAt) { sentAt = null; clearErrors(); } // a later action was taken
        code.textContent = state.code;
        joinUrl.textContent = state.join_url;
        joinUrl.href = state.join_url;
        const { connected, following } = state.students;
        students.count(state.students.joined);
        presence.textContent = `${connected} connected · ${following} following`;
        presence.dataset.connected = String(connected);
        presence.dataset.following = String(following);
        status.textContent = playStatus(state, "you, for everyone");
        status.dataset.playing = String(state.playing);
        play.textContent = state.playing ? "❚❚ Pause" : "▶ Play";
        if (![...scale.options].some((o) => Number(o.value) === state.time_scale)) scale.add(new Option(scaleText(state.time_scale), String(state.time_scale)));
        scale.value = [...scale.options].find((o) => Number(o.value) === state.time_scale).value;
        mode.textContent = state.mode === "follow" ? "Let everyone explore" : "Bring everyone back";
        element.dataset.mode = state.mode;
        polls.state(state);
        practice.state(state);
      },
    };
  }

  // The students in the room, for the instructor: each by the name they gave (or their number), connected or not, and
  // a button that removes one (their answers leave the results and their device cannot join this room again).
  function instructorStudents(showError) {
    const summary = el("summary", { text: "Students (0)" });
    const list = el("ul", { class: "room-student-list" });
    const empty = el("p", { class: "muted", text: "Nobody has joined yet." });
    const element = el("details", { class: "room-students" }, summary, empty, list);
    const label = (s) => s.name || `Student ${s.student_id.slice(1)} (no name)`;
    async function remove(student, button) {
      if (!window.confirm(`Remove ${label(student)} from the room? Their answers are taken out of the results, and this device cannot join the room again.`)) return;
      button.disabled = true;
      try {
        await api("DELETE", `/api/rooms/${roomId}/students/${student.student_id}`);
      } catch (err) {
        button.disabled = false;
        showError(`Could not remove ${label(student)}: ${err.message}`);
      }
    }
    return {
      element,
      count(joined) { summary.textContent = `Students (${joined})`; },
      render(students) {
        summary.textContent = `Students (${students.length})`;
        empty.hidden = students.length > 0;
        list.replaceChildren(...students.map((s) => {
          const button = el("button", { type: "button", class: "room-remove", "data-student": s.student_id, text: "Remove" });
          button.addEventListener("click", () => remove(s, button));
          return el("li", { "data-student": s.student_id, "data-connected": String(s.connected) },
            el("span", { class: "room-student-name", text: label(s) }),
            el("span", { class: "room-student-status muted", text: s.connected ? (s.following ? "following" : "exploring") : "not connected" }),
            button);
        }));
      },
    };
  }

  // The instructor's polls: ask a ready question or one's own, watch the answers, close, reveal, export.
  // Its own question goes by request, so a refusal is shown in the form (the socket's errors go to the panel's line);
  // `asked` clears the panel's errors once a question is asked.
  function instructorPolls(act, asked) {
    const ready = el("select", { id: "room-ready" }, new Option("Loading ready questions…", ""));
    const askReady = el("button", { type: "button", text: "Ask", "data-room": "ask-ready" });
    const question = el("input", { type: "text", id: "room-own-question", maxlength: config.classroom.poll.question_max_chars });
    const kind = el("select", { id: "room-own-kind" }, new Option("Multiple choice", "choice"), new Option("A number with a unit", "number"));
    const choices = el("textarea", { id: "room-own-choices", rows: 3, placeholder: "one choice per line" });
    const unit = el("input", { type: "text", id: "room-own-unit", maxlength: config.classroom.poll.unit_max_chars, placeholder: "e.g. rad/s" });
    const choicesRow = el("p", {}, el("label", { for: choices.id, text: `Choices (${config.classroom.poll.choices_min} to ${config.classroom.poll.choices_max}, one a line)` }), choices);
    const unitRow = el("p", { hidden: true }, el("label", { for: unit.id, text: "Unit" }), unit);
    // The right answer, if the instructor gives one: Reveal shows it (a ready question's is computed by the scene).
    const answerChoice = el("select", { id: "room-own-answer-choice" }, new Option("No answer given", ""));
    const answerValue = el("input", { type: "number", step: "any", id: "room-own-answer-value", inputmode: "decimal" });
    const answerUnit = el("span", { class: "unit" });
    const answerChoiceRow = el("p", {}, el("label", { for: answerChoice.id, text: "Right answer (optional)" }), answerChoice);
    const answerValueRow = el("p", { hidden: true }, el("label", { for: answerValue.id, text: "Right answer (optional)" }),
      el("span", { class: "room-own-value" }, answerValue, answerUnit));
    const ownError = el("p", { class: "room-own-error error", role: "alert", hidden: true });
    const askOwn = el("button", { type: "submit", text: "Ask", "data-room": "ask-own" });
    const own = el("form", { class: "room-own", novalidate: true }, // its own words for a bad answer, as /join
      el("p", {}, el("label", { for: question.id, text: "Question" }), question),
      el("p", {}, el("label", { for: kind.id, text: "Answer as " }), kind), choicesRow, unitRow, answerChoiceRow, answerValueRow,
      el("p", { class: "room-own-hint muted", text: "Reveal shows the right answer you give here; without one it has nothing to show." }),
      ownError, askOwn);
    const resultsQuestion = el("p", { class: "room-results-question" });
    const count = el("p", { class: "room-results-count", "aria-live": "polite" });
    const bars = el("ol", { class: "room-histogram", "aria-label": "Answers (anonymous counts)" });
    const revealed = el("p", { class: "room-results-revealed", hidden: true });
    const close = el("button", { type: "button", text: "Close", "data-room": "close-poll" });
    const reveal = el("button", { type: "button", text: "Reveal answer", "data-room": "reveal" });
    const names = el("input", { type: "checkbox", id: "room-show-names" });
    const csv = el("a", { class: "room-csv", text: "Download CSV", download: "" });
    const nameList = el("ul", { class: "room-names", hidden: true });
    const results = el("div", { class: "room-results", hidden: true }, resultsQuestion, count, bars, revealed,
      el("div", { class: "room-buttons" }, close, reveal, el("label", { for: names.id }, names, " Show names"), csv), nameList);
    const element = el("section", { class: "room-polls", "aria-label": "Polls" },
      el("h3", { text: "Predict, then observe" }),
      el("p", { class: "room-ready-row" }, el("label", { for: ready.id, text: "Ready question " }), ready, askReady),
      el("details", {}, el("summary", { text: "Ask your own question" }), own), results);
    let poll = null, shownId = null;

    const typedChoices = () => choices.value.split("\n").map((c) => c.trim()).filter(Boolean);
    // The right-answer list follows the choices as they are typed, keeping the one picked while it is still there.
    function listChoices() {
      const picked = answerChoice.selectedIndex > 0 ? answerChoice.options[answerChoice.selectedIndex].text : null;
      const typed = typedChoices();
      answerChoice.replaceChildren(new Option("No answer given", ""), ...typed.map((c, index) => new Option(c, String(index))));
      const again = picked === null ? -1 : typed.indexOf(picked);
      answerChoice.value = again < 0 ? "" : String(again);
    }
    choices.addEventListener("input", listChoices);
    unit.addEventListener("input", () => { answerUnit.textContent = unit.value.trim() ? ` ${unit.value.trim()}` : ""; });
    kind.addEventListener("change", () => {
      const choice = kind.value === "choice";
      choicesRow.hidden = answerChoiceRow.hidden = !choice;
      unitRow.hidden = answerValueRow.hidden = choice;
    });
    askReady.addEventListener("click", () => { if (ready.value) act({ type: "open_poll", ready_id: ready.value }); });
    const showOwnError = (text) => { ownError.textContent = text; ownError.hidden = false; };
    own.addEventListener("submit", async (event) => {
      event.preventDefault();
      ownError.hidden = true;
      const body = { question: question.value.trim(), kind: kind.value };
      if (kind.value === "choice") {
        body.choices = typedChoices();
        if (answerChoice.value !== "") body.answer_choice = Number(answerChoice.value);
      } else {
        body.unit = unit.value.trim();
        const value = Number(answerValue.value);
        if (answerValue.validity.badInput || (answerValue.value !== "" && !Number.isFinite(value))) {
          showOwnError("Right answer: type a number, or leave it empty.");
          return;
        }
        if (answerValue.value !== "") body.answer_value = value;
      }
      askOwn.disabled = true;
      try {
        await api("POST", `/api/rooms/${roomId}/polls`, body); // the poll itself comes back on the room socket
        asked();
      } catch (err) {
        showOwnError(`Not asked: ${err.message}`);
      } finally {
        askOwn.disabled = false;
      }
    });
    close.addEventListener("click", () => poll && act({ type: "update_poll", poll_id: poll.poll_id, open: !poll.open }));
    reveal.addEventListener("click", () => poll && act({ type: "update_poll", poll_id: poll.poll_id, reveal: true }));
    names.addEventListener("change", () => poll && act({ type: "update_poll", poll_id: poll.poll_id, show_names: names.checked }));

    let readyFor;
    async function loadReady(sceneId) {
      if (readyFor === sceneId) return;
      readyFor = sceneId;
      try {
        const list = await api("GET", `/api/rooms/${roomId}/polls/ready`);
        ready.replaceChildren(...(list.length ? list.map((q) => new Option(q.question, q.id)) : [new Option("No ready questions for this chapter", "")]));
        askReady.disabled = !list.length;
      } catch (err) {
        ready.replaceChildren(new Option(`Ready questions unavailable: ${err.message}`, ""));
        askReady.disabled = true;
      }
    }
    function showResults(r) {
      if (!poll || r.poll_id !== poll.poll_id) return;
      results.hidden = false;
      resultsQuestion.textContent = r.question + (r.unit ? ` (${r.unit})` : "");
      count.textContent = `${r.answers} ${r.answers === 1 ? "answer" : "answers"}${r.open ? "" : " · closed"}`;
      count.dataset.answers = String(r.answers);
      const most = Math.max(1, ...r.histogram.map((b) => b.count));
      bars.replaceChildren(...r.histogram.map((bin) => el("li", { "data-count": String(bin.count) },
        el("span", { class: "bar-label", text: bin.lo === null ? bin.label : `${bin.label} ${r.unit}`.trim() }),
        el("span", { class: "bar", style: `width: ${(100 * bin.count) / most}%` }),
        el("span", { class: "bar-count", text: String(bin.count) }))));
      if (!r.histogram.length) bars.append(el("li", { class: "muted", text: "No answers yet" }));
      revealed.hidden = !r.revealed;
      if (r.revealed) revealed.textContent = `Answer: ${r.revealed.text} — ${r.revealed.source}`;
      names.checked = r.show_names;
      nameList.hidden = !r.names;
      nameList.replaceChildren(...(r.names || []).map((n) => el("li", { text: `${n.name}: ${n.answer}` })));
    }
    return {
      element,
      results: showResults,
      clearError() { ownError.hidden = true; },
      state(state) {
        loadReady(state.scene_id);
        if (state.poll && poll && state.poll.poll_id !== poll.poll_id) ownError.hidden = true; // a later poll was asked
        poll = state.poll;
        if (!poll) { results.hidden = true; shownId = null; return; }
        close.textContent = poll.open ? "Close" : "Reopen";
        reveal.disabled = Boolean(poll.revealed);
        csv.href = `/api/rooms/${roomId}/polls/${poll.poll_id}/results.csv`;
        if (shownId !== poll.poll_id) {
          shownId = poll.poll_id;
          api("GET", `/api/rooms/${roomId}/polls/${poll.poll_id}/results`).then(showResults).catch(() => {});
        }
      },
    };
  }
})();
