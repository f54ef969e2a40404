// A JSON websocket to the app (a room's socket) that reconnects when it drops, by the one rule in the page's
// configuration (socket_reconnect: the first wait, the factor each further try multiplies it by, the longest wait; the
// wait starts again at the first once a socket opens), and at once when a hidden tab (a phone that slept) is shown.
// `onClose(event)` says whether to try again (false: the room is gone, or the page is done with it).
import { config } from "./config.js";

export function reconnectingSocket(path, { onOpen = () => {}, onMessage = () => {}, onClose = () => true } = {}) {
  const rule = config.socket_reconnect;
  let socket = null, timer = null, waitMs = rule.initial_ms, stopped = false;
  function connect() {
    timer = null;
    const scheme = location.protocol === "https:" ? "wss" : "ws";
    const current = new WebSocket(`${scheme}://${location.host}${path}`);
    socket = current;
    current.addEventListener("open", () => { waitMs = rule.initial_ms; onOpen(); });
    current.addEventListener("message", (event) => {
      let message;
      try { message = JSON.parse(event.data); } catch (e) { return; }
      onMessage(message);
    });
    current.addEventListener("close", (event) => {
      if (stopped || current !== socket) return;
      if (onClose(event) === false) { stopped = true; return; }
      retry();
    });
  }
  function retry() {
    if (timer || stopped) return;
    timer = setTimeout(connect, waitMs);
    waitMs = Math.min(waitMs * rule.factor, rule.cap_ms);
  }
  document.addEventListener("visibilitychange", () => {
    if (!document.hidden && !stopped && socket && socket.readyState === WebSocket.CLOSED) { clearTimeout(timer); connect(); }
  });
  connect();
  return {
    // False when the socket is not open (the message is not sent).
    send(message) {
      if (!socket || socket.readyState !== WebSocket.OPEN) return false;
      socket.send(JSON.stringify(message));
      return true;
    },
    close() {
      stopped = true;
      clearTimeout(timer);
      if (socket) socket.close();
    },
  };
}
