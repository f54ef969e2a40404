// The page's configuration: the JSON the server renders into every page (app/web/page_config.py), read once.
// Every page has the values every script shares (the time scales offered, the sockets' reconnect rule); a lesson
// page adds its lesson (its id, the shown scene's schema, its worked examples and derivations).
export const config = Object.freeze(JSON.parse(document.getElementById("dynlab-config").textContent));
