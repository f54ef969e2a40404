// The viewer's own buttons, under the 3D scene on every lesson page with one (animated or not): "Reset view" puts
// the camera back at the scene's start pose and "Save image" saves what the viewer shows as a PNG. viser's control
// panel, which had these, is hidden (app/web/pages.py VIEWER_CSS). R resets the view too: on the page (outside
// text boxes) here, inside the viewer by the script the viewer page carries.
import { lesson } from "./lesson.js";

(function () {
  const frame = document.getElementById("viewer");
  const resetButton = document.getElementById("reset-view");
  const saveButton = document.getElementById("save-image");
  if (!lesson || !frame || !resetButton || !saveButton) return;
  const status = document.createElement("span");
  status.className = "viewer-toolbar-status";
  status.setAttribute("role", "status");
  saveButton.after(status);
  const say = (text) => { status.textContent = text; };

  // The page's own viewer (its session): the server puts every viewer of the session back at the start pose.
  // A room's viewer is the room's: this browser's camera alone goes back, inside the viewer.
  const ownViewer = () => lesson.session && lesson.showsOwnViewer();
  const viewerWindow = () => { try { return frame.contentWindow; } catch (e) { return null; } };
  async function resetView() {
    if (ownViewer()) {
      const done = await lesson.setPlayback({ reset_camera: true }).then(() => true, () => false);
      say(done ? "View reset" : "The view could not be reset: the scene is not connected");
      return;
    }
    const viewer = viewerWindow() && viewerWindow().__viserMutable;
    if (viewer && typeof viewer.resetCameraPose === "function") { viewer.resetCameraPose(true); say("View reset"); }
  }

  // viser draws with preserveDrawingBuffer, so the canvas holds the last frame (labels included) to read back.
  function saveImage() {
    const doc = frame.contentDocument;
    const canvas = doc && doc.querySelector("canvas[data-engine]");
    if (!canvas) { say("No image yet: the scene has not been drawn"); return; }
    canvas.toBlob((blob) => {
      if (!blob) { say("The image could not be read from the viewer"); return; }
      const link = document.createElement("a");
      link.href = URL.createObjectURL(blob);
      link.download = `${lesson.scene ? lesson.scene.id : "scene"}.png`;
      document.body.append(link);
      link.click();
      link.remove();
      setTimeout(() => URL.revokeObjectURL(link.href), 10000);
      say(`Saved ${link.download}`);
    }, "image/png");
  }

  resetButton.addEventListener("click", resetView);
  saveButton.addEventListener("click", saveImage);
  window.addEventListener("message", (event) => {
    if (event.origin === location.origin && event.source === viewerWindow() && event.data && event.data.type === "dynlab:reset-view") resetView();
  });
  document.addEventListener("keydown", (event) => {
    if (event.key !== "r" && event.key !== "R") return;
    if (event.ctrlKey || event.metaKey || event.altKey || event.target.closest("input, select, textarea, [contenteditable]")) return;
    if (!document.getElementById("viewer-wrap").hidden) resetView();
  });
})();
