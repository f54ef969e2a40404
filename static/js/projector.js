// The projector view (/rooms/<room_id>/projector, instructor only): the room's scene large and, in type readable from
// the back row, how to join, the readout, the play state and the current poll's anonymous histogram. It has no
// controls: it reads the room socket (an instructor socket, opened with the instructor's cookie, so it also gets
// poll results) and reconnects when the socket drops.
import "./common.js";
import { config } from "./config.js";
import { formatNumber } from "./format.js";
import { reconnectingSocket } from "./socket.js";

(function () {
  const root = document.getElementById("projector");
  const roomId = root.dataset.roomId;
  const $ = (id) => document.getElementById(id);
  const viewer = $("projector-viewer");
  const MAX_QUANTITIES = 6;

  // ---- numbers: about four significant figures, an exponent only when very large or small ----------
  const fmt = (v) => (typeof v === "number" && Number.isFinite(v) ? formatNumber(v, { digits: 4 }) : "—");
  // The join address as a student types it: without its code (they type that in the box) or an "http://".
  const joinAddress = (state) => {
    const url = state.join_url.endsWith(`/${state.code}`) ? state.join_url.slice(0, -state.code.length - 1) : state.join_url;
    return url.replace(/^http:\/\//, "");
  };

  // ---- the room's state ----------------------------------------------------------------------
  let state = null;
  let results = null;
  function renderState(next) {
    const sceneChanged = state !== null && next.scene_id !== state.scene_id;
    state = next;
    $("projector-code").textContent = state.code;
    $("projector-url").textContent = joinAddress(state);
    const play = $("projector-play");
    play.textContent = state.playing ? `▶ ${fmt(state.time_scale)}×` : "⏸ paused";
    play.dataset.playing = String(state.playing);
    const { connected, following } = state.students;
    const students = `${connected} student${connected === 1 ? "" : "s"} connected`;
    $("projector-students").textContent = state.mode === "explore"
      ? `${students} · exploring on their own` : `${students} · ${following} following`;
    if (sceneChanged) {
      // A new scene is a new stage: the viewer reconnects to its stream, and the old readout no longer applies.
      viewer.src = `/room-viewer/${roomId}/?hideViserLogo`;
      renderReadout(null);
    }
    renderPoll();
  }

  // ---- the readout (about twice a second) ----------------------------------------------------------
  const TIME_QUANTITY = "t_s";
  function renderReadout(data) {
    const box = $("projector-readout");
    const list = $("projector-quantities");
    const all = (data && data.readout && data.readout.quantities) || [];
    // Time goes beside the play state (integrated scenes send it as data.t_s, others as their t_s quantity).
    const timeQuantity = all.find((q) => q.name === TIME_QUANTITY);
    const t = data && typeof data.t_s === "number" ? data.t_s : timeQuantity && timeQuantity.value;
    $("projector-time").textContent = typeof t === "number" ? `t = ${t.toFixed(1)} s` : "";
    const quantities = all.filter((q) => q.name !== TIME_QUANTITY).slice(0, MAX_QUANTITIES);
    const problem = data && data.status ? String(data.status) : "";
    box.hidden = quantities.length === 0 && !problem;
    const names = (problem ? "!|" : "") + quantities.map((q) => q.name).join("|");
    if (list.dataset.names !== names) {
      const rows = quantities.map(() => {
        const row = document.createElement("div");
        row.className = "projector-quantity";
        row.innerHTML = "<dt></dt><dd><span class='value'></span> <span class='unit'></span></dd>";
        return row;
      });
      if (problem) {
        // A simulation that stopped says so first, above the numbers it can no longer vouch for.
        const row = document.createElement("div");
        row.className = "projector-quantity projector-problem";
        row.innerHTML = "<dt>Simulation</dt><dd></dd>";
        rows.unshift(row);
      }
      list.replaceChildren(...rows);
      list.dataset.names = names;
    }
    const offset = problem ? 1 : 0;
    if (problem) list.firstElementChild.querySelector("dd").textContent = problem;
    quantities.forEach((q, i) => {
      const row = list.children[i + offset];
      row.dataset.quantity = q.name;
      row.querySelector("dt").textContent = q.label;
      const hasNumber = typeof q.value === "number";
      // A word, or no value at this instant: the text says which (e.g. "undefined (gimbal lock)").
      row.querySelector(".value").textContent = hasNumber ? (q.text ? `${fmt(q.value)} (${q.text})` : fmt(q.value)) : (q.text || "—");
      row.querySelector(".value").classList.toggle("word", !hasNumber);
      row.querySelector(".unit").textContent = hasNumber || q.text_in_unit ? (q.unit || "") : "";
    });
    fitRows(box, list);
  }
  // Show whole rows only: the ones that do not fit the panel's height are left out (never cut in half).
  function fitRows(box, list) {
    const rows = [...list.children];
    rows.forEach((row) => { row.hidden = false; });
    const bottom = box.getBoundingClientRect().bottom - parseFloat(getComputedStyle(box).paddingBottom);
    rows.forEach((row) => { row.hidden = row.getBoundingClientRect().bottom > bottom + 1; });
  }
  window.addEventListener("resize", () => fitRows($("projector-readout"), $("projector-quantities")));

  // ---- the current poll: question, anonymous histogram, the revealed answer ---------------------------
  let fetching = null;
  function fetchResults(pollId) {
    if (fetching === pollId) return;
    fetching = pollId;
    fetch(`/api/rooms/${roomId}/polls/${encodeURIComponent(pollId)}/results`)
      .then((response) => (response.ok ? response.json() : null))
      .then((body) => { if (body && state && state.poll && body.poll_id === state.poll.poll_id) { results = body; renderPoll(); } })
      .catch(() => { /* the next state or results message brings them */ })
      .finally(() => { fetching = null; });
  }

  function renderPoll() {
    const poll = state && state.poll;
    const box = $("projector-poll");
    root.classList.toggle("has-poll", Boolean(poll));
    box.hidden = !poll;
    if (!poll) return;
    box.dataset.pollId = poll.poll_id;
    $("projector-question").textContent = poll.question + (poll.kind === "number" && poll.unit ? ` (${poll.unit})` : "");
    const current = results && results.poll_id === poll.poll_id ? results : null;
    // The socket sends results on each answer; a poll opened before this page connected needs them fetched once.
    if (!current || poll.answers > current.answers) fetchResults(poll.poll_id);
    const answers = current ? Math.max(current.answers, poll.answers) : poll.answers;
    $("projector-answers").textContent = String(answers);
    $("projector-answers").dataset.count = String(answers);
    $("projector-answers-word").textContent = answers === 1 ? "answer" : "answers";
    // Once revealed, the answer line below says so; before, whether answers are still taken.
    $("projector-poll-open").textContent = poll.revealed ? "" : poll.open ? "open for answers" : "closed";
    renderHistogram(current ? current.histogram : poll.choices.map((label) => ({ label, count: 0, lo: null, hi: null })), poll);
    const revealed = $("projector-revealed");
    revealed.hidden = !poll.revealed;
    if (poll.revealed) {
      revealed.replaceChildren();
      const answer = document.createElement("strong");
      answer.textContent = `Answer: ${poll.revealed.text}`;
      const source = document.createElement("span");
      source.className = "projector-source";
      source.textContent = ` — ${poll.revealed.source}`;
      revealed.append(answer, source);
    }
  }

  // Bars labelled by choice or bin; counts only (never names, even when the instructor turned names on).
  function renderHistogram(bins, poll) {
    const list = $("projector-histogram");
    const most = Math.max(1, ...bins.map((b) => b.count));
    const revealed = poll.revealed;
    list.replaceChildren(...bins.map((bin, i) => {
      const item = document.createElement("li");
      const isAnswer = revealed && (revealed.choice === i && poll.kind === "choice"
        || poll.kind === "number" && typeof revealed.value === "number" && bin.lo !== null
          && revealed.value >= bin.lo && (revealed.value < bin.hi || i === bins.length - 1));
      item.className = isAnswer ? "is-answer" : "";
      item.dataset.count = String(bin.count);
      item.style.setProperty("--share", String(bin.count / most));
      item.innerHTML = "<span class='count'></span><span class='bar'></span><span class='label'></span>";
      item.querySelector(".count").textContent = String(bin.count);
      // A number poll's bin as "30–35" (shorter than the server's "30 to 35", so it fits under a narrow bar).
      const label = typeof bin.lo === "number" && typeof bin.hi === "number" && bin.lo !== bin.hi ? `${fmt(bin.lo)}–${fmt(bin.hi)}` : bin.label;
      item.querySelector(".label").textContent = label;
      item.setAttribute("aria-label", `${bin.label}: ${bin.count}`);
      return item;
    }));
    list.hidden = bins.length === 0;
  }

  // ---- the room socket, reconnecting by the page's one rule ----------------------------------------------
  const connection = $("projector-connection");
  let closed = false;
  let dropped = false;
  let ping = null;
  function connect() {
    const socket = reconnectingSocket(`/api/rooms/${roomId}/socket`, {
      onOpen() {
        connection.textContent = "";
        if (dropped) viewer.src = `/room-viewer/${roomId}/?hideViserLogo`;  // the server may have restarted the stream
        dropped = false;
        ping = setInterval(() => socket.send({ type: "ping" }), config.classroom.socket_ping_interval_ms);
      },
      onMessage(message) {
        if (message.type === "state") renderState(message.state);
        else if (message.type === "readout" && state && message.scene_id === state.scene_id) renderReadout(message.data);
        else if (message.type === "results") { results = message.results; renderPoll(); }
        else if (message.type === "closed") { closed = true; connection.textContent = "The instructor closed this room."; }
      },
      onClose(event) {
        clearInterval(ping);
        if (closed || event.code === 1008) {
          connection.textContent = "This room is closed.";
          return false;
        }
        dropped = true;
        connection.textContent = "Connection lost: reconnecting…";
        return true;
      },
    });
  }

  // ---- hide the join code (button or the J key) -------------------------------------------------------
  const hideButton = $("projector-hide-code");
  const setHidden = (hidden) => {
    root.classList.toggle("code-hidden", hidden);
    $("projector-join").hidden = hidden;
    hideButton.setAttribute("aria-pressed", String(hidden));
    hideButton.textContent = hidden ? "Show join code (J)" : "Hide join code (J)";
  };
  hideButton.addEventListener("click", () => setHidden(!root.classList.contains("code-hidden")));
  document.addEventListener("keydown", (event) => {
    if ((event.key === "j" || event.key === "J") && !event.altKey && !event.ctrlKey && !event.metaKey) {
      setHidden(!root.classList.contains("code-hidden"));
    }
  });

  connect();
})();
