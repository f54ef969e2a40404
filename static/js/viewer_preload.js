// Lesson page: starts the page's own viewer as the parser reaches it, long before the page's modules have all
// arrived and run (they wait for the whole graph and the end of parsing). The server inlines it right after the
// viewer's frame as an async module (app/web/static_files.py inline_module), which runs at once: a classic inline
// script would first wait for the page's style sheets. It settles the tab's session for this lesson (sessionStorage
// `dynlab.session.<lesson>`: {id, key}, which lesson.js reads and keeps) and loads the viewer with `wait`
// (app/web/pages.py VIEWER_SCRIPT), so viser's client starts at once and opens its websocket only when lesson.js
// says the session exists. Not in a classroom room (?room=…), whose viewer room.js chooses.
(() => {
  const config = JSON.parse(document.getElementById("dynlab-config").textContent);
  if (!config.scene || new URLSearchParams(location.search).has("room")) return;
  const storageKey = `dynlab.session.${config.lesson_id}`;
  const randomId = () => Array.from(crypto.getRandomValues(new Uint8Array(16)), (b) => b.toString(16).padStart(2, "0")).join("");
  let session;
  try {
    session = JSON.parse(sessionStorage.getItem(storageKey)) || {};
    if (!session.id || !session.key) {
      session = { id: randomId(), key: randomId() };
      sessionStorage.setItem(storageKey, JSON.stringify(session));
    }
  } catch (e) {
    return; // no session storage: lesson.js makes the session and loads the viewer itself
  }
  document.getElementById("viewer-wrap").hidden = false;
  document.getElementById("viewer").src = `/viewer/${config.scene.id}/${session.id}/?hideViserLogo&wait`;
})();
