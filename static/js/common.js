// Shared by every page: projector (large text) mode, remembered per browser.
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
  document.addEventListener("DOMContentLoaded", () => {
    apply(localStorage.getItem("dynlab.large") === "1");
    const button = document.getElementById("large-text");
    if (button) button.addEventListener("click", toggle);
    document.querySelectorAll(".math").forEach((el) => {
      if (window.katex) {
        katex.render(el.textContent, el, { displayMode: el.classList.contains("math-display"), throwOnError: false });
      }
    });
  });
  document.addEventListener("keydown", (e) => {
    if (e.altKey && (e.key === "l" || e.key === "L")) { e.preventDefault(); toggle(); }
  });
})();
