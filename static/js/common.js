// Shared by every page (each page's script imports it): projector (large text) mode, remembered per browser, and
// the keyboard access to boxes that scroll sideways.
import "./scroll_boxes.js";

(function () {
  const root = document.documentElement;
  const apply = (on) => {
    root.classList.toggle("large", on);
    const button = document.getElementById("large-text");
    if (button) button.setAttribute("aria-pressed", String(on));
  };
  apply(localStorage.getItem("dynlab.large") === "1");
  const toggle = () => {
    const on = !root.classList.contains("large");
    localStorage.setItem("dynlab.large", on ? "1" : "0");
    apply(on);
  };
  const button = document.getElementById("large-text");
  if (button) button.addEventListener("click", toggle);
  document.addEventListener("keydown", (e) => {
    if (e.altKey && (e.key === "l" || e.key === "L")) { e.preventDefault(); toggle(); }
  });
})();
