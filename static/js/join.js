// The join page (/join, /join/<code>): a student types the room's code (or opens the QR code's link, which fills it
// in), may give a name, and joins; keeps the token the room gives in localStorage ("dynlab.room.<room_id>") and goes
// to the room's lesson; before the instructor has opened one it waits on the room socket. The server knows the
// device by a cookie, so joining again from it is the same student. Too many joins at once (429), or a server too
// busy to keep the join just now (503): it waits as the server says (Retry-After) and tries again by itself.
import "./common.js";
import { config } from "./config.js";
import { reconnectingSocket } from "./socket.js";

(function () {
  const CODE_LENGTH = config.classroom.room_code_length;
  const form = document.getElementById("join-form");
  const codeBox = document.getElementById("join-code");
  const nameBox = document.getElementById("join-name");
  const button = document.getElementById("join-button");
  const errorBox = document.getElementById("join-error");
  const statusBox = document.getElementById("join-status");
  const NAME_KEY = "dynlab.name"; // the name this device gave last time, offered again

  // A code as typed or pasted: a whole join link gives its last part; capitals and digits only.
  const normalise = (text) => {
    const link = /\/join\/([^/?#\s]+)/.exec(text);
    return (link ? link[1] : text).toUpperCase().replace(/[^A-Z0-9]/g, "").slice(0, CODE_LENGTH);
  };
  const showError = (message) => {
    errorBox.textContent = message;
    codeBox.setAttribute("aria-invalid", message ? "true" : "false");
    if (message) codeBox.focus();
  };
  const showStatus = (message) => { statusBox.textContent = message; };

  codeBox.addEventListener("input", () => {
    const clean = normalise(codeBox.value);
    if (clean !== codeBox.value) codeBox.value = clean;
    if (errorBox.textContent) showError("");
  });

  const lessonUrl = (state, roomId) => {
    const scene = state.scene_id ? `&scene=${encodeURIComponent(state.scene_id)}` : "";
    return `/lessons/${encodeURIComponent(state.lesson_id)}?room=${encodeURIComponent(roomId)}${scene}`;
  };

  // Why a join failed, in words for a student holding a phone.
  async function refusal(response, code) {
    let detail = "";
    try {
      const body = await response.json();
      detail = Array.isArray(body.detail) ? body.detail.map((d) => d.msg).join("; ") : String(body.detail || "");
    } catch (e) { /* not JSON: the status says enough */ }
    if (response.status === 404) return `No open room has the code ${code}. Check the code on the projector.`;
    if (response.status === 403) return `The instructor removed this device from room ${code}, so it cannot join that room again.`;
    if (response.status === 422) return detail ? `That did not work: ${detail}` : "The code or the name is not valid.";
    return `The server refused to join (${response.status}${detail ? `: ${detail}` : ""}).`;
  }

  let joining = false, retryTimer = null;
  async function join() {
    if (joining || retryTimer) return;
    const code = normalise(codeBox.value);
    codeBox.value = code;
    if (code.length !== CODE_LENGTH) {
      showError(code ? `A room code has ${CODE_LENGTH} characters; this one has ${code.length}.` : "Type the room code first.");
      return;
    }
    showError("");
    joining = true;
    button.disabled = true;
    showStatus(`Joining room ${code}…`);
    try {
      const response = await fetch("/api/rooms/join", {
        method: "POST",
        headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ code, name: nameBox.value.trim() }),
      });
      if (response.status === 429 || response.status === 503) { // many joining at once, or the server busy: wait
        const waitS = Math.max(1, Math.min(60, Number(response.headers.get("Retry-After")) || 5)); // as it says
        showStatus(response.status === 429 ? `Many people are joining right now. Trying again in ${waitS} s…`
          : `The server is busy. Trying again in ${waitS} s…`);
        retryTimer = setTimeout(() => { retryTimer = null; join(); }, waitS * 1000);
        return;
      }
      if (!response.ok) {
        showStatus("");
        showError(await refusal(response, code));
        return;
      }
      const joined = await response.json();
      localStorage.setItem(`dynlab.room.${joined.room_id}`, JSON.stringify({ student_token: joined.student_token }));
      if (nameBox.value.trim()) localStorage.setItem(NAME_KEY, nameBox.value.trim());
      if (joined.state.lesson_id) {
        showStatus(`Joined room ${code}: opening the lesson…`);
        location.assign(lessonUrl(joined.state, joined.room_id));
      } else {
        form.hidden = true;
        wait(joined.room_id, joined.student_token, code);
      }
    } catch (e) {
      showStatus("");
      showError("Could not reach the server. Check that you are on the classroom's network and try again.");
    } finally {
      joining = false;
      button.disabled = Boolean(retryTimer);
    }
  }

  // Joined, no lesson yet: the room socket says when the instructor opens one (reconnecting if it drops).
  function wait(roomId, token, code) {
    const waiting = `Joined room ${code} — waiting for the instructor to open a lesson`;
    let done = false;
    const stop = (message) => { done = true; showStatus(message); };
    showStatus(waiting);
    const socket = reconnectingSocket(`/api/rooms/${encodeURIComponent(roomId)}/socket`, {
      onOpen() {
        showStatus(waiting);
        socket.send({ type: "hello", student_token: token, following: true });
      },
      onMessage(message) {
        if (message.type === "state" && message.state && message.state.lesson_id) {
          stop("The instructor opened a lesson: opening it…");
          socket.close();
          location.assign(lessonUrl(message.state, roomId));
        } else if (message.type === "removed") {
          stop(`The instructor removed you from room ${code}.`);
          localStorage.removeItem(`dynlab.room.${roomId}`);
        } else if (message.type === "closed") {
          stop(`Room ${code} has been closed by the instructor.`);
          socket.close();
        } else if (message.type === "error" && message.status === 403) {
          stop("");
          socket.close();
          localStorage.removeItem(`dynlab.room.${roomId}`);
          form.hidden = false;
          showError("The room no longer knows this device: join again with the code.");
        }
      },
      onClose(event) {
        if (done) return false;
        if (event.code === 1008) { stop(`Room ${code} is closed.`); return false; }  // the room is gone
        showStatus(`Reconnecting to room ${code}…`);
        return true;
      },
    });
  }

  form.addEventListener("submit", (event) => {
    event.preventDefault();
    join();
  });
  // The name this device gave before; the QR code's link (/join/<code>) has the code already: the name is next.
  nameBox.value = localStorage.getItem(NAME_KEY) || "";
  if (codeBox.dataset.fromUrl) nameBox.focus();
  else codeBox.focus();
})();
